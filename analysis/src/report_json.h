// The report.json form of each analysis type, in one place: COSIM_JSON_FIELDS where the keys
// are the field names (in this order), a small to_json where report.json names a field
// otherwise. Private to cosim_analysis; found by argument-dependent lookup (`Json j = stats;`).
#pragma once

#include <nlohmann/json.hpp>

#include "cosim/analysis/coating_statistics.h"
#include "cosim/analysis/extrapolation.h"
#include "cosim/analysis/files.h"
#include "cosim/analysis/histogram.h"
#include "cosim/analysis/mass_balance.h"
#include "cosim/analysis/mixing_verdict.h"
#include "cosim/analysis/normality_test.h"
#include "cosim/analysis/parcel_places.h"
#include "cosim/analysis/report.h"
#include "cosim/analysis/runs_test.h"
#include "cosim/analysis/window_study.h"
#include "cosim/analysis/zone_pass_statistics.h"

// nlohmann's NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE for our Json (an ordered_json: the keys stay in
// the order given), serialising only: report.json is written, never read back into these types.
#define COSIM_JSON_FIELDS(Type, ...)                                         \
  inline void to_json(Json& nlohmann_json_j, const Type& nlohmann_json_t) {  \
    NLOHMANN_JSON_EXPAND(NLOHMANN_JSON_PASTE(NLOHMANN_JSON_TO, __VA_ARGS__)) \
  }

namespace cosim::analysis {

inline void to_json(Json& j, const CoatingStatistics& s) {
  j = {{"time", s.time},
       {"count", s.count},
       {"mean", s.mean},
       {"std", s.std_dev},
       {"variance", s.variance},
       {"cv", s.cv},
       {"min", s.min},
       {"max", s.max},
       {"total", s.total},
       {"uncoated_threshold", s.uncoated_threshold},
       {"uncoated_share", s.uncoated_share},
       {"skewness", s.skewness},
       {"excess_kurtosis", s.excess_kurtosis}};
}

COSIM_JSON_FIELDS(RunsTest, valid, positive, negative, runs, expected_runs, z, p_too_few)
COSIM_JSON_FIELDS(NormalityTrend, measured, from, to, snapshots, skewness_decay, kurtosis_decay, at,
                  projected_skewness, projected_excess_kurtosis)
COSIM_JSON_FIELDS(NormalityTest, valid, problem, n, skewness, kurtosis, z_skewness, z_kurtosis, k2,
                  p_value)
COSIM_JSON_FIELDS(CvPrediction, tau, cv, cv_low, cv_high, band)
COSIM_JSON_FIELDS(PredictedDistribution, tau, mean, sigma, cv, sigma_low, sigma_high)
COSIM_JSON_FIELDS(PredictionCheckPoint, time, simulated_mean, predicted_mean, mean_error,
                  simulated_std, predicted_std, std_error, simulated_cv, predicted_cv, cv_error)
COSIM_JSON_FIELDS(PredictionCheck, points, max_abs_mean_error, max_abs_std_error, max_abs_cv_error)
COSIM_JSON_FIELDS(WindowStudyPoint, t_end, wall_seconds, ok, a1, a1_se, a2, a2_se, cv_horizon,
                  cv_run_end, cv_run_end_error)
COSIM_JSON_FIELDS(WindowStudy, horizon, run_end, simulated_cv_run_end, points)

// The precursor balance; `removed` and `pending` are null when the time series has no
// precursor_removed column.
inline void to_json(Json& j, const MassBalance& b) {
  j = {{"precursor_in", b.precursor_in},
       {"precursor_out", b.precursor_out},
       {"held_start", b.held_start},
       {"held_end", b.held_end},
       {"held_change", b.held_change},
       {"expected_coating", b.expected_coating},
       {"coated_start", b.coated_start},
       {"coated_end", b.coated_end},
       {"obtained_coating", b.obtained_coating},
       {"error", b.error},
       {"error_percent", b.error_percent},
       {"initial_state", b.initial_state},
       {"obtained_source", b.obtained_source},
       {"removed", b.has_removed ? Json(b.removed) : Json()},
       {"pending", b.has_removed ? Json(b.pending) : Json()}};
}

// A histogram at a requested time: the snapshot's statistics with the bins
inline void to_json(Json& j, const HistogramAt& h) {
  j = h.stats;
  j["requested"] = h.requested;
  j["edges"] = h.histogram.edges;
  j["counts"] = h.histogram.counts;
  j["rule"] = h.histogram.rule;
}

// A spread of values with its histogram (zone passes: passes per parcel, cycle times, ...)
inline void to_json(Json& j, const Spread& s) {
  j = {{"n", s.n},
       {"mean", s.mean},
       {"sd", s.sd},
       {"min", s.min},
       {"p10", s.p10},
       {"p25", s.p25},
       {"p50", s.p50},
       {"p75", s.p75},
       {"p90", s.p90},
       {"max", s.max},
       {"edges", s.histogram.edges},
       {"counts", s.histogram.counts}};
}

COSIM_JSON_FIELDS(MannPrediction, t, mean, sd, cv, cv_with_pass_spread, passes_mean)

inline void to_json(Json& j, const PlaceOfGroup& p) {
  j = {{"parcels", p.parcels},
       {"mean_height_m", p.mean_height},
       {"mean_radius_m", p.mean_radius},
       {"start_height_m", p.start_height},
       {"start_radius_m", p.start_radius}};
}

}  // namespace cosim::analysis

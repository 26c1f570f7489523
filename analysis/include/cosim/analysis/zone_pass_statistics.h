// What the passes through the coating zone (zone_passes.csv) say about the bed, and what coating
// distribution they predict by Mann's cycle-time analysis (docs/analysis.md section 10):
//   - per parcel: number of passes, time in the zone; the share that never entered;
//   - per pass: time in the zone, coating; between passes: the cycle time (entry to next entry);
//   - Mann: a parcel that enters every T (mean mu_T, sd sigma_T) and takes W0 per pass has after
//     coating time t the mean mu = W0 t / mu_T and the variance sigma^2 = W0^2 sigma_T^2 t /
//     mu_T^3, so CV = sigma_T / sqrt(mu_T t); with a spread sigma_W of the coating per pass the
//     variance gains (t / mu_T) sigma_W^2.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "cosim/analysis/histogram.h"
#include "cosim/analysis/zone_pass_file.h"

namespace cosim::analysis {

// A distribution summarised: count, mean, standard deviation, extremes, percentiles (linear
// interpolation, numpy's default) and a histogram (histogram.h rule).
struct Spread {
  std::size_t n = 0;
  double mean = std::numeric_limits<double>::quiet_NaN();
  double sd = std::numeric_limits<double>::quiet_NaN();
  double min = std::numeric_limits<double>::quiet_NaN();
  double p10 = std::numeric_limits<double>::quiet_NaN();
  double p25 = std::numeric_limits<double>::quiet_NaN();
  double p50 = std::numeric_limits<double>::quiet_NaN();
  double p75 = std::numeric_limits<double>::quiet_NaN();
  double p90 = std::numeric_limits<double>::quiet_NaN();
  double max = std::numeric_limits<double>::quiet_NaN();
  Histogram histogram;
};

// sample = true: sd with n - 1 (a sample of a process: cycles, passes); false: with n (the whole
// bed: passes per parcel). NaN moments for n = 0; sd NaN for a sample of one.
Spread spreadOf(const std::vector<double>& values, bool sample);

// Mann's prediction at coating time t [s].
struct MannPrediction {
  double t = 0;                    // [s] since the coating started
  double mean = 0;                 // [kg] W0 t / mu_T
  double sd = 0;                   // [kg] W0 sigma_T sqrt(t / mu_T^3)
  double cv = 0;                   // sigma_T / sqrt(mu_T t)
  double passes_mean = 0;          // t / mu_T
  double cv_with_pass_spread = 0;  // sqrt((sigma_T^2 / mu_T^2 + sigma_W^2 / W0^2) mu_T / t)
};
MannPrediction mannPrediction(double w0, double mu_t, double sigma_t, double sigma_w, double t);

struct ZonePassStatistics {
  double start = 0, end = 0;        // [s] the coating time the passes cover
  std::size_t parcels = 0;          // parcels of the bed (the ids given)
  std::size_t passes = 0;           // every pass, censored ones included
  std::size_t complete_passes = 0;  // entry and exit observed
  std::size_t entries = 0;          // passes whose entry was observed (not at_start)
  std::size_t never_entered = 0;    // parcels with no pass at all
  double never_entered_share = std::numeric_limits<double>::quiet_NaN();
  std::size_t at_most_one_entry = 0;  // parcels with no observed cycle
  Spread passes_per_parcel;           // every parcel, zeros included (population sd)
  double passes_cv = std::numeric_limits<double>::quiet_NaN();  // sd / mean of passes per parcel
  Spread time_in_zone_per_parcel;                               // [s]
  double time_in_zone_share = std::numeric_limits<double>::quiet_NaN();  // of parcel-seconds
  // [kg/s] what a parcel takes up per second while in the zone (coating in passes / time in the
  // zone): the zone's driving force. Coating per second = parcels x time_in_zone_share x this.
  double uptake_rate_in_zone = std::numeric_limits<double>::quiet_NaN();
  Spread pass_duration;     // [s] complete passes
  Spread cycle_time;        // [s] entry to next entry of the same parcel, both observed
  Spread coating_per_pass;  // [kg] complete passes
  // Mean time between entries from the entry rate, (parcels x coating time) / entries: counts the
  // parcels that never entered, unlike the observed cycles, which a short run cuts at its length.
  double cycle_time_from_rate = std::numeric_limits<double>::quiet_NaN();
  double coating_in_passes = 0;                          // [kg] sum over every pass
  double w0 = std::numeric_limits<double>::quiet_NaN();  // [kg] coating_in_passes / passes
  bool prediction_ok = false;  // at least 2 cycles: mu_T and sigma_T exist
  std::string prediction_problem;
  // Per parcel (the ids given, in that order): passes, seconds in the zone, coating of its passes.
  std::vector<std::int64_t> ids;
  std::vector<std::size_t> parcel_passes;
  std::vector<double> parcel_time_in_zone;
  std::vector<double> parcel_coating;
};

// `parcel_ids`: every parcel of the bed (those with no pass count as never entered); `start`,
// `end`: the coating time covered. Passes of parcels not among the ids are counted as passes.
ZonePassStatistics zonePassStatistics(const std::vector<ZonePass>& passes,
                                      const std::vector<std::int64_t>& parcel_ids, double start,
                                      double end);

// Mann's prediction with the run's statistics (mu_T, sigma_T from the cycles, W0, sigma_W from
// coating_per_pass.sd or 0); NaN fields when !prediction_ok.
MannPrediction predictFromPasses(const ZonePassStatistics& s, double t);

}  // namespace cosim::analysis

// The long-time model held against the rest of its own run: fitted on the record up to a time T,
// it carries the parcels on from T, and the run's own snapshots after T say how far its answer is
// from the CFD-DEM's (mean, CV, never-coated share at each check time; the distribution of the
// parcels' coating at the last one). `cosim batch RUN --to T` prints it; docs/physics.md,
// "Coating over a whole batch", says how to read it.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "cosim/analysis/files.h"
#include "cosim/analysis/long_time.h"

namespace cosim::analysis {

class ParticleFile;

// The coating of every parcel in one recorded snapshot.
struct RecordedCoating {
  double time = 0;  // [s]
  std::vector<std::int64_t> ids;
  std::vector<double> coating;  // [kg], in the order of ids
};

// The snapshots of `file` at `times` (each the snapshot at or just before it, within 1e-6 s of
// the record's grid). Throws naming the file when a time lies before the first snapshot.
std::vector<RecordedCoating> readRecordedCoating(const ParticleFile& file,
                                                 const std::vector<double>& times);

struct LongTimeCheckRow {
  double time = 0;  // [s]
  LongTimePoint predicted, recorded;
  double mean_error = 0;    // predicted / recorded - 1
  double cv_error = 0;      // predicted / recorded - 1
  double never_points = 0;  // predicted - recorded never-coated share, in percentage points
};

struct LongTimeCheck {
  std::vector<LongTimeCheckRow> rows;
  std::size_t parcels = 0;  // compared at the last check time: in the model and in the record
  // The parcels' coating at the last check time, predicted against recorded: the two-sample
  // Kolmogorov-Smirnov distance (largest gap between the two cumulative distributions) and the
  // distance two independent samples of these sizes exceed one time in twenty.
  double ks_distance = 0;
  double ks_critical = 0;
  std::vector<double> predicted_deciles, recorded_deciles;  // 10 %, 20 %, ... 90 % [kg]
};

// batch.json's and report.json's form: rows (time_s, model and run: mean_kg, cv,
// never_coated_share; mean_error, cv_error, never_coated_points), parcels, ks_distance,
// ks_critical_5pct, model_deciles_kg, run_deciles_kg.
void to_json(Json& j, const LongTimeCheck& c);

// Two-sample Kolmogorov-Smirnov distance of `a` and `b` (neither empty).
double ksDistance(std::vector<double> a, std::vector<double> b);

// Carries the model's parcels (fitted on `db`) on to each recorded time after the record's end
// and compares. The recorded side takes the parcels the model carries (by id): a parcel the
// record has and the model does not (inserted later) is left out of both.
LongTimeCheck checkLongTime(const LongTimeModel& model, const CoatingDatabase& db,
                            const std::vector<RecordedCoating>& record, std::uint64_t seed = 1);

// The model held against parcels it was not fitted on: the record's parcels split in two
// (alternately, in the record's order); each half's model, fitted on the whole record with a
// step of `lag` intervals, carries the other half from the record's first snapshot, and the two
// predictions together are held against the record at a quarter, half, three quarters of the
// way and at its end. Where the half check below looks half the record ahead, this one looks
// all of it ahead, so a model that brings the parcels to the zone too soon (a step shorter than
// the bed's memory) shows it over twice the time. nullopt when the record holds fewer than two
// of the model's steps.
std::optional<LongTimeCheck> checkOnHeldOutParcels(const CoatingDatabase& db, std::size_t lag,
                                                   std::uint64_t seed = 1);

// The model fitted on the record [from, until] (until < 0: to the end) cut at its middle
// snapshot, held against the run's snapshots of the second half (at a quarter, half, three
// quarters of the way and at the end). nullopt for a record of fewer than 6 snapshots.
struct HalfCheck {
  double record_to = 0;  // [s] the first half's end
  double step = 0;       // [s] the model's step
  LongTimeCheck check;
  // The first half's model settles to a coating rate off the record's by more than
  // kSettledRateTolerance (compartments it enters and never leaves, say): it may hold the next
  // seconds and still carry a batch wrong.
  bool settles_off = false;
  double wall_seconds = 0;
};
// `lag`: the model's step in the record's intervals (fitLongTimeModel); the check times are
// whole steps after the first half's end. nullopt also when either half holds fewer than two
// steps.
std::optional<HalfCheck> checkOnSecondHalf(const ParticleFile& file, double from, double until,
                                           const Compartments& grid, std::size_t lag = 1,
                                           std::uint64_t seed = 1);

// The compartments the record itself holds best: each candidate checked on the record's second
// half (checkOnSecondHalf) and on held-out parcels over the whole record
// (checkOnHeldOutParcels); the chosen one has the least trialDistance among those whose
// first-half model settles to the record's coating rate (all, when none does).
// Candidates the record cannot check (too short) are left out; none checkable: `chosen` is the
// first candidate and `trials` empty.
// Each grid is tried with each of the model's steps in `steps` (seconds, each rounded to a whole
// number of the record's intervals, at least one; 0: the record's interval).
struct GridTrial {
  Compartments grid;
  std::size_t lag = 1;  // the model's step, in the record's intervals
  HalfCheck half;
  std::optional<LongTimeCheck> held_out;  // checkOnHeldOutParcels on the whole record
};
struct GridChoice {
  std::vector<GridTrial> trials;
  Compartments chosen;
  std::size_t lag = 1;
};
// How far a trial's model is from the record, in units of the 5 % distance of two independent
// samples: the larger of the two checks' Kolmogorov-Smirnov distances (the second half, the
// held-out parcels) each over its 5 % distance. The choice takes the least.
double trialDistance(const GridTrial& t);
// rings, layers, step_s, record_to_s, settles_off, wall_s, the check's fields (to_json above),
// held_out_parcels (the same fields) and distance (trialDistance)
void to_json(Json& j, const GridTrial& t);
inline const std::vector<Compartments> kCandidateGrids = {
    {6, 8, 0, 0}, {12, 16, 0, 0}, {16, 24, 0, 0}, {24, 32, 0, 0}};
inline const std::vector<double> kCandidateSteps = {0, 0.2, 0.5, 1.0};  // [s]
// The steps in `steps` [s] as whole numbers of `interval`, each at least 1, without repeats.
std::vector<std::size_t> candidateLags(double interval, const std::vector<double>& steps);
GridChoice chooseCompartments(const ParticleFile& file, double from, double until,
                              const std::vector<Compartments>& candidates = kCandidateGrids,
                              const std::vector<double>& steps = kCandidateSteps,
                              std::uint64_t seed = 1);

}  // namespace cosim::analysis

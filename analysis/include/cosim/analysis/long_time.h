// The whole batch from seconds of CFD-DEM: a Markov model of the parcels between compartments of
// the bed, with the coating each one gained on each recorded move (docs/physics.md, "Coating over
// a whole batch"). From the particle snapshots of a run (the database): where each parcel is at
// each snapshot (a compartment: a ring about the vessel's axis and a layer) and the coating it
// gained until the next. The model carries every parcel on from where the record ends, one
// snapshot interval at a time: its next compartment drawn with the recorded transition
// probabilities, its coating gain drawn from the gains recorded for that same move (from, to), so
// it never gives a parcel a pass the record has no example of. It says when the record is too
// short for the bed's slow motion: a mixing time longer than the record, compartments the parcels
// were seen in but never seen to leave.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace cosim::analysis {

class ParticleFile;

// Rings about the vertical axis x = y = 0 (equal areas out to r_max) times layers (equal heights
// up to z_max; parcels above it in the top layer). r_max and z_max: set from the record when 0.
struct Compartments {
  int rings = 6;
  int layers = 8;
  double r_max = 0;  // [m]
  double z_max = 0;  // [m]
  int count() const { return rings * layers; }
  int of(double x, double y, double z) const;
};

// The record: per parcel present in every snapshot used, its compartment and coating at each.
struct CoatingDatabase {
  double interval = 0;        // [s] between two snapshots
  std::vector<double> times;  // [s] of the snapshots used
  Compartments grid;
  std::vector<std::int64_t> ids;
  std::vector<std::vector<int>> state;       // [snapshot][parcel]
  std::vector<std::vector<double>> coating;  // [snapshot][parcel] [kg]
  std::size_t left_out = 0;  // parcels not in every snapshot (inserted or deleted): not modelled
  std::vector<double>
      off_interval;  // [s] snapshots set aside: between two of the interval (a stop's)
};

// The snapshots a record uses (below): their indices in the file, times and interval, and the
// ones set aside. Reads no field.
struct RecordGrid {
  double interval = 0;  // [s]
  std::vector<std::size_t> use;
  std::vector<double> times, off_interval;  // [s]
};
RecordGrid recordGrid(const ParticleFile& file, double from, double until);

// Snapshots with from <= t <= until (until < 0: to the end) at a constant interval (the most
// frequent spacing); a snapshot between two of them (written where a run was stopped) is set
// aside and listed in off_interval. Throws naming the file when fewer than 3 remain, when one is
// missing from the interval's sequence, or when a field is missing.
CoatingDatabase readCoatingDatabase(const ParticleFile& file, double from, double until,
                                    Compartments grid);

struct LongTimeModel {
  int states = 0;
  std::size_t lag = 1;                     // the record's intervals per step of the model
  double interval = 0;                     // [s] a step of the model: lag x the record's interval
  double record_seconds = 0;               // [s] the database's length
  std::vector<double> P;                   // [from * states + to], rows sum to 1 (or 0: never seen)
  std::vector<std::vector<double>> gains;  // [from * states + to]: the coating gains recorded
  std::vector<std::size_t> departures;     // steps recorded starting in each state
  // Mean coating gained over a step from each state (a state that goes by single intervals: over
  // `lag` of them, by the single-interval chain).
  std::vector<double> expected_gain;
  // With lag > 1: the single-interval chain too (P1, gains1, departures1), and the states whose
  // moves over a step the record holds too few of (fewer than min_departures): a parcel there
  // goes by `lag` single intervals instead (the record's last steps hold no move of a step's
  // length from where a parcel was near the record's end).
  std::vector<char> by_single;
  std::vector<double> P1;
  std::vector<std::vector<double>> gains1;
  std::vector<std::size_t> departures1;
  std::vector<std::size_t> occupied_at_end;  // parcels in each state at the record's end
  // Moves over a step left out of the chain because they end in a compartment the record never
  // shows a parcel leaving (seen only at its last snapshots): kept, each would hold the parcels
  // the chain sends there for the whole batch.
  std::size_t dead_end_moves = 0;
  // The mixing time: intervals until the distribution started from any visited state is within
  // 0.25 (total variation) of the stationary one, in seconds; infinite when it never is.
  double mixing_seconds = 0;
  // Expected time from each state until a parcel first enters a compartment whose moves gained
  // coating (infinite: it cannot reach one), and its largest over the states parcels occupy at
  // the record's end: the bed's longest coating cycle, which the record must hold.
  std::vector<double> zone_return_seconds;
  double longest_wait_seconds = 0;
  // Coating per parcel and interval [kg], on average: the record's over its second half, and the
  // chain's once settled from the record's last occupancy; a warning when they differ by more
  // than kSettledRateTolerance.
  double record_gain_per_interval = 0;
  double settled_gain_per_interval = 0;
  std::vector<std::string> warnings;  // plain-language: the record is too short, and why
};
inline constexpr double kSettledRateTolerance = 0.05;

// The model steps `lag` of the record's intervals at a time: its moves and gains are those the
// record shows over that time, counted from every snapshot (overlapping). A step longer than the
// record's interval keeps what a parcel does within it (a pass through the zone and back, a
// stay in a dead zone) as the record shows it, where a chain of short steps forgets at every
// step where a parcel came from and mixes the bed faster than it mixes (docs/physics.md 5b).
// `min_departures`: a state the parcels occupy with fewer recorded departures than this is
// named in the warnings (its rates rest on too few moves).
LongTimeModel fitLongTimeModel(const CoatingDatabase& db, std::size_t lag = 1,
                               std::size_t min_departures = 20);

struct LongTimePoint {
  double time = 0;  // [s] since the start of the run
  double mean = 0;  // [kg] per parcel
  double cv = 0;
  double never_coated_share = 0;  // parcels with no coating
};

struct LongTimePrediction {
  std::vector<LongTimePoint> points;  // at the times asked, in order
  std::vector<std::int64_t> ids;
  std::vector<double> final_coating;  // [kg] per parcel at the last time
  double wall_seconds = 0;
};

// Carries every parcel of the database on from its last snapshot to each of `times` (s since the
// run's start; those before the record's end are read from the record itself), with a seeded
// generator: the same seed gives the same answer. A time between two of the model's steps is
// answered at the nearest step, and its point carries that step's time.
LongTimePrediction predictLongTime(const LongTimeModel& model, const CoatingDatabase& db,
                                   std::vector<double> times, std::uint64_t seed = 1);

// Adds a warning to `model` when its mixing time is longer than the batch goes on past the
// record (from `record_end_s` to `batch_end_s`, both since the run's start): such a bed is not
// well mixed by the batch's end, a record long enough for its slow motion would be longer than
// the batch itself, and the never-coated share at the end rests on which parcels the record
// shows reaching the zone (a longer record lowers it).
void warnWhenTheBedOutlastsTheBatch(LongTimeModel& model, double record_end_s, double batch_end_s);

}  // namespace cosim::analysis

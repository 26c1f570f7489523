#include "cosim/analysis/long_time_check.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <unordered_map>

#include "cosim/analysis/coating_statistics.h"
#include "cosim/analysis/particle_file.h"
#include "cosim/link/fields.h"
#include "cosim/util/errors.h"

namespace cosim::analysis {

std::vector<RecordedCoating> readRecordedCoating(const ParticleFile& file,
                                                 const std::vector<double>& times) {
  const auto& snaps = file.snapshots();
  if (!file.hasField(field::coating_mass))
    throw InputError(file.path().string() + ": no coating recorded (a scene with coating)");
  std::vector<RecordedCoating> out;
  for (const double t : times) {
    std::size_t at = snaps.size();
    for (std::size_t i = 0; i < snaps.size(); ++i)
      if (snaps[i].time <= t + 1e-6) at = i;
    if (at == snaps.size())
      throw InputError(
          fmt::format("{}: no snapshot at or before t = {:g} s", file.path().string(), t));
    out.push_back({snaps[at].time, file.ids(at), file.read(at, field::coating_mass)});
  }
  return out;
}

double ksDistance(std::vector<double> a, std::vector<double> b) {
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  const double na = static_cast<double>(a.size()), nb = static_cast<double>(b.size());
  double d = 0;
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    const double x = std::min(a[i], b[j]);  // step both distributions past every value x
    while (i < a.size() && a[i] <= x) ++i;
    while (j < b.size() && b[j] <= x) ++j;
    d = std::max(d, std::fabs(static_cast<double>(i) / na - static_cast<double>(j) / nb));
  }
  return d;
}

namespace {
LongTimePoint pointOf(double t, const std::vector<double>& c) {
  const auto s = coatingStatistics(t, c, 0.0);
  const auto zero = std::count_if(c.begin(), c.end(), [](double x) { return x <= 0; });
  return {t, s.mean, s.cv,
          c.empty() ? 0.0 : static_cast<double>(zero) / static_cast<double>(c.size())};
}

std::vector<double> deciles(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  std::vector<double> q;
  for (int k = 1; k <= 9; ++k)
    q.push_back(v.empty() ? 0.0 : v[static_cast<std::size_t>(k * (v.size() - 1) / 10)]);
  return q;
}

// The parcels' predicted and recorded coating at time t as a row of the check; at the last check
// time also the two distributions compared
void addRow(LongTimeCheck& check, double t, const std::vector<double>& predicted,
            const std::vector<double>& recorded, bool last) {
  LongTimeCheckRow row;
  row.time = t;
  row.predicted = pointOf(t, predicted);
  row.recorded = pointOf(t, recorded);
  row.mean_error = row.predicted.mean / row.recorded.mean - 1;
  row.cv_error = row.predicted.cv / row.recorded.cv - 1;
  row.never_points = 100 * (row.predicted.never_coated_share - row.recorded.never_coated_share);
  check.rows.push_back(row);
  if (!last || predicted.empty() || recorded.empty()) return;
  check.parcels = predicted.size();
  check.ks_distance = ksDistance(predicted, recorded);
  const double n = static_cast<double>(predicted.size());
  const double m = static_cast<double>(recorded.size());
  check.ks_critical = 1.358 * std::sqrt((n + m) / (n * m));
  check.predicted_deciles = deciles(predicted);
  check.recorded_deciles = deciles(recorded);
}
}  // namespace

LongTimeCheck checkLongTime(const LongTimeModel& model, const CoatingDatabase& db,
                            const std::vector<RecordedCoating>& record, std::uint64_t seed) {
  LongTimeCheck check;
  const double end = db.times.back();
  // the recorded times after the record's end that the model's steps reach
  std::vector<const RecordedCoating*> after;
  for (const auto& r : record) {
    const double steps = (r.time - end) / model.interval;
    if (r.time > end + 1e-9 * std::max(1.0, end) && std::fabs(steps - std::round(steps)) < 1e-3)
      after.push_back(&r);
  }
  if (after.empty()) return check;
  std::sort(after.begin(), after.end(),
            [](const auto* x, const auto* y) { return x->time < y->time; });
  std::unordered_map<std::int64_t, std::size_t> slot;
  for (std::size_t j = 0; j < db.ids.size(); ++j) slot[db.ids[j]] = j;
  // the recorded parcels the model carries, and which of the model's the record still holds
  std::vector<std::vector<double>> recorded(after.size());
  std::vector<std::vector<char>> held(after.size(), std::vector<char>(db.ids.size(), 0));
  for (std::size_t k = 0; k < after.size(); ++k)
    for (std::size_t i = 0; i < after[k]->ids.size(); ++i) {
      const auto it = slot.find(after[k]->ids[i]);
      if (it == slot.end()) continue;
      recorded[k].push_back(after[k]->coating[i]);
      held[k][it->second] = 1;
    }
  // one prediction per check time, each carried from the record's end with the same seed, so
  // that every row has the parcels' predicted coating to restrict to the ones the record holds
  for (std::size_t k = 0; k < after.size(); ++k) {
    const double t = after[k]->time;
    const auto pr = predictLongTime(model, db, {t}, seed);
    std::vector<double> predicted;
    for (std::size_t j = 0; j < db.ids.size(); ++j)
      if (held[k][j]) predicted.push_back(pr.final_coating[j]);
    addRow(check, t, predicted, recorded[k], k + 1 == after.size());
  }
  return check;
}

namespace {
// The model's steps at which a check compares, of `steps` in all: a quarter, half and three
// quarters of the way and the last, each once and none at 0
std::vector<std::size_t> checkSteps(std::size_t steps) {
  std::vector<std::size_t> q;
  for (const std::size_t s : {steps / 4, steps / 2, 3 * steps / 4, steps})
    if (s > 0 && (q.empty() || s > q.back())) q.push_back(s);
  return q;
}

// The parcels of `db` in `fold` (0 or 1: alternate parcels in the record's order); with
// `first_only`, only the record's first snapshot of them (where a prediction starts)
CoatingDatabase parcelsOf(const CoatingDatabase& db, std::size_t fold, bool first_only) {
  CoatingDatabase part;
  part.interval = db.interval;
  part.grid = db.grid;
  const std::size_t snapshots = first_only ? 1 : db.times.size();
  part.times.assign(db.times.begin(), db.times.begin() + static_cast<std::ptrdiff_t>(snapshots));
  part.state.resize(snapshots);
  part.coating.resize(snapshots);
  for (std::size_t j = fold; j < db.ids.size(); j += 2) {
    part.ids.push_back(db.ids[j]);
    for (std::size_t t = 0; t < snapshots; ++t) {
      part.state[t].push_back(db.state[t][j]);
      part.coating[t].push_back(db.coating[t][j]);
    }
  }
  return part;
}
}  // namespace

std::optional<LongTimeCheck> checkOnHeldOutParcels(const CoatingDatabase& db, std::size_t lag,
                                                   std::uint64_t seed) {
  const std::size_t last = db.times.size() - 1;
  const std::size_t steps = lag < 1 ? 0 : last / lag;
  if (steps < 2 || db.ids.size() < 2) return std::nullopt;
  std::vector<std::size_t> at;  // snapshots a quarter, half, three quarters of the way and last
  for (const std::size_t q : checkSteps(steps)) at.push_back(q * lag);
  std::vector<std::vector<double>> predicted(at.size()), recorded(at.size());
  for (std::size_t fold = 0; fold < 2; ++fold) {
    const auto model = fitLongTimeModel(parcelsOf(db, 1 - fold, false), lag);
    const auto start = parcelsOf(db, fold, true);
    for (std::size_t k = 0; k < at.size(); ++k) {
      const auto pr = predictLongTime(model, start, {db.times[at[k]]}, seed + fold);
      predicted[k].insert(predicted[k].end(), pr.final_coating.begin(), pr.final_coating.end());
      for (std::size_t j = fold; j < db.ids.size(); j += 2)
        recorded[k].push_back(db.coating[at[k]][j]);
    }
  }
  LongTimeCheck check;
  for (std::size_t k = 0; k < at.size(); ++k)
    addRow(check, db.times[at[k]], predicted[k], recorded[k], k + 1 == at.size());
  return check;
}

namespace {
// The record [from, until] cut at its middle snapshot: the snapshot times, the middle's index
// and the first half's database on `grid`. nullopt for fewer than 6 snapshots.
struct Halves {
  RecordGrid whole;
  std::size_t mid = 0;
  CoatingDatabase first;
};
std::optional<Halves> halves(const ParticleFile& file, double from, double until,
                             const Compartments& grid) {
  Halves h;
  h.whole = recordGrid(file, from, until);  // its times only: no field read
  const std::size_t n = h.whole.times.size();
  if (n < 6) return std::nullopt;
  h.mid = (n - 1) / 2;
  h.first = readCoatingDatabase(file, h.whole.times.front(), h.whole.times[h.mid], grid);
  return h;
}

// The first half's model stepping `lag` intervals, held against the second half
std::optional<HalfCheck> holdOnSecondHalf(const ParticleFile& file, const Halves& halves,
                                          std::size_t lag, std::uint64_t seed) {
  const auto wall0 = std::chrono::steady_clock::now();
  const std::size_t n = halves.whole.times.size(), mid = halves.mid;
  // the model's steps: at least two in each half
  const std::size_t steps = (n - 1 - mid) / lag;
  if (lag < 1 || mid < 2 * lag || steps < 2) return std::nullopt;
  HalfCheck h;
  h.record_to = halves.whole.times[mid];
  std::vector<double> times;  // a quarter, half, three quarters of the second half and its end
  for (const std::size_t q : checkSteps(steps)) times.push_back(halves.whole.times[mid + q * lag]);
  const auto model = fitLongTimeModel(halves.first, lag);
  const double record = model.record_gain_per_interval;
  h.settles_off =
      record > 0 && std::fabs(model.settled_gain_per_interval / record - 1) > kSettledRateTolerance;
  h.step = model.interval;
  h.check = checkLongTime(model, halves.first, readRecordedCoating(file, times), seed);
  h.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return h;
}
}  // namespace

std::optional<HalfCheck> checkOnSecondHalf(const ParticleFile& file, double from, double until,
                                           const Compartments& grid, std::size_t lag,
                                           std::uint64_t seed) {
  const auto wall0 = std::chrono::steady_clock::now();
  const auto h = halves(file, from, until, grid);
  if (!h) return std::nullopt;
  auto check = holdOnSecondHalf(file, *h, lag, seed);
  if (check)
    check->wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return check;
}

std::vector<std::size_t> candidateLags(double interval, const std::vector<double>& steps) {
  std::vector<std::size_t> lags;
  for (const double step : steps) {
    const auto lag = std::max<std::size_t>(
        1, static_cast<std::size_t>(std::llround(step / std::max(interval, 1e-300))));
    if (std::find(lags.begin(), lags.end(), lag) == lags.end()) lags.push_back(lag);
  }
  return lags;
}

GridChoice chooseCompartments(const ParticleFile& file, double from, double until,
                              const std::vector<Compartments>& candidates,
                              const std::vector<double>& steps, std::uint64_t seed) {
  GridChoice c;
  if (candidates.empty() || steps.empty()) return c;
  const double interval = recordGrid(file, from, until).interval;
  const auto lags = candidateLags(interval, steps);
  c.chosen = candidates.front();
  c.lag = lags.front();
  for (const auto& grid : candidates) {
    const auto since = [](auto t0) {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    };
    const auto wall0 = std::chrono::steady_clock::now();
    const auto h = halves(file, from, until, grid);  // each half and the whole read once per grid
    if (!h) continue;
    const auto whole = readCoatingDatabase(file, from, until, grid);
    const double read = since(wall0) / static_cast<double>(lags.size());
    for (const std::size_t lag : lags) {
      auto half = holdOnSecondHalf(file, *h, lag, seed);
      if (!half || half->check.rows.empty()) continue;
      const auto held0 = std::chrono::steady_clock::now();
      auto held_out = checkOnHeldOutParcels(whole, lag, seed);
      // the trial's wall: both checks and its share of reading the grid's record
      half->wall_seconds += since(held0) + read;
      c.trials.push_back({grid, lag, std::move(*half), std::move(held_out)});
    }
  }
  const bool any_settles = std::any_of(c.trials.begin(), c.trials.end(),
                                       [](const GridTrial& t) { return !t.half.settles_off; });
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : c.trials) {
    if (any_settles && t.half.settles_off) continue;
    if (trialDistance(t) < best) {
      best = trialDistance(t);
      c.chosen = t.grid;
      c.lag = t.lag;
    }
  }
  return c;
}

double trialDistance(const GridTrial& t) {
  const auto scaled = [](const LongTimeCheck& c) {
    return c.ks_critical > 0 ? c.ks_distance / c.ks_critical : c.ks_distance;
  };
  return std::max(scaled(t.half.check), t.held_out ? scaled(*t.held_out) : 0.0);
}

void to_json(Json& j, const LongTimeCheck& c) {
  const auto point = [](const LongTimePoint& p) {
    return Json{{"mean_kg", p.mean}, {"cv", p.cv}, {"never_coated_share", p.never_coated_share}};
  };
  Json rows = Json::array();
  for (const auto& r : c.rows)
    rows.push_back({{"time_s", r.time},
                    {"model", point(r.predicted)},
                    {"run", point(r.recorded)},
                    {"mean_error", r.mean_error},
                    {"cv_error", r.cv_error},
                    {"never_coated_points", r.never_points}});
  j = Json{{"rows", rows},
           {"parcels", c.parcels},
           {"ks_distance", c.ks_distance},
           {"ks_critical_5pct", c.ks_critical},
           {"model_deciles_kg", c.predicted_deciles},
           {"run_deciles_kg", c.recorded_deciles}};
}

void to_json(Json& j, const GridTrial& t) {
  j = Json{{"rings", t.grid.rings},
           {"layers", t.grid.layers},
           {"step_s", t.half.step},
           {"record_to_s", t.half.record_to},
           {"settles_off", t.half.settles_off},
           {"wall_s", t.half.wall_seconds},
           {"held_out_parcels", t.held_out ? Json(*t.held_out) : Json()},
           {"distance", trialDistance(t)}};
  j.update(Json(t.half.check));
}

}  // namespace cosim::analysis

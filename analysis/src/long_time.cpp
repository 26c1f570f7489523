#include "cosim/analysis/long_time.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <unordered_map>

#include "cosim/analysis/coating_statistics.h"
#include "cosim/analysis/particle_file.h"
#include "cosim/link/fields.h"
#include "cosim/util/errors.h"

namespace cosim::analysis {

int Compartments::of(double x, double y, double z) const {
  const double r2 = x * x + y * y;
  const int ring =
      r_max > 0 ? static_cast<int>(std::floor(rings * r2 / (r_max * r_max))) : 0;  // equal areas
  const int layer = z_max > 0 ? static_cast<int>(std::floor(layers * z / z_max)) : 0;
  return std::clamp(layer, 0, layers - 1) * rings + std::clamp(ring, 0, rings - 1);
}

namespace {
// The record's output interval: the most frequent spacing of the snapshots in `use` (a stop's
// extra snapshot makes two shorter ones).
double recordInterval(const std::vector<SnapshotInfo>& snaps, const std::vector<std::size_t>& use) {
  std::vector<double> gaps;
  for (std::size_t k = 1; k < use.size(); ++k)
    gaps.push_back(snaps[use[k]].time - snaps[use[k - 1]].time);
  std::sort(gaps.begin(), gaps.end());
  double best = gaps.front();
  std::size_t most = 0;
  for (std::size_t a = 0; a < gaps.size();) {
    std::size_t b = a;
    while (b < gaps.size() && gaps[b] - gaps[a] <= 1e-6 * gaps[a]) ++b;
    if (b - a > most) {
      most = b - a;
      best = gaps[a];
    }
    a = b;
  }
  return best;
}
}  // namespace

RecordGrid recordGrid(const ParticleFile& file, double from, double until) {
  const std::string where = file.path().string();
  RecordGrid g;
  const auto& snaps = file.snapshots();
  for (std::size_t i = 0; i < snaps.size(); ++i) {
    const double t = snaps[i].time;
    if (t + 1e-9 >= from && (until < 0 || t <= until + 1e-9)) g.use.push_back(i);
  }
  auto tooFew = [&] {
    return InputError(fmt::format(
        "{}: {} snapshots between t = {:g} and {:g} s; the long-time model needs at least 3 "
        "(a record of several seconds, output.interval 0.1 s)",
        where, g.use.size(), from, until));
  };
  if (g.use.size() < 3) throw tooFew();
  g.interval = recordInterval(snaps, g.use);
  // A run stopped with Ctrl-C (or by a time limit) writes one more snapshot where it stopped,
  // between two of the output interval: set aside, the record steps on without it.
  const double t0 = snaps[g.use[0]].time;
  std::erase_if(g.use, [&](std::size_t i) {
    const double k = (snaps[i].time - t0) / g.interval;
    const bool off = std::fabs(k - std::round(k)) > 1e-6 * std::max(1.0, k);
    if (off) g.off_interval.push_back(snaps[i].time);
    return off;
  });
  if (g.use.size() < 3) throw tooFew();
  for (std::size_t k = 0; k < g.use.size(); ++k) {
    g.times.push_back(snaps[g.use[k]].time);
    if (k > 0 && std::fabs(g.times[k] - g.times[k - 1] - g.interval) > 1e-6 * g.interval)
      throw InputError(fmt::format(
          "{}: the snapshots are not evenly spaced (t = {:g} s after {:g} s, not {:g} s later): "
          "the model steps by one interval; give --from after the uneven ones",
          where, g.times[k], g.times[k - 1], g.interval));
  }
  return g;
}

CoatingDatabase readCoatingDatabase(const ParticleFile& file, double from, double until,
                                    Compartments grid) {
  const std::string where = file.path().string();
  if (grid.rings < 1 || grid.layers < 1)
    throw InputError("long-time model: at least one ring and one layer");
  if (!file.hasField(field::position) || !file.hasField(field::coating_mass))
    throw InputError(where + ": no positions or coating recorded (a scene with coating)");
  RecordGrid record = recordGrid(file, from, until);
  const std::vector<std::size_t>& use = record.use;
  CoatingDatabase db;
  db.grid = grid;
  db.interval = record.interval;
  db.times = record.times;
  db.off_interval = record.off_interval;
  // parcels present in every snapshot used
  std::unordered_map<std::int64_t, std::size_t> seen;
  for (std::size_t k : use)
    for (auto id : file.ids(k)) ++seen[id];
  for (const auto& [id, n] : seen) {
    if (n == use.size())
      db.ids.push_back(id);
    else
      ++db.left_out;
  }
  std::sort(db.ids.begin(), db.ids.end());
  std::unordered_map<std::int64_t, std::size_t> slot;
  for (std::size_t i = 0; i < db.ids.size(); ++i) slot[db.ids[i]] = i;
  const std::size_t n = db.ids.size();
  std::vector<std::vector<double>> pos(use.size());
  db.coating.assign(use.size(), std::vector<double>(n, 0.0));
  double r_max = 0;
  std::vector<double> heights;
  for (std::size_t k = 0; k < use.size(); ++k) {
    const auto ids = file.ids(use[k]);
    const auto x = file.read(use[k], field::position);
    const auto m = file.read(use[k], field::coating_mass);
    pos[k].assign(3 * n, 0.0);
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const auto it = slot.find(ids[i]);
      if (it == slot.end()) continue;
      const std::size_t j = it->second;
      for (int c = 0; c < 3; ++c) pos[k][3 * j + c] = x[3 * i + c];
      db.coating[k][j] = m[i];
      r_max = std::max(r_max, std::hypot(x[3 * i], x[3 * i + 1]));
      heights.push_back(x[3 * i + 2]);
    }
  }
  if (db.grid.r_max <= 0) db.grid.r_max = r_max * (1 + 1e-9);
  if (db.grid.z_max <= 0 && !heights.empty()) {  // the bed's top: 99 % of the parcels below
    const auto q = heights.begin() +
                   static_cast<std::ptrdiff_t>(0.99 * static_cast<double>(heights.size() - 1));
    std::nth_element(heights.begin(), q, heights.end());
    db.grid.z_max = *q;
  }
  db.state.assign(use.size(), std::vector<int>(n, 0));
  for (std::size_t k = 0; k < use.size(); ++k)
    for (std::size_t j = 0; j < n; ++j)
      db.state[k][j] = db.grid.of(pos[k][3 * j], pos[k][3 * j + 1], pos[k][3 * j + 2]);
  return db;
}

namespace {

using Matrix = std::vector<double>;  // K x K, row-major

Matrix multiply(const Matrix& a, const Matrix& b, int k) {
  Matrix c(a.size(), 0.0);
  for (int i = 0; i < k; ++i)
    for (int l = 0; l < k; ++l) {
      const double ail = a[i * k + l];
      if (ail == 0) continue;
      for (int j = 0; j < k; ++j) c[i * k + j] += ail * b[l * k + j];
    }
  return c;
}

// P^(2^i) for i = 0, 1, ... by repeated squaring, until a square changes no entry by more than
// 1e-14 (the limit reached) or i = 40; the last is each row's limit (the chain reducible or not).
std::vector<Matrix> squarings(const Matrix& p, int k) {
  std::vector<Matrix> powers = {p};
  for (int i = 0; i < 40; ++i) {
    Matrix next = multiply(powers.back(), powers.back(), k);
    double change = 0;
    for (std::size_t e = 0; e < next.size(); ++e)
      change = std::max(change, std::fabs(next[e] - powers.back()[e]));
    powers.push_back(std::move(next));
    if (change <= 1e-14) break;
  }
  return powers;
}

// Intervals until every visited state's row of P^n is within 0.25 (total variation) of its own
// limit; infinity when it is not within the squarings.
double mixingIntervals(const std::vector<Matrix>& powers, int k,
                       const std::vector<std::size_t>& departures) {
  const Matrix& limit = powers.back();
  for (std::size_t i = 0; i < powers.size(); ++i) {
    double worst = 0;
    for (int s = 0; s < k; ++s) {
      if (departures[s] == 0) continue;
      double tv = 0;
      for (int j = 0; j < k; ++j) tv += std::fabs(powers[i][s * k + j] - limit[s * k + j]);
      worst = std::max(worst, 0.5 * tv);
    }
    if (worst < 0.25) return std::ldexp(1.0, static_cast<int>(i));
  }
  return std::numeric_limits<double>::infinity();
}

// Expected intervals until a parcel starting in each state first starts an interval in a coating
// state (one whose recorded moves gained coating): (I - Q) h = 1 over the other states, Q the
// moves among them; infinity for states that cannot reach one. Gaussian elimination (K ~ 50).
std::vector<double> intervalsToTheZone(const Matrix& p, int k, const std::vector<char>& coats) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> h(k, inf);
  std::vector<char> reach(coats.begin(), coats.end());
  for (bool grew = true; grew;) {  // states from which a coating state can be reached
    grew = false;
    for (int a = 0; a < k; ++a)
      for (int b = 0; b < k && !reach[a]; ++b)
        if (p[a * k + b] > 0 && reach[b]) reach[a] = grew = true;
  }
  std::vector<int> idx;
  for (int a = 0; a < k; ++a) {
    if (coats[a])
      h[a] = 0;
    else if (reach[a])
      idx.push_back(a);
  }
  const std::size_t n = idx.size();
  std::vector<double> A(n * (n + 1), 0.0);  // [I - Q | 1]
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j)
      A[i * (n + 1) + j] = (i == j ? 1.0 : 0.0) - p[idx[i] * k + idx[j]];
    A[i * (n + 1) + n] = 1.0;
  }
  for (std::size_t c = 0; c < n; ++c) {  // partial pivoting
    std::size_t piv = c;
    for (std::size_t r = c + 1; r < n; ++r)
      if (std::fabs(A[r * (n + 1) + c]) > std::fabs(A[piv * (n + 1) + c])) piv = r;
    for (std::size_t j = 0; j <= n; ++j) std::swap(A[c * (n + 1) + j], A[piv * (n + 1) + j]);
    const double d = A[c * (n + 1) + c];
    if (d == 0) continue;
    for (std::size_t r = 0; r < n; ++r) {
      if (r == c) continue;
      const double f = A[r * (n + 1) + c] / d;
      if (f == 0) continue;
      for (std::size_t j = c; j <= n; ++j) A[r * (n + 1) + j] -= f * A[c * (n + 1) + j];
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double d = A[i * (n + 1) + i];
    if (d != 0) h[idx[i]] = A[i * (n + 1) + n] / d;
  }
  return h;
}

// The coating a parcel gains per interval, on average over the population: in the record over
// its second half, and in the chain settled from the record's last occupancy (`settled`:
// P^(2^20), or P's limit if reached sooner). They
// differ when the record's bed had not settled yet, or when a compartment lumps parcels that coat
// differently: the model then carries the batch on at a rate the record did not show.
void checkSettledRate(const CoatingDatabase& db, const Matrix& settled, LongTimeModel& m) {
  const int k = m.states;
  const std::size_t last = db.coating.size() - 1, mid = last / 2;
  if (last == mid || db.ids.empty()) return;
  double sum_last = 0, sum_mid = 0;
  for (std::size_t j = 0; j < db.ids.size(); ++j) {
    sum_last += db.coating[last][j];
    sum_mid += db.coating[mid][j];
  }
  const auto n = static_cast<double>(db.ids.size());
  m.record_gain_per_interval =
      (sum_last - sum_mid) / n / static_cast<double>(last - mid) * static_cast<double>(m.lag);
  std::vector<double> d(k, 0.0);
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b)
      d[b] += static_cast<double>(m.occupied_at_end[a]) * settled[a * k + b];
  double mass = 0, gain = 0;
  for (int a = 0; a < k; ++a) {
    mass += d[a];
    gain += d[a] * m.expected_gain[a];
  }
  if (mass <= 0) return;
  m.settled_gain_per_interval = gain / mass;
  const double record = m.record_gain_per_interval, model = m.settled_gain_per_interval;
  if (record > 0 && std::fabs(model / record - 1) > kSettledRateTolerance)
    m.warnings.push_back(fmt::format(
        "the model settles to a coating rate {:+.0f} % off the record's over its second half "
        "({:.4g} against {:.4g} kg per parcel and second): the record's bed had not settled, or "
        "its compartments lump parcels that coat differently; the batch's mean errs by about as "
        "much (a later --from, past the bed's start-up; a longer record; or more --rings and "
        "--layers)",
        100 * (model / record - 1), model / m.interval, record / m.interval));
}

}  // namespace

namespace {
// The moves the record holds over `lag` of its intervals, from every snapshot: their counts
// (turned into probabilities by `toProbabilities`), the gains of each (from, to), the departures
// from each state.
struct Moves {
  Matrix P;
  std::vector<std::vector<double>> gains;
  std::vector<std::size_t> departures;
};
Moves countMoves(const CoatingDatabase& db, std::size_t lag, int k) {
  Moves m;
  m.P.assign(static_cast<std::size_t>(k) * k, 0.0);
  m.gains.assign(static_cast<std::size_t>(k) * k, {});
  m.departures.assign(k, 0);
  for (std::size_t t = 0; t + lag < db.state.size(); ++t) {
    for (std::size_t j = 0; j < db.ids.size(); ++j) {
      const int a = db.state[t][j], b = db.state[t + lag][j];
      m.P[a * k + b] += 1;
      m.gains[a * k + b].push_back(db.coating[t + lag][j] - db.coating[t][j]);
      ++m.departures[a];
    }
  }
  return m;
}

void toProbabilities(Moves& m, int k) {
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b)
      if (m.departures[a] > 0) m.P[a * k + b] /= static_cast<double>(m.departures[a]);
}

// A compartment the record enters but never shows a parcel leaving (seen only at its last
// snapshots: no move out over a step, none over an interval) is a dead end of the record, not of
// the bed: a chain that keeps the moves into it holds every parcel it sends there for the whole
// batch, uncoated, and over an hour such parcels add up. The moves into dead ends are left out
// (again while leaving them out makes new ones); returns how many. `single`: the moves over one
// interval when the step is longer (else empty).
std::size_t dropMovesIntoDeadEnds(Moves& step, Moves& single, int k) {
  const bool has_single = !single.departures.empty();
  const auto dead = [&](int b) {
    return step.departures[b] == 0 && (!has_single || single.departures[b] == 0);
  };
  std::size_t dropped = 0;
  for (bool again = true; again;) {
    again = false;
    for (int b = 0; b < k; ++b) {
      if (!dead(b)) continue;
      for (int a = 0; a < k; ++a) {
        for (Moves* m : {&step, has_single ? &single : nullptr}) {
          if (m == nullptr || m->P[a * k + b] == 0) continue;
          const auto n = static_cast<std::size_t>(m->P[a * k + b]);
          m->P[a * k + b] = 0;
          m->gains[a * k + b].clear();
          m->departures[a] -= n;
          dropped += m == &step ? n : 0;
          again = again || dead(a);
        }
      }
    }
  }
  return dropped;
}

// Mean recorded gain of a move from each state (0 where none is recorded)
std::vector<double> meanGains(const std::vector<std::vector<double>>& gains,
                              const std::vector<std::size_t>& departures, int k) {
  std::vector<double> g(k, 0.0);
  for (int a = 0; a < k; ++a) {
    if (departures[a] == 0) continue;
    for (int b = 0; b < k; ++b)
      for (const double x : gains[a * k + b]) g[a] += x;
    g[a] /= static_cast<double>(departures[a]);
  }
  return g;
}
}  // namespace

namespace {
// The record's shortcomings the fitted chain shows, as plain-language warnings: parcels that
// cannot reach the zone, a wait for the zone or a mixing time longer than the record, parcels
// where no move out (or too few) is recorded. `h`: intervals to the zone from each state;
// `seen`: departures the chain knows from each state.
void warnAboutTheRecord(LongTimeModel& m, const std::vector<double>& h,
                        const std::vector<std::size_t>& seen, std::size_t min_departures) {
  const int k = m.states;
  std::size_t unreachable = 0;
  for (int a = 0; a < k; ++a)
    if (m.occupied_at_end[a] > 0 && seen[a] > 0 && !std::isfinite(h[a]))
      unreachable += m.occupied_at_end[a];
  if (unreachable > 0)
    m.warnings.push_back(fmt::format(
        "{} parcels sit in compartments from which the record shows no way to the coating zone: "
        "the model keeps them uncoated by the zone for the whole batch; a longer record would "
        "show whether they reach it",
        unreachable));
  if (std::isfinite(m.longest_wait_seconds) && m.longest_wait_seconds > m.record_seconds) {
    m.warnings.push_back(fmt::format(
        "parcels of the bed wait longer for the coating zone than the record lasts: from the "
        "slowest compartment a parcel reaches the zone after {:.3g} s on average, the record is "
        "{:.3g} s long; record at least {:.3g} s (twice that wait) so that these moves are seen "
        "often enough to carry the batch",
        m.longest_wait_seconds, m.record_seconds, 2 * m.longest_wait_seconds));
  } else if (m.mixing_seconds > m.record_seconds) {
    m.warnings.push_back(
        std::isfinite(m.mixing_seconds)
            ? fmt::format("the bed's slowest motion takes longer than the record: the "
                          "compartments mix in about {:.3g} s, the record is {:.3g} s long; "
                          "record at least {:.3g} s (twice the mixing time) for rates seen "
                          "often enough to carry the batch",
                          m.mixing_seconds, m.record_seconds, 2 * m.mixing_seconds)
            : fmt::format("the compartments do not mix within any time from this {:.3g} s "
                          "record: parts of the bed the parcels were seen in are never seen to "
                          "exchange with the rest; a longer record would show whether they do",
                          m.record_seconds));
  }
  // Parcels where the record has no move out at all, or too few to trust its rates
  std::size_t stuck = 0, thin = 0;
  int stuck_states = 0, thin_states = 0;
  for (int s = 0; s < k; ++s) {
    if (m.occupied_at_end[s] == 0) continue;
    const bool single = m.by_single[s] != 0;
    const std::size_t departures = single ? m.departures1[s] : m.departures[s];
    const std::size_t stays = single ? m.gains1[s * k + s].size() : m.gains[s * k + s].size();
    if (departures == stays) {  // no move elsewhere
      stuck += m.occupied_at_end[s];
      ++stuck_states;
    } else if (departures < min_departures) {
      thin += m.occupied_at_end[s];
      ++thin_states;
    }
  }
  if (stuck > 0)
    m.warnings.push_back(fmt::format(
        "{} parcels sit in {} compartments no parcel was seen to leave in the record: the model "
        "keeps them there (and uncoated if they are) for the whole batch",
        stuck, stuck_states));
  if (thin > 0)
    m.warnings.push_back(fmt::format(
        "{} parcels sit in {} compartments seen fewer than {} times in the record: their rates "
        "rest on few moves",
        thin, thin_states, min_departures));
}
}  // namespace

LongTimeModel fitLongTimeModel(const CoatingDatabase& db, std::size_t lag,
                               std::size_t min_departures) {
  if (lag < 1 || lag >= db.state.size())
    throw InputError(fmt::format(
        "long-time model: a step of {} intervals of {:g} s does not fit a record of {} snapshots",
        lag, db.interval, db.state.size()));
  LongTimeModel m;
  const int k = db.grid.count();
  m.states = k;
  m.lag = lag;
  m.interval = db.interval * static_cast<double>(lag);
  m.record_seconds = db.times.back() - db.times.front();
  Moves step_moves = countMoves(db, lag, k), single_moves;
  if (lag > 1) single_moves = countMoves(db, 1, k);
  m.dead_end_moves = dropMovesIntoDeadEnds(step_moves, single_moves, k);
  toProbabilities(step_moves, k);
  m.P = std::move(step_moves.P);
  m.gains = std::move(step_moves.gains);
  m.departures = std::move(step_moves.departures);
  m.occupied_at_end.assign(k, 0);
  for (int s : db.state.back()) ++m.occupied_at_end[s];
  m.expected_gain = meanGains(m.gains, m.departures, k);
  m.by_single.assign(k, 0);
  // The chain the warnings and the settled rate are computed on: each state's row of moves over
  // a step, or for a state that goes by single intervals, the row of P1^lag.
  Matrix step = m.P;
  if (lag > 1) {
    toProbabilities(single_moves, k);
    m.P1 = std::move(single_moves.P);
    m.gains1 = std::move(single_moves.gains);
    m.departures1 = std::move(single_moves.departures);
    bool any = false;
    for (int a = 0; a < k; ++a) {
      m.by_single[a] = m.departures[a] < min_departures && m.departures1[a] > 0 ? 1 : 0;
      any = any || m.by_single[a];
    }
    if (any) {
      Matrix power = m.P1;  // P1^i, and the gain over i single intervals from each state
      const std::vector<double> g1 = meanGains(m.gains1, m.departures1, k);
      std::vector<double> over = g1;
      for (std::size_t i = 1; i < lag; ++i) {
        for (int a = 0; a < k; ++a)
          for (int b = 0; b < k; ++b) over[a] += power[a * k + b] * g1[b];
        power = multiply(power, m.P1, k);
      }
      for (int a = 0; a < k; ++a) {
        if (!m.by_single[a]) continue;
        std::copy(power.begin() + a * k, power.begin() + (a + 1) * k, step.begin() + a * k);
        m.expected_gain[a] = over[a];
      }
    }
  }
  std::vector<std::size_t> seen = m.departures;  // states the chain knows a move out of
  for (int a = 0; a < k; ++a)
    if (m.by_single[a]) seen[a] = m.departures1[a];

  const std::vector<Matrix> powers = squarings(step, k);
  m.mixing_seconds = mixingIntervals(powers, k, seen) * m.interval;
  std::vector<char> coats(k, 0);  // states whose moves gain coating
  for (int a = 0; a < k; ++a) coats[a] = m.expected_gain[a] > 0 ? 1 : 0;
  const auto h = intervalsToTheZone(step, k, coats);
  m.zone_return_seconds.assign(k, 0.0);
  m.longest_wait_seconds = 0;
  for (int a = 0; a < k; ++a) {
    m.zone_return_seconds[a] = h[a] * m.interval;
    if (m.occupied_at_end[a] > 0 && seen[a] > 0)
      m.longest_wait_seconds = std::max(m.longest_wait_seconds, m.zone_return_seconds[a]);
  }
  warnAboutTheRecord(m, h, seen, min_departures);
  // settled: 2^20 intervals on (a day at 0.1 s, longer than any batch), or the limit if sooner
  checkSettledRate(db, powers[std::min<std::size_t>(20, powers.size() - 1)], m);
  return m;
}

LongTimePrediction predictLongTime(const LongTimeModel& model, const CoatingDatabase& db,
                                   std::vector<double> times, std::uint64_t seed) {
  const auto wall0 = std::chrono::steady_clock::now();
  std::sort(times.begin(), times.end());
  LongTimePrediction out;
  out.ids = db.ids;
  const int k = model.states;
  const std::size_t n = db.ids.size();
  const double end = db.times.back();
  // cumulative rows for drawing the next compartment, over a step and over one interval
  const auto cumulative = [k](const std::vector<double>& P) {
    std::vector<double> cum(P.size());
    for (int a = 0; a < k && !P.empty(); ++a) {
      double c = 0;
      for (int b = 0; b < k; ++b) cum[a * k + b] = (c += P[a * k + b]);
    }
    return cum;
  };
  const std::vector<double> cum = cumulative(model.P), cum1 = cumulative(model.P1);
  std::vector<int> state = db.state.back();
  std::vector<double> coating = db.coating.back();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  double now = end;
  const auto point = [&](double t, const std::vector<double>& c) {
    const auto s = coatingStatistics(t, c, 0.0);
    std::size_t zero = 0;
    for (double x : c) zero += x <= 0 ? 1 : 0;
    return LongTimePoint{t, s.mean, s.cv,
                         n ? static_cast<double>(zero) / static_cast<double>(n) : 0.0};
  };
  for (double t : times) {
    if (t <= end + 1e-9 * std::max(1.0, end)) {  // within the record: read it
      std::size_t at = 0;
      while (at + 1 < db.times.size() && db.times[at + 1] <= t + 1e-9) ++at;
      out.points.push_back(point(db.times[at], db.coating[at]));
      continue;
    }
    const auto steps = static_cast<long long>(std::llround((t - now) / model.interval));
    for (long long step = 0; step < steps; ++step) {
      for (std::size_t j = 0; j < n; ++j) {
        // a move drawn from the recorded ones from `a`, with a gain recorded for that move
        const auto move = [&](const std::vector<double>& c,
                              const std::vector<std::vector<double>>& gains, int a) {
          const double* row = &c[static_cast<std::size_t>(a) * k];
          int b = static_cast<int>(std::upper_bound(row, row + k, uniform(rng) * row[k - 1]) - row);
          b = std::min(b, k - 1);
          const auto& g = gains[static_cast<std::size_t>(a) * k + b];
          if (!g.empty()) {
            const auto pick =
                static_cast<std::size_t>(uniform(rng) * static_cast<double>(g.size()));
            coating[j] += g[std::min(pick, g.size() - 1)];
          }
          state[j] = b;
        };
        const int a = state[j];
        if (model.by_single[a]) {  // too few moves over a step recorded: single intervals
          for (std::size_t i = 0; i < model.lag; ++i)
            if (model.departures1[state[j]] > 0) move(cum1, model.gains1, state[j]);
          continue;
        }
        if (model.departures[a] == 0) continue;  // never seen to move: stays, gains nothing
        move(cum, model.gains, a);
      }
    }
    now += static_cast<double>(steps) * model.interval;
    // the time asked, when the steps reach it; else the step's own time
    const bool reached = std::fabs(now - t) <= 1e-6 * std::max(1.0, t);
    out.points.push_back(point(reached ? t : now, coating));
  }
  out.final_coating = coating;
  out.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return out;
}

void warnWhenTheBedOutlastsTheBatch(LongTimeModel& m, double record_end_s, double batch_end_s) {
  const double batch = batch_end_s - record_end_s;
  if (batch <= 0 || !std::isfinite(m.mixing_seconds) || m.mixing_seconds <= batch) return;
  m.warnings.push_back(fmt::format(
      "the bed mixes more slowly than the batch lasts: its compartments mix in about {:.3g} s, the "
      "batch goes on {:.3g} s past the record; it will not be well mixed by its end, and a record "
      "long enough for its slow motion would outlast the batch itself: the never-coated share at "
      "the end is what this record shows reaching the coating zone, and a longer record lowers "
      "it (compare two record lengths with --to)",
      m.mixing_seconds, batch));
}

}  // namespace cosim::analysis

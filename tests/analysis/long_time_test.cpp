// The long-time coating model against a bed whose exact long-time answer is computable: a
// synthetic record drawn from a known three-compartment chain (far from the jet, beside it, in the
// zone, gaining a fixed coating on every interval that starts in the zone). The model fitted on
// 40 intervals of it predicts the mean, the CV and the never-coated share hundreds of intervals
// later as the exact chain gives them (dynamic programming over compartment and passes).
#include "cosim/analysis/long_time.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "cosim/analysis/long_time_check.h"
#include "cosim/analysis/particle_file.h"
#include "cosim/analysis/particle_recorder.h"
#include "cosim/link/fields.h"
#include "cosim/util/errors.h"

using namespace cosim::analysis;

namespace {

const std::vector<double> kTrue = {0.90, 0.10, 0.00,   // far from the jet
                                   0.20, 0.50, 0.30,   // beside it
                                   0.00, 0.60, 0.40};  // in the zone: gains kGain per interval
const double kGain = 1.0;

int draw(const std::vector<double>& p, int from, double u) {
  double c = 0;
  for (int to = 0; to < 3; ++to)
    if (u < (c += p[from * 3 + to])) return to;
  return 2;
}

CoatingDatabase synthetic(const std::vector<double>& p, std::size_t parcels, int intervals,
                          std::uint64_t seed) {
  CoatingDatabase db;
  db.grid.rings = 3;
  db.grid.layers = 1;
  db.interval = 0.1;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  for (std::size_t j = 0; j < parcels; ++j) db.ids.push_back(static_cast<std::int64_t>(j + 1));
  std::vector<int> s(parcels, 0);
  std::vector<double> c(parcels, 0.0);
  for (int t = 0; t <= intervals; ++t) {
    db.times.push_back(0.1 * t);
    db.state.push_back(s);
    db.coating.push_back(c);
    for (std::size_t j = 0; j < parcels; ++j) {
      if (s[j] == 2) c[j] += kGain;
      s[j] = draw(p, s[j], u(rng));
    }
  }
  return db;
}

struct Exact {
  double mean, cv, never;
};

// The exact population statistics n intervals after the record's end, for the parcels as the
// record leaves them: per parcel, the distribution of the passes it makes, by dynamic programming
// over (compartment, passes), then the mixture over parcels.
Exact exactAfter(const std::vector<double>& p, const CoatingDatabase& db, int n) {
  // per starting compartment: distribution of the number of gains in n intervals
  std::vector<std::vector<double>> dist(3);
  for (int s0 = 0; s0 < 3; ++s0) {
    std::vector<std::vector<double>> f(3, std::vector<double>(n + 1, 0.0));
    f[s0][0] = 1;
    for (int t = 0; t < n; ++t) {
      std::vector<std::vector<double>> g(3, std::vector<double>(n + 1, 0.0));
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c <= t; ++c) {
          if (f[a][c] == 0) continue;
          const int c2 = a == 2 ? c + 1 : c;
          for (int b = 0; b < 3; ++b) g[b][c2] += f[a][c] * p[a * 3 + b];
        }
      f = g;
    }
    dist[s0].assign(n + 1, 0.0);
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c <= n; ++c) dist[s0][c] += f[a][c];
  }
  double m1 = 0, m2 = 0, never = 0;
  const auto& s = db.state.back();
  const auto& c0 = db.coating.back();
  for (std::size_t j = 0; j < s.size(); ++j) {
    for (int c = 0; c <= n; ++c) {
      const double x = c0[j] + kGain * c, w = dist[s[j]][c];
      m1 += w * x;
      m2 += w * x * x;
      if (x == 0) never += w;
    }
  }
  const double N = static_cast<double>(s.size());
  const double mean = m1 / N;
  return {mean, std::sqrt(m2 / N - mean * mean) / mean, never / N};
}

}  // namespace

TEST(LongTimeModel, PredictsAKnownChainsMeanCvAndNeverCoatedShare) {
  const CoatingDatabase db = synthetic(kTrue, 20000, 40, 7);
  const LongTimeModel m = fitLongTimeModel(db);
  // the fitted rates: within the sampling error of 10^5 moves
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(m.P[i], kTrue[i], 0.01) << i;
  EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
  EXPECT_LT(m.mixing_seconds, 4.0);
  const std::vector<int> after = {3, 20, 300};
  std::vector<double> times;
  for (int n : after) times.push_back(4.0 + 0.1 * n);
  const LongTimePrediction pr = predictLongTime(m, db, times, 11);
  ASSERT_EQ(pr.points.size(), 3u);
  for (std::size_t i = 0; i < after.size(); ++i) {
    const Exact e = exactAfter(kTrue, db, after[i]);
    SCOPED_TRACE(after[i]);
    std::printf("after %d intervals: mean %.4f (exact %.4f), CV %.4f (%.4f), never %.4f (%.4f)\n",
                after[i], pr.points[i].mean, e.mean, pr.points[i].cv, e.cv,
                pr.points[i].never_coated_share, e.never);
    EXPECT_NEAR(pr.points[i].mean, e.mean, 0.01 * e.mean);
    EXPECT_NEAR(pr.points[i].cv, e.cv, 0.03 * e.cv);
    EXPECT_NEAR(pr.points[i].never_coated_share, e.never, 0.01);
  }
  // within the record the answer is the record's own
  const LongTimePrediction in = predictLongTime(m, db, {2.0}, 1);
  double sum = 0;
  for (double x : db.coating[20]) sum += x;
  EXPECT_DOUBLE_EQ(in.points[0].mean, sum / 20000.0);
  // the same seed, the same answer
  EXPECT_EQ(predictLongTime(m, db, {10.0}, 5).final_coating,
            predictLongTime(m, db, {10.0}, 5).final_coating);
}

// A bed whose far compartment is left once in 500 intervals: 40 intervals cannot hold that. The
// model says so from the record itself, with the length it needs; and compartments no parcel was
// seen to leave are named, their parcels kept there.
TEST(LongTimeModel, SaysWhenTheRecordIsTooShortForTheSlowMotion) {
  std::vector<double> slow = kTrue;
  slow[0] = 0.998;
  slow[1] = 0.002;
  const LongTimeModel m = fitLongTimeModel(synthetic(slow, 20000, 40, 3));
  ASSERT_FALSE(m.warnings.empty());
  EXPECT_GT(m.longest_wait_seconds, 4.0);  // about 500 intervals far from the jet
  EXPECT_NE(m.warnings.front().find("record at least"), std::string::npos) << m.warnings.front();

  std::vector<double> stuck = kTrue;
  stuck[0] = 1.0;
  stuck[1] = 0.0;
  const CoatingDatabase db = synthetic(stuck, 1000, 40, 3);
  const LongTimeModel s = fitLongTimeModel(db);
  bool named = false;
  for (const auto& w : s.warnings)
    named |= w.find("no parcel was seen to leave") != std::string::npos;
  EXPECT_TRUE(named);
  // all start far from the jet and never leave: none is ever coated
  EXPECT_EQ(predictLongTime(s, db, {3600.0}, 1).points[0].never_coated_share, 1.0);
}

namespace {
// The exact chain's mixing time by hand: the first n at which every row of P^n lies within 0.25
// (total variation) of the stationary distribution, P^n taken one interval at a time.
int exactMixingIntervals(const std::vector<double>& p) {
  std::vector<double> pn = p, limit = p;
  for (int i = 0; i < 40; ++i) {  // the stationary rows: P^(2^40), squared up
    std::vector<double> sq(9, 0.0);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int c = 0; c < 3; ++c) sq[a * 3 + c] += limit[a * 3 + b] * limit[b * 3 + c];
    limit = sq;
  }
  for (int n = 1; n < 100000; ++n) {
    double worst = 0;
    for (int a = 0; a < 3; ++a) {
      double tv = 0;
      for (int c = 0; c < 3; ++c) tv += std::fabs(pn[a * 3 + c] - limit[a * 3 + c]);
      worst = std::max(worst, 0.5 * tv);
    }
    if (worst < 0.25) return n;
    std::vector<double> next(9, 0.0);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int c = 0; c < 3; ++c) next[a * 3 + c] += pn[a * 3 + b] * p[b * 3 + c];
    pn = next;
  }
  return 100000;
}
}  // namespace

// A bed of two parts that exchange rarely (the far compartment left once in 500 intervals, the
// jet's two left for it once in 250 from beside the jet) is named as such when the batch is
// shorter than its mixing time, and not when the batch is several mixing times long: the
// threshold against the exact chain's own mixing time.
TEST(LongTimeModel, SaysWhenTheBedMixesMoreSlowlyThanTheBatchLasts) {
  const std::vector<double> slow = {0.998, 0.002, 0.000,   // far from the jet
                                    0.004, 0.596, 0.400,   // beside it
                                    0.000, 0.600, 0.400};  // in the zone
  const CoatingDatabase db = synthetic(slow, 20000, 100, 3);
  const double exact = 0.1 * exactMixingIntervals(slow);  // [s]
  ASSERT_GT(exact, 10.0);  // hundreds of intervals: longer than the 10 s record
  const auto says = [](const LongTimeModel& m) {
    for (const auto& w : m.warnings)
      if (w.find("mixes more slowly than the batch lasts") != std::string::npos) return true;
    return false;
  };
  const LongTimeModel fitted = fitLongTimeModel(db);
  std::printf("mixing time: exact %.1f s, fitted %.1f s\n", exact, fitted.mixing_seconds);
  LongTimeModel shortBatch = fitted, longBatch = fitted;
  warnWhenTheBedOutlastsTheBatch(shortBatch, 10.0, 10.0 + 0.4 * exact);
  EXPECT_TRUE(says(shortBatch)) << "mixing " << fitted.mixing_seconds << " s, exact " << exact;
  warnWhenTheBedOutlastsTheBatch(longBatch, 10.0, 10.0 + 3.0 * exact);
  EXPECT_FALSE(says(longBatch)) << "mixing " << fitted.mixing_seconds << " s, exact " << exact;
  // a well-mixed chain is silent over any batch past a few seconds
  LongTimeModel mixed = fitLongTimeModel(synthetic(kTrue, 20000, 40, 7));
  warnWhenTheBedOutlastsTheBatch(mixed, 4.0, 60.0);
  EXPECT_FALSE(says(mixed));
}

namespace {
namespace fs = std::filesystem;

// An empty folder of this test process's own
fs::path freshFolder(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("cosim-long-time-" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A recorder of the parcels' positions and coating into `dir`
ParticleRecorder recorder(const fs::path& dir) {
  return ParticleRecorder(dir, {cosim::field::position, cosim::field::coating_mass},
                          RunIdentity{"long-time-test", 1.0});
}

// A particles.h5 of two parcels with snapshots at `times`.
fs::path recordAt(const std::string& name, const std::vector<double>& times) {
  const fs::path dir = freshFolder(name);
  ParticleRecorder rec = recorder(dir);
  for (const double t : times) {
    cosim::link::ParticleData p;
    p.ids = {1, 2};
    p.field(cosim::field::position) = {0.001, 0, 0.01, 0.002, 0, 0.02};
    p.field(cosim::field::coating_mass) = {1e-12 * t, 0};
    rec.write(t, p);
  }
  return dir / "particles.h5";
}

// A particles.h5 of `parcels` parcels on the vessel's axis plane with `snapshots` snapshots
// 0.1 s apart; `place(k, j)` gives parcel j's (x, coating) at snapshot k and may draw the next
// move (it is called in order of k, then j).
template <class Place>
fs::path recordOf(const std::string& name, std::size_t parcels, int snapshots, Place place) {
  const fs::path dir = freshFolder(name);
  ParticleRecorder rec = recorder(dir);
  for (int k = 0; k < snapshots; ++k) {
    cosim::link::ParticleData p;
    p.ids.resize(parcels);
    auto& x = p.field(cosim::field::position);
    auto& m = p.field(cosim::field::coating_mass);
    x.assign(3 * parcels, 0.0);
    m.assign(parcels, 0.0);
    for (std::size_t j = 0; j < parcels; ++j) {
      p.ids[j] = static_cast<std::int64_t>(j + 1);
      const auto [radius, coating] = place(k, j);
      x[3 * j] = radius;
      x[3 * j + 2] = 0.01;
      m[j] = coating;
    }
    rec.write(0.1 * k, p);
  }
  return dir / "particles.h5";
}
}  // namespace

// A run stopped with Ctrl-C records one more snapshot where it stopped (here 0.26 s between the
// 0.1 s ones, and 0.43 s at the end): the record keeps its interval and sets those aside.
TEST(LongTimeDatabase, SetsAsideTheSnapshotsAStopWroteBetweenTheInterval) {
  const ParticleFile f(recordAt("stopped", {0.0, 0.1, 0.2, 0.26, 0.3, 0.4, 0.43}));
  const auto db = readCoatingDatabase(f, 0.0, -1, Compartments{2, 2});
  EXPECT_DOUBLE_EQ(db.interval, 0.1);
  ASSERT_EQ(db.times.size(), 5u);
  EXPECT_NEAR(db.times.back(), 0.4, 1e-12);
  ASSERT_EQ(db.off_interval.size(), 2u);
  EXPECT_NEAR(db.off_interval[0], 0.26, 1e-12);
  EXPECT_NEAR(db.off_interval[1], 0.43, 1e-12);
  EXPECT_NEAR(db.coating.back()[0], 0.4e-12, 1e-24);
}

// A snapshot missing from the sequence is a gap the model cannot step over: refused, naming the
// file and the times.
TEST(LongTimeDatabase, RefusesARecordWithASnapshotMissing) {
  const ParticleFile f(recordAt("gap", {0.0, 0.1, 0.2, 0.3, 0.5, 0.6}));
  try {
    (void)readCoatingDatabase(f, 0.0, -1, Compartments{2, 2});
    FAIL() << "a record with a gap was accepted";
  } catch (const std::exception& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("particles.h5"), std::string::npos) << what;
    EXPECT_NE(what.find("t = 0.5 s after 0.3 s"), std::string::npos) << what;
  }
}

// A bed still settling through its record: every parcel starts far from the jet and the bed
// exchanges with it at 0.5-1 % an interval, so the record's second half coats far below the
// chain's settled rate (its stationary share in the zone, the gain being 1 per interval there).
// The model says so, and its settled rate is the exact chain's.
TEST(LongTimeModel, SaysWhenItSettlesToAnotherRateThanTheRecordShows) {
  const std::vector<double> slow = {0.995, 0.005, 0.00,  //
                                    0.01,  0.69,  0.30,  //
                                    0.00,  0.60,  0.40};
  const auto db = synthetic(slow, 50000, 40, 7);
  const auto m = fitLongTimeModel(db);
  // stationary (a chain 0 <-> 1 <-> 2): pi1 = pi0 * 0.005 / 0.01, pi2 = pi1 * 0.3 / 0.6
  const double pi0 = 1.0, pi1 = 0.5, pi2 = 0.25;
  const double exact = pi2 / (pi0 + pi1 + pi2);
  EXPECT_NEAR(m.settled_gain_per_interval, exact, 0.005 * exact);  // 5.5e-4 reached (seed 7)
  EXPECT_LT(m.record_gain_per_interval, 0.5 * exact);
  bool said = false;
  for (const auto& w : m.warnings)
    said = said || w.find("settles to a coating rate") != std::string::npos;
  EXPECT_TRUE(said);
}

// A compartment the record's last snapshot alone holds (a parcel of the known chain moved there at
// the end; the record never shows one leaving it) is a dead end of the record: the moves into it
// are left out of the chain, so it sends no parcel there, and the rest of the chain is the known
// one. Kept, the chain would absorb a parcel there now and then and keep its coating from then
// on for the whole batch: one move of the origin's 40 x 20,000 x (its share) makes
// 20,000 x 3,000 / 800,000 = 75 parcels in 3,000 intervals, each short of about half the mean:
// the CV about 8 % higher.
TEST(LongTimeModel, LeavesOutMovesIntoCompartmentsNeverSeenLeft) {
  CoatingDatabase db = synthetic(kTrue, 20000, 40, 7);
  db.grid.rings = 4;  // a fourth compartment, entered at the record's last snapshot only
  const int origin = db.state[39][0];
  db.state[40][0] = 3;
  for (const std::size_t lag : {1u, 4u}) {
    SCOPED_TRACE(lag);
    const LongTimeModel m = fitLongTimeModel(db, lag);
    EXPECT_EQ(m.dead_end_moves, 1u);  // parcel 0's last move over a step, from snapshot 40 - lag
    for (int a = 0; a < 4; ++a) {
      EXPECT_EQ(m.P[a * 4 + 3], 0.0) << "from " << a;
      if (lag > 1) {
        EXPECT_EQ(m.P1[a * 4 + 3], 0.0) << "from " << a;
      }
    }
    EXPECT_NEAR(m.P[origin * 4 + 0] + m.P[origin * 4 + 1] + m.P[origin * 4 + 2], 1.0, 1e-12);
    // the parcel that ended there is named, and stays where the record left it
    bool said = false;
    for (const auto& w : m.warnings) said = said || w.find("1 parcels sit in 1 compart") == 0;
    EXPECT_TRUE(said);
  }
  // the mean, CV and never-coated share 3,000 intervals on: the known chain's, for the 19,999
  // parcels that go on moving (the one in the dead end keeps its coating)
  const LongTimeModel m = fitLongTimeModel(db, 1);
  const auto pr = predictLongTime(m, db, {4.0 + 300.0}, 3);
  ASSERT_EQ(pr.final_coating.size(), 20000u);
  const Exact exact = exactAfter(kTrue, synthetic(kTrue, 20000, 40, 7), 3000);
  const auto& p = pr.points[0];
  std::printf("after 3000 intervals: mean %.4f (exact %.4f), CV %.5f (%.5f)\n", p.mean, exact.mean,
              p.cv, exact.cv);
  EXPECT_NEAR(p.mean, exact.mean, 0.01 * exact.mean);
  EXPECT_NEAR(p.cv, exact.cv, 0.03 * exact.cv);
}

// The two-sample Kolmogorov-Smirnov distance by hand: {1,2,3} against {2,3,4}: at 1, 1/3 against
// 0; at 2, 2/3 against 1/3; at 3, 1 against 2/3: 1/3. With ties ({0,0,1} against {0,1,1}): 1/3.
TEST(LongTimeCheck, KolmogorovSmirnovDistanceByHand) {
  EXPECT_DOUBLE_EQ(ksDistance({1, 2, 3}, {2, 3, 4}), 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(ksDistance({0, 0, 1}, {0, 1, 1}), 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(ksDistance({5, 1}, {1, 5}), 0.0);
  EXPECT_DOUBLE_EQ(ksDistance({1}, {2}), 1.0);
}

// The model fitted on the first 40 intervals of a known chain's record, held against the same
// record 20, 100 and 300 intervals later (the parcels' own later history, not the exact answer):
// within the sampling noise of 20,000 parcels, and the histograms as close as two independent
// samples' (Kolmogorov-Smirnov below twice the 5 % critical distance).
TEST(LongTimeCheck, AgreesWithTheRestOfAKnownChainsRecord) {
  const CoatingDatabase full = synthetic(kTrue, 20000, 340, 7);
  CoatingDatabase db = full;
  db.times.resize(41);
  db.state.resize(41);
  db.coating.resize(41);
  const LongTimeModel m = fitLongTimeModel(db);
  std::vector<RecordedCoating> rest;
  for (int k : {60, 140, 340}) rest.push_back({full.times[k], full.ids, full.coating[k]});
  rest.push_back({full.times[20], full.ids, full.coating[20]});  // within the record: not a row
  const LongTimeCheck c = checkLongTime(m, db, rest, 3);
  ASSERT_EQ(c.rows.size(), 3u);
  EXPECT_NEAR(c.rows[0].time, 6.0, 1e-9);
  EXPECT_NEAR(c.rows[2].time, 34.0, 1e-9);
  for (const auto& r : c.rows) {
    SCOPED_TRACE(r.time);
    std::printf("t = %g: mean %+.4f, CV %+.4f, never %+.3f points\n", r.time, r.mean_error,
                r.cv_error, r.never_points);
    EXPECT_LT(std::fabs(r.mean_error), 0.01);
    EXPECT_LT(std::fabs(r.cv_error), 0.03);
    EXPECT_LT(std::fabs(r.never_points), 1.0);
  }
  EXPECT_EQ(c.parcels, 20000u);
  EXPECT_NEAR(c.ks_critical, 1.358 * std::sqrt(2.0 / 20000), 1e-12);
  std::printf("KS %.4f (critical %.4f)\n", c.ks_distance, c.ks_critical);
  EXPECT_LT(c.ks_distance, 2 * c.ks_critical);
  ASSERT_EQ(c.recorded_deciles.size(), 9u);

  // a model that does not hold the record's motion (the zone never left once entered, and so
  // twice too much coating): the check shows it
  LongTimeModel wrong = m;
  for (int b = 0; b < 3; ++b) wrong.P[6 + b] = b == 2 ? 1.0 : 0.0;
  wrong.gains[8] = {kGain};
  const LongTimeCheck w = checkLongTime(wrong, db, rest, 3);
  EXPECT_GT(w.rows.back().mean_error, 0.5);
  EXPECT_GT(w.ks_distance, 10 * w.ks_critical);
}

// Held-out parcels: a model fitted on alternate parcels of a known chain's 40 intervals carries
// the others from the record's start to its end as the record shows them (within the sampling
// noise of 10,000 parcels a side), rows at a quarter, half, three quarters and the end.
TEST(LongTimeCheck, HoldsParcelsItWasNotFittedOn) {
  const CoatingDatabase db = synthetic(kTrue, 20000, 40, 11);
  const auto c = checkOnHeldOutParcels(db, 1, 5);
  ASSERT_TRUE(c);
  ASSERT_EQ(c->rows.size(), 4u);
  EXPECT_NEAR(c->rows[0].time, 1.0, 1e-9);
  EXPECT_NEAR(c->rows[3].time, 4.0, 1e-9);
  for (const auto& r : c->rows) {
    SCOPED_TRACE(r.time);
    std::printf("held out, t = %g: mean %+.4f, CV %+.4f, never %+.3f points\n", r.time,
                r.mean_error, r.cv_error, r.never_points);
    EXPECT_LT(std::fabs(r.mean_error), 0.01);
    EXPECT_LT(std::fabs(r.cv_error), 0.03);
    EXPECT_LT(std::fabs(r.never_points), 1.0);
  }
  EXPECT_EQ(c->parcels, 20000u);
  EXPECT_LT(c->ks_distance, 2 * c->ks_critical);
  // two of the model's steps at the least
  EXPECT_FALSE(checkOnHeldOutParcels(db, 21, 5));
}

// The recorded side: each time the snapshot at or just before it; none before the first.
TEST(LongTimeCheck, ReadsTheRecordedSnapshotAtOrBeforeEachTime) {
  const ParticleFile f(recordAt("check", {0.0, 0.1, 0.2, 0.3}));
  const auto r = readRecordedCoating(f, {0.2, 0.25});
  ASSERT_EQ(r.size(), 2u);
  EXPECT_DOUBLE_EQ(r[0].time, 0.2);
  EXPECT_DOUBLE_EQ(r[1].time, 0.2);
  ASSERT_EQ(r[0].coating.size(), 2u);
  EXPECT_DOUBLE_EQ(r[0].coating[0], 1e-12 * 0.2);
  EXPECT_THROW(readRecordedCoating(f, {-0.5}), cosim::InputError);
}

// The compartments chosen by the record itself: parcels that either sit in the zone (the inner
// ring, gaining 1 per interval) or far from it (the outer ring), each staying for many intervals.
// One compartment for the whole vessel lumps the two and spreads the coating evenly over the
// parcels (a far narrower distribution than the record's); two rings hold the record's chain
// exactly. The check on the record's second half says so, and the choice is the two rings.
TEST(LongTimeCheck, ChoosesTheCompartmentsTheRecordHoldsBest) {
  const std::vector<double> stay = {0.95, 0.975};  // in the zone, far from it
  const std::size_t n = 2000;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<int> s(n);
  std::vector<double> c(n, 0.0);
  for (std::size_t j = 0; j < n; ++j) s[j] = j % 3 == 0 ? 0 : 1;
  const ParticleFile f(recordOf("grids", n, 61, [&](int, std::size_t j) {
    const std::pair<double, double> at = {s[j] == 0 ? 0.001 : 0.009, c[j]};
    if (s[j] == 0) c[j] += 1e-12;  // the move to the next snapshot
    if (u(rng) > stay[s[j]]) s[j] = 1 - s[j];
    return at;
  }));
  const GridChoice choice =
      chooseCompartments(f, 0, -1, {Compartments{1, 1}, Compartments{2, 1}}, {0.0});
  ASSERT_EQ(choice.trials.size(), 2u);
  EXPECT_EQ(choice.chosen.rings, 2);
  const auto& lumped = choice.trials[0].half.check;
  const auto& rings = choice.trials[1].half.check;
  std::printf("Kolmogorov-Smirnov: one compartment %.4f, two rings %.4f (5 %%: %.4f)\n",
              lumped.ks_distance, rings.ks_distance, rings.ks_critical);
  EXPECT_GT(lumped.ks_distance, 3 * lumped.ks_critical);
  EXPECT_LT(rings.ks_distance, 2 * rings.ks_critical);
  EXPECT_NEAR(choice.trials[1].half.record_to, 3.0, 1e-9);
}

// The model's step chosen by the record: every parcel cycles 3 intervals far from the zone (the
// outer ring), 1 in it (the inner ring), gaining 1e-12 kg on leaving it, each at its own phase
// and from its own coating before the record.
// A chain of single intervals forgets how long a parcel has waited (it leaves the outer ring
// with probability 1/3 at every step, so some wait far longer than 3 intervals and others pass
// twice): the parcels' coating spreads where the record's does not. Over a step of 4 intervals
// every parcel passes exactly once, as recorded. Counted by hand: at one interval the outer ring
// moves to the zone 1/3 of the time; at four, every move gains exactly 1e-12 kg.
TEST(LongTimeCheck, ChoosesTheStepTheRecordHoldsBest) {
  const std::size_t n = 2000;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> start(n);  // each parcel's coating before the record: all different
  for (auto& c : start) c = 1e-12 * u(rng);
  const ParticleFile f(recordOf("steps", n, 41, [&](int k, std::size_t j) {
    const int phase = static_cast<int>(j % 4) + k;  // in the zone when phase % 4 == 3
    return std::pair<double, double>{phase % 4 == 3 ? 0.001 : 0.009,
                                     start[j] + 1e-12 * static_cast<double>(phase / 4)};
  }));
  const CoatingDatabase db = readCoatingDatabase(f, 0, -1, Compartments{2, 1, 0.01, 0.02});
  const LongTimeModel one = fitLongTimeModel(db, 1), four = fitLongTimeModel(db, 4);
  EXPECT_NEAR(four.interval, 0.4, 1e-12);
  const int outer = 1, zone = 0;
  EXPECT_NEAR(one.P[outer * 2 + zone], 1.0 / 3.0, 0.01);
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (const double g : four.gains[a * 2 + b]) ASSERT_NEAR(g, 1e-12, 1e-26);
  // a time between two steps is answered at the nearest step, and says so
  const auto pr = predictLongTime(four, db, {4.5}, 1);
  ASSERT_EQ(pr.points.size(), 1u);
  EXPECT_NEAR(pr.points[0].time, 4.4, 1e-9);

  const GridChoice choice = chooseCompartments(f, 0, -1, {Compartments{2, 1}}, {0.0, 0.4});
  ASSERT_EQ(choice.trials.size(), 2u);
  EXPECT_EQ(choice.lag, 4u);
  const auto& short_steps = choice.trials[0].half.check;
  const auto& cycle = choice.trials[1].half.check;
  std::printf("Kolmogorov-Smirnov: steps of 0.1 s %.4f, of 0.4 s %.4f (5 %%: %.4f)\n",
              short_steps.ks_distance, cycle.ks_distance, cycle.ks_critical);
  EXPECT_GT(short_steps.ks_distance, 3 * short_steps.ks_critical);
  EXPECT_LT(cycle.ks_distance, cycle.ks_critical);
  EXPECT_NEAR(choice.trials[1].half.step, 0.4, 1e-12);
  // held-out parcels over the whole 4 s: at 0.4 s every step gains exactly one pass, so the
  // held-out half comes out as recorded (to the round-off of the recorded gains)
  ASSERT_TRUE(choice.trials[0].held_out && choice.trials[1].held_out);
  const auto& held_short = *choice.trials[0].held_out;
  const auto& held_cycle = *choice.trials[1].held_out;
  std::printf("held out: steps of 0.1 s %.4f, of 0.4 s %.4f (5 %%: %.4f)\n", held_short.ks_distance,
              held_cycle.ks_distance, held_cycle.ks_critical);
  EXPECT_NEAR(held_cycle.rows.back().time, 4.0, 1e-9);
  EXPECT_GT(held_short.ks_distance, 3 * held_short.ks_critical);
  EXPECT_LT(held_cycle.ks_distance, 0.2 * held_cycle.ks_critical);
  EXPECT_LT(std::fabs(held_cycle.rows.back().mean_error), 1e-9);
}

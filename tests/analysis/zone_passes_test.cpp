// zone_passes.csv (reading, writing, resume cut) and the pass statistics with Mann's cycle-time
// prediction, against hand-computed numbers and a renewal process of known cycle times.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "cosim/analysis/files.h"
#include "cosim/analysis/parcel_places.h"
#include "cosim/analysis/particle_file.h"
#include "cosim/analysis/particle_recorder.h"
#include "cosim/analysis/report.h"
#include "cosim/analysis/zone_pass_file.h"
#include "cosim/analysis/zone_pass_statistics.h"
#include "cosim/link/fields.h"
#include "report_fixture.h"

namespace fs = std::filesystem;
using namespace cosim::analysis;
using Exit = ZonePass::Exit;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("cosim_zone_passes_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Four parcels over 10 s of coating (hand-made):
//   1: passes [1, 1.5] 2 kg, [3, 3.2] 1 kg, [6, 6.5] 3 kg   -> cycles 2, 3
//   2: in the zone at the start [0, 0.4] 1 kg, then [5, 10] 0.5 kg still in at the end
//   3: never
//   4: passes [2, 2.6] 2 kg, [4, 4.4] 2 kg                  -> cycle 2
std::vector<ZonePass> handMade() {
  return {{1, 1.0, 1.5, 2.0, false, Exit::left},    {2, 0.0, 0.4, 1.0, true, Exit::left},
          {4, 2.0, 2.6, 2.0, false, Exit::left},    {1, 3.0, 3.2, 1.0, false, Exit::left},
          {4, 4.0, 4.4, 2.0, false, Exit::left},    {1, 6.0, 6.5, 3.0, false, Exit::left},
          {2, 5.0, 10.0, 0.5, false, Exit::run_end}};
}

}  // namespace

TEST(ZonePassFile, WritesAndReadsBackEveryFieldExactly) {
  const auto path = scratch("roundtrip.csv");
  auto passes = handMade();
  passes.push_back({9, 0.1 + 0.2, 1.0 / 3.0, 1.234567890123e-13, false, Exit::deleted});
  {
    ZonePassWriter w(path);
    w.write({passes.begin(), passes.begin() + 3});
    w.write({passes.begin() + 3, passes.end()});
    EXPECT_EQ(w.rows(), passes.size());
  }
  const auto back = readZonePasses(path);
  ASSERT_EQ(back.size(), passes.size());
  for (std::size_t i = 0; i < back.size(); ++i) {
    EXPECT_EQ(back[i].parcel_id, passes[i].parcel_id);
    EXPECT_EQ(back[i].entry_time, passes[i].entry_time);
    EXPECT_EQ(back[i].exit_time, passes[i].exit_time);
    EXPECT_EQ(back[i].coating, passes[i].coating);
    EXPECT_EQ(back[i].at_start, passes[i].at_start);
    EXPECT_EQ(back[i].exit, passes[i].exit);
  }
  EXPECT_NE(slurp(path).find("2,0,0.4,1,at_start,left\n"), std::string::npos) << slurp(path);

  // Resume: cut back to 5 rows, append, and the append mode counts the rows kept.
  truncateZonePasses(path, 5);
  ZonePassWriter again(path, ZonePassWriter::Mode::append);
  EXPECT_EQ(again.rows(), 5u);
  again.write({passes[5]});
  EXPECT_EQ(readZonePasses(path).size(), 6u);
  EXPECT_THROW(truncateZonePasses(path, 7), std::runtime_error);
}

TEST(ZonePassFile, ALastLineCutByACrashIsIgnoredAndBadLinesAreNamed) {
  const auto path = scratch("cut.csv");
  {
    ZonePassWriter w(path);
    w.write(handMade());
  }
  std::ofstream(path, std::ios::app) << "3,0.5,0.";
  EXPECT_EQ(readZonePasses(path).size(), 7u);

  std::ofstream(path, std::ios::app) << "6,entered,left\n7,1,2,0,entered,left\n";
  try {
    readZonePasses(path);
    FAIL() << "a bad line in the middle must be refused";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cut.csv:9:"), std::string::npos) << e.what();
  }
  std::ofstream(path) << "parcel_id,entry_time,exit_time,coating_kg,entry,exit\n"
                         "1,2,1,0,entered,left\n2,0,1,0,entered,left\n";
  try {
    readZonePasses(path);
    FAIL() << "an exit before the entry must be refused";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cut.csv:2: exit_time 1 is before entry_time 2"),
              std::string::npos)
        << e.what();
  }
}

TEST(ZonePassStatistics, HandMadeParcelsGiveTheHandCountedNumbers) {
  const auto s = zonePassStatistics(handMade(), {1, 2, 3, 4}, 0.0, 10.0);
  EXPECT_EQ(s.parcels, 4u);
  EXPECT_EQ(s.passes, 7u);
  EXPECT_EQ(s.complete_passes, 5u);  // parcel 2's two passes are censored
  EXPECT_EQ(s.entries, 6u);          // parcel 2's first entry is not observed
  EXPECT_EQ(s.never_entered, 1u);
  EXPECT_DOUBLE_EQ(s.never_entered_share, 0.25);
  EXPECT_EQ(s.at_most_one_entry, 2u);  // parcels 2 and 3

  // Passes per parcel 3, 2, 0, 2: mean 1.75, population variance 4.75 / 4.
  EXPECT_EQ(s.parcel_passes, (std::vector<std::size_t>{3, 2, 0, 2}));
  EXPECT_DOUBLE_EQ(s.passes_per_parcel.mean, 1.75);
  EXPECT_NEAR(s.passes_per_parcel.sd, std::sqrt(4.75 / 4.0), 1e-15);
  EXPECT_NEAR(s.passes_cv, std::sqrt(4.75 / 4.0) / 1.75, 1e-15);
  // One bin per whole number of passes 0..3: one parcel with 0, none with 1, two with 2, one
  // with 3.
  EXPECT_EQ(s.passes_per_parcel.histogram.counts, (std::vector<std::size_t>{1, 0, 2, 1}));

  // Cycles 2, 3, 2: mean 7/3, sample variance (1/9 + 4/9 + 1/9) / 2 = 1/3; p90 = 2 + 0.8.
  EXPECT_EQ(s.cycle_time.n, 3u);
  EXPECT_NEAR(s.cycle_time.mean, 7.0 / 3.0, 1e-15);
  EXPECT_NEAR(s.cycle_time.sd, std::sqrt(1.0 / 3.0), 1e-15);
  EXPECT_DOUBLE_EQ(s.cycle_time.p50, 2.0);
  EXPECT_NEAR(s.cycle_time.p90, 2.8, 1e-15);

  // Complete passes last 0.5, 0.2, 0.6, 0.4, 0.5 s and carry 2, 1, 2, 2, 3 kg.
  EXPECT_NEAR(s.pass_duration.mean, 2.2 / 5.0, 1e-15);
  EXPECT_DOUBLE_EQ(s.coating_per_pass.mean, 2.0);
  EXPECT_NEAR(s.coating_per_pass.sd, std::sqrt(2.0 / 4.0), 1e-15);

  // Time in the zone: 1.2 + 5.4 + 0 + 1.0 = 7.6 parcel-seconds of 40.
  EXPECT_NEAR(s.time_in_zone_share, 7.6 / 40.0, 1e-15);
  EXPECT_NEAR(s.parcel_time_in_zone[1], 5.4, 1e-15);
  // One entry every 40 / 6 parcel-seconds; 11.5 kg over 7 passes.
  EXPECT_NEAR(s.cycle_time_from_rate, 40.0 / 6.0, 1e-14);
  EXPECT_DOUBLE_EQ(s.coating_in_passes, 11.5);
  EXPECT_DOUBLE_EQ(s.w0, 11.5 / 7.0);
  // 11.5 kg taken up over 7.6 parcel-seconds in the zone.
  EXPECT_NEAR(s.uptake_rate_in_zone, 11.5 / 7.6, 1e-15);
  EXPECT_EQ(s.parcel_coating, (std::vector<double>{6.0, 1.5, 0.0, 4.0}));
  EXPECT_TRUE(s.prediction_ok) << s.prediction_problem;
}

TEST(ZonePassStatistics, WithoutTwoCyclesThereIsNoPredictionAndItSaysWhy) {
  const std::vector<ZonePass> one = {{1, 1.0, 1.5, 2.0, false, Exit::left},
                                     {1, 3.0, 3.5, 2.0, false, Exit::left}};
  const auto s = zonePassStatistics(one, {1, 2}, 0.0, 5.0);
  EXPECT_EQ(s.cycle_time.n, 1u);
  EXPECT_FALSE(s.prediction_ok);
  EXPECT_NE(s.prediction_problem.find("fewer than 2 cycles"), std::string::npos);
  EXPECT_TRUE(std::isnan(predictFromPasses(s, 100.0).cv));
  const auto none = zonePassStatistics({}, {1, 2, 3}, 0.0, 5.0);
  EXPECT_EQ(none.never_entered, 3u);
  EXPECT_DOUBLE_EQ(none.never_entered_share, 1.0);
  EXPECT_TRUE(std::isnan(none.cycle_time_from_rate));
}

TEST(MannPrediction, FormulaByHand) {
  // W0 = 2 kg, mu_T = 4 s, sigma_T = 2 s, t = 100 s: mean 2 * 100 / 4 = 50 kg,
  // sd = 2 * 2 * sqrt(100 / 64) = 5 kg, CV = 2 / sqrt(400) = 0.1; 25 passes.
  const auto p = mannPrediction(2.0, 4.0, 2.0, 0.0, 100.0);
  EXPECT_DOUBLE_EQ(p.mean, 50.0);
  EXPECT_DOUBLE_EQ(p.sd, 5.0);
  EXPECT_DOUBLE_EQ(p.cv, 0.1);
  EXPECT_DOUBLE_EQ(p.passes_mean, 25.0);
  EXPECT_DOUBLE_EQ(p.cv_with_pass_spread, 0.1);
  // sigma_W = 1 kg: CV^2 = (0.25 + 0.25) * 4 / 100 = 0.02.
  EXPECT_NEAR(mannPrediction(2.0, 4.0, 2.0, 1.0, 100.0).cv_with_pass_spread, std::sqrt(0.02),
              1e-15);
}

// A renewal process of known cycle times: every parcel passes the zone for d = 0.2 s, then waits
// a gamma-distributed gap (mean 0.8 s, sd 0.5 s), so the cycle has mu_T = 1 s and sigma_T = 0.5 s,
// and takes W0 = 3 ng per pass. Over t = 400 s Mann predicts mean 1200 ng and CV
// 0.5 / sqrt(400) = 0.025. The measured cycle statistics must match mu_T and sigma_T within
// their sampling error, and the coating of the simulated bed the predicted mean and CV.
TEST(MannPrediction, ARenewalProcessOfKnownCycleTimesIsPredicted) {
  const double d = 0.2, gap_mean = 0.8, gap_sd = 0.5, w0 = 3e-12, T = 400.0;
  const double mu_t = d + gap_mean, sigma_t = gap_sd;
  const std::size_t n = 4000;
  std::mt19937_64 rng(20240607);
  const double k = (gap_mean / gap_sd) * (gap_mean / gap_sd);
  std::gamma_distribution<double> gap(k, gap_mean / k);
  std::uniform_real_distribution<double> phase(0.0, 1.0);
  std::vector<ZonePass> passes;
  std::vector<std::int64_t> ids;
  std::vector<double> coating(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    ids.push_back(static_cast<std::int64_t>(i + 1));
    // Start anywhere in a cycle (stationary enough for T = 400 mu_T).
    double t = -phase(rng) * (d + gap(rng));
    while (t < T) {
      const double entry = t, exit = t + d;
      if (exit > 0.0) {
        ZonePass p{ids.back(), std::max(entry, 0.0), std::min(exit, T), 0.0,
                   entry<0.0, exit> T ? Exit::run_end : Exit::left};
        p.coating = w0 * p.duration() / d;  // coating at a constant rate while in the zone
        coating[i] += p.coating;
        passes.push_back(p);
      }
      t = exit + gap(rng);
    }
  }
  const auto s = zonePassStatistics(passes, ids, 0.0, T);
  ASSERT_TRUE(s.prediction_ok) << s.prediction_problem;
  const double cycles = static_cast<double>(s.cycle_time.n);
  EXPECT_GT(cycles, 0.99 * n * (T / mu_t - 2));
  // Sampling errors: sd / sqrt(n) for the mean, about sd / sqrt(2 n) for the sd (cycles of one
  // parcel are independent gaps, so the pooled cycles are independent).
  EXPECT_NEAR(s.cycle_time.mean, mu_t, 4.0 * sigma_t / std::sqrt(cycles));
  EXPECT_NEAR(s.cycle_time.sd, sigma_t, 4.0 * 1.3 * sigma_t / std::sqrt(2.0 * cycles));
  EXPECT_NEAR(s.pass_duration.mean, d, 1e-9 * d);  // exit - entry at t ~ 400 s, summed 1.6e6 times
  EXPECT_NEAR(s.w0, w0, 0.01 * w0);                // the censored passes at both ends are partial

  const auto p = predictFromPasses(s, T);
  const double cv_true = sigma_t / std::sqrt(mu_t * T);
  EXPECT_NEAR(p.cv, cv_true, 0.01 * cv_true);
  EXPECT_NEAR(p.mean, w0 * T / mu_t, 0.01 * w0 * T / mu_t);

  // The simulated bed: its coating mean and CV are what Mann predicts, within the sampling error
  // of n parcels (relative error of a CV about 1 / sqrt(2 n) = 1.1 %) and the renewal process's
  // edge terms of order mu_T / T.
  double mean = 0, var = 0;
  for (double m : coating) mean += m / n;
  for (double m : coating) var += (m - mean) * (m - mean) / n;
  const double cv = std::sqrt(var) / mean;
  EXPECT_NEAR(mean, p.mean, 0.01 * p.mean);
  EXPECT_NEAR(cv, p.cv, 0.05 * p.cv) << "simulated CV " << cv << ", Mann " << p.cv;
  std::printf(
      "renewal bed: cycles %.0f, mu_T %.5f s, sigma_T %.5f s, CV simulated %.5f, "
      "predicted %.5f, true %.5f\n",
      cycles, s.cycle_time.mean, s.cycle_time.sd, cv, p.cv, cv_true);
}

namespace {

// A run folder of four parcels over 2 s: 1 and 2 near the axis and high, pass the zone; 3 and 4
// low at the wall, never in it. Snapshots at 0, 1, 2 s.
//   parcel  x [m]    z at 0, 1, 2 s [m]        passes
//   1       0.001    0.02, 0.03, 0.04         [0.2, 0.4] 1 pg, [1.0, 1.3] 2 pg, [1.8, 2.0) 1 pg
//   (run end) 2      -0.001    0.02, 0.02, 0.02         [0, 0.5] 3 pg (at start), [1.5, 1.7] 1 pg
//   3       0.01     0.001, 0.001, 0.001      none
//   4      -0.01     0.002, 0.004, 0.003      none
fs::path makeRunWithPasses() {
  const fs::path dir = scratch("run-with-passes");
  fs::remove_all(dir);
  fs::create_directories(dir);
  {
    ParticleRecorder rec(dir, {cosim::field::position, cosim::field::coating_mass},
                         cosim::analysis::RunIdentity{"zone-passes-test", 1.0});
    const double x[4] = {0.001, -0.001, 0.01, -0.01};
    const double z[3][4] = {
        {0.02, 0.02, 0.001, 0.002}, {0.03, 0.02, 0.001, 0.004}, {0.04, 0.02, 0.001, 0.003}};
    const double m[3][4] = {{0, 0, 0, 0}, {1e-12, 3e-12, 0, 0}, {4e-12, 4e-12, 0, 0}};
    for (int s = 0; s < 3; ++s) {
      cosim::link::ParticleData p;
      p.ids = {1, 2, 3, 4};
      auto& pos = p.field(cosim::field::position);
      pos.resize(12);
      for (int i = 0; i < 4; ++i) {
        pos[3 * i] = x[i];
        pos[3 * i + 2] = z[s][i];
      }
      p.field(cosim::field::coating_mass) = {m[s][0], m[s][1], m[s][2], m[s][3]};
      rec.write(static_cast<double>(s), p);
    }
  }
  ZonePassWriter w(dir / kZonePassesFile);
  w.write({{2, 0.0, 0.5, 3e-12, true, Exit::left},
           {1, 0.2, 0.4, 1e-12, false, Exit::left},
           {1, 1.0, 1.3, 2e-12, false, Exit::left},
           {2, 1.5, 1.7, 1e-12, false, Exit::left},
           {1, 1.8, 2.0, 1e-12, false, Exit::run_end}});
  return dir;
}

}  // namespace

TEST(ParcelPlaces, GroupAveragesByHand) {
  const fs::path dir = makeRunWithPasses();
  const ParticleFile f(dir / "particles.h5");
  const auto p = placesOf(f, {3, 4});
  ASSERT_TRUE(p.valid) << p.problem;
  EXPECT_NEAR(p.axis_x, 0.0, 1e-18);
  EXPECT_EQ(p.snapshots, 3u);
  EXPECT_EQ(p.group.parcels, 2u);
  EXPECT_NEAR(p.group.mean_height, (0.001 + 0.003) / 2, 1e-15);
  EXPECT_NEAR(p.group.mean_radius, 0.01, 1e-15);
  EXPECT_NEAR(p.group.start_height, (0.001 + 0.002) / 2, 1e-15);
  EXPECT_NEAR(p.others.mean_height, (0.03 + 0.02) / 2, 1e-15);
  EXPECT_NEAR(p.others.mean_radius, 0.001, 1e-15);
  EXPECT_NEAR(p.others.start_height, 0.02, 1e-15);
}

TEST(ZonePassReport, TheReportShowsThePassesAndWhereTheMissingParcelsSit) {
  const fs::path dir = makeRunWithPasses();
  test::QuietReport report({dir});
  report.options.bootstrap_resamples = 0;
  ASSERT_EQ(report.run(), 0) << report.log.str();
  const auto j = readJsonFile(dir / "report" / "report.json").at("zone_passes");
  ASSERT_TRUE(j.at("recorded").get<bool>());
  EXPECT_EQ(j.at("parcels").get<int>(), 4);
  EXPECT_EQ(j.at("passes").get<int>(), 5);
  EXPECT_EQ(j.at("never_entered").get<int>(), 2);
  EXPECT_DOUBLE_EQ(j.at("never_entered_share").get<double>(), 0.5);
  // Cycles of parcel 1 only (parcel 2's first entry is not observed): 0.8 and 0.8 s.
  EXPECT_EQ(j.at("cycle_time_s").at("n").get<int>(), 2);
  EXPECT_NEAR(j.at("cycle_time_s").at("mean").get<double>(), 0.8, 1e-15);
  // Entry rate: 4 parcels x 2 s / 4 observed entries.
  EXPECT_NEAR(j.at("cycle_time_from_rate_s").get<double>(), 2.0, 1e-15);
  EXPECT_NEAR(j.at("coating_in_passes_kg").get<double>(), 8e-12, 1e-24);
  EXPECT_NEAR(j.at("coating_on_parcels_kg").get<double>(), 8e-12, 1e-24);
  EXPECT_NEAR(j.at("w0_kg").get<double>(), 8e-12 / 5, 1e-24);
  // Mann at the run end (t = 2 s): W0 t / mu_T = 1.6e-12 * 2 / 0.8 = 4e-12 per parcel.
  EXPECT_NEAR(j.at("mann_prediction").at(0).at("t").get<double>(), 2.0, 1e-15);
  EXPECT_NEAR(j.at("mann_prediction").at(0).at("mean").get<double>(), 4e-12, 1e-24);
  const auto& pl = j.at("never_entered_places");
  EXPECT_NEAR(pl.at("never_entered").at("mean_height_m").get<double>(), 0.002, 1e-15);
  EXPECT_NEAR(pl.at("others").at("mean_radius_m").get<double>(), 0.001, 1e-15);
  EXPECT_TRUE(j.at("cycles_cut_by_run").get<bool>());

  const std::string html = slurp(dir / "report" / "report.html");
  EXPECT_NE(html.find("Never reached the zone:</b> 2 of 4 parcels"), std::string::npos);
  EXPECT_NE(html.find("never reached the zone</td><td>2</td><td>2.0</td><td>10.0</td>"),
            std::string::npos)
      << "mean height 2.0 mm, 10.0 mm from the axis";
  EXPECT_NE(html.find("Hypothetical"), std::string::npos) << "cycles cut by the run are labelled";
  const std::string csv = slurp(dir / "report" / "zone_passes_per_parcel.csv");
  EXPECT_EQ(csv,
            "parcel_id,passes,time_in_zone_s,coating_in_passes_kg\n"
            "1,3,0.7,4e-12\n2,2,0.7,4e-12\n3,0,0,0\n4,0,0,0\n");

  // A run without the file says so and is reported as before.
  fs::remove(dir / kZonePassesFile);
  ASSERT_EQ(report.run(), 0) << report.log.str();
  EXPECT_FALSE(
      readJsonFile(dir / "report" / "report.json").at("zone_passes").at("recorded").get<bool>());
  EXPECT_NE(slurp(dir / "report" / "report.html").find("No pass statistics"), std::string::npos);
}

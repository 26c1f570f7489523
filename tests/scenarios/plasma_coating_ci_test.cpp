// The reduced plasma coating bed with the real solvers (OpenFOAM + LIGGGHTS through the
// orchestrator): the precursor mass balance closes to better than 0.01 %, every gram removed
// from the gas arrives on the particles, coating accrues only during the recorded passes through
// the coating zone, and the analytics and report are produced.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../orchestrator/tcp_relay.h"
#include "batch_command.h"
#include "cosim/analysis/files.h"
#include "cosim/analysis/particle_file.h"
#include "cosim/analysis/report.h"
#include "cosim/analysis/time_series.h"
#include "cosim/analysis/zone_pass_file.h"
#include "cosim/link/curve_keys.h"
#include "cosim/link/fields.h"
#include "cosim/link/peer_link.h"
#include "cosim/util/child_process.h"
#include "coupler.h"
#include "run_pack.h"
#include "scenario.h"
#include "step_retreat.h"

using namespace cosim::orchestrator;
namespace fs = std::filesystem;

namespace {
// The LIGGGHTS dumps of a run (dem/in.liggghts: particles/post/grains_<step>.dump): file names,
// and of one file its TIMESTEP and the positions by id.
std::set<std::string> dumpFiles(const fs::path& run) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(run / "particles" / "post"))
    names.insert(e.path().filename().string());
  return names;
}

long long dumpStep(const fs::path& file, std::map<long long, std::vector<double>>& position) {
  std::ifstream in(file);
  long long step = -1;
  std::string line;
  while (std::getline(in, line)) {
    if (line == "ITEM: TIMESTEP") {
      std::getline(in, line);
      step = std::stoll(line);
    } else if (line.rfind("ITEM: ATOMS id type x y z", 0) == 0) {
      while (std::getline(in, line)) {
        std::istringstream r(line);
        long long id = 0, type = 0;
        std::vector<double> x(3);
        if (r >> id >> type >> x[0] >> x[1] >> x[2]) position[id] = x;
      }
    }
  }
  return step;
}
// The row of a time series at `time` (a failure when there is none).
std::size_t rowAt(const cosim::analysis::TimeSeries& ts, double time) {
  const auto& times = ts.at("time");
  for (std::size_t r = 0; r < times.size(); ++r)
    if (std::fabs(times[r] - time) < 1e-9) return r;
  ADD_FAILURE() << "no row at t = " << time;
  return 0;
}

// The precursor's balance over a run (its totals): what the gas lost is what the parcels took and
// hold, to round-off, and what came in went out, stayed or was taken, to the run's tolerance.
void expectBalanceCloses(const std::map<std::string, double>& t) {
  const double in = t.at("precursor_in_kg");
  EXPECT_LT(std::fabs(t.at("precursor_removed_kg") - t.at("coating_credited_kg")), 1e-12 * in);
  EXPECT_LT(std::fabs(t.at("coating_on_particles_kg") - t.at("coating_credited_kg")), 1e-12 * in);
  EXPECT_LT(std::fabs(in - t.at("precursor_out_kg") - t.at("precursor_held_kg") -
                      t.at("precursor_removed_kg")),
            1e-4 * in);
}

// Waits (at most `seconds`) until the run in `run` writes a checkpoint while an earlier one is
// complete: the moment to aim a kill or a Ctrl-C at. False if the run ended first.
bool awaitCheckpointBeingWritten(const fs::path& run, cosim::util::ChildProcess& p,
                                 double seconds) {
  const auto t0 = std::chrono::steady_clock::now();
  while (p.running() &&
         std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < seconds) {
    bool complete = false, partial = false;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(run / "checkpoints", ec))
      (e.path().filename().string().rfind(".partial", 0) == 0 ? partial : complete) = true;
    if (complete && partial) return true;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  return false;
}

// The first step after a resume, at `time`, against the uninterrupted run's: the pressure drop and
// the precursor columns to 1e-11 (relative).
void expectFirstStepAgrees(const fs::path& full, const fs::path& resumed, double time) {
  const auto ta = cosim::analysis::readTimeSeries(full / "timeseries.csv");
  const auto tb = cosim::analysis::readTimeSeries(resumed / "timeseries.csv");
  const std::size_t ra = rowAt(ta, time), rb = rowAt(tb, time);
  for (const char* c : {"precursor_in", "precursor_out", "precursor_held", "precursor_removed",
                        "coated_mass", "pressure_drop"}) {
    const double va = ta.at(c)[ra], vb = tb.at(c)[rb];
    std::printf("first step after the resume: %s %.3g relative\n", c,
                std::fabs(va - vb) / std::max(std::fabs(va), 1e-300));
    EXPECT_LE(std::fabs(va - vb), 1e-11 * std::fabs(va)) << c << " at t = " << time;
  }
}

// The process `name` started by this one (the participants of an in-process Coupler), or 0.
pid_t childNamed(const std::string& name) {
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string pid = e.path().filename().string();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(e.path() / "stat");
    std::string line;
    std::getline(stat, line);
    const auto close = line.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream rest(line.substr(close + 2));
    char state = 0;
    long ppid = 0;
    rest >> state >> ppid;
    if (ppid != getpid()) continue;
    std::ifstream cmd(e.path() / "cmdline");
    std::string args((std::istreambuf_iterator<char>(cmd)), std::istreambuf_iterator<char>());
    if (args.find(name) != std::string::npos) return std::stoi(pid);
  }
  return 0;
}
}  // namespace

// The particle solver killed (SIGKILL) between two particle snapshots: the run stops as failed,
// and its records end at the same instant: particles.h5 gets the parcels as they were after the
// last step done, so each parcel's coating equals the coating of its passes in zone_passes.csv
// (before, the file ended at the last output time and the passes went on: 71 % apart on the
// default bed), which `cosim report` checks parcel by parcel.
TEST(PlasmaCoatingCi, AParticleSolverKilledMidRunLeavesRecordsThatAgree) {
  const fs::path out =
      fs::temp_directory_path() / ("cosim-plasma-kill-" + std::to_string(getpid()));
  fs::remove_all(out);
  RunOptions o;
  o.quiet = true;
  o.output = out / "run";
  Coupler c(loadScenario(fs::path(COSIM_SOURCE_DIR) / "scenarios/plasma-coating-bed/ci.yaml"), o);
  bool killed = false;
  c.on_step = [&](double t, const cosim::link::ParticleData&) {
    if (killed || t < 0.0255) return;  // between the snapshots at 0.02 and 0.03 s
    const pid_t victim = childNamed("cosim-liggghts");
    ASSERT_GT(victim, 0);
    ::kill(victim, SIGKILL);
    killed = true;
  };
  RunResult r = c.run();
  ASSERT_TRUE(killed);
  ASSERT_NE(r.exit_code, 0);
  const auto summary = cosim::analysis::readJsonFile(r.folder / "summary.json");
  EXPECT_EQ(summary.at("status"), "failed");

  cosim::analysis::ReportOptions ro;
  ro.runs = {r.folder};
  ro.output = out / "report";
  ro.plots = false;
  EXPECT_EQ(cosim::analysis::runReport(ro), 0);
  const auto report = cosim::analysis::readJsonFile(out / "report" / "report.json");
  const auto& zp = report.at("zone_passes");
  ASSERT_TRUE(zp.at("recorded").get<bool>());
  const double passes = zp.at("coating_in_passes_kg"), parcels = zp.at("coating_on_parcels_kg");
  ASSERT_GT(passes, 0.0);
  EXPECT_NEAR(parcels, passes, 1e-12 * passes);
  EXPECT_TRUE(zp.at("ledgers_agree").get<bool>()) << zp.value("ledger_problem", "");
  // The series' totals agree with the parcels too: coated mass (credited + owed) at the last row
  const auto ts = cosim::analysis::readTimeSeries(r.folder / "timeseries.csv");
  const double coated = ts.at("coated_mass").back();
  EXPECT_NEAR(coated, parcels, 1e-12 * parcels);
  fs::remove_all(out);
}

TEST(PlasmaCoatingCi, MassBalanceClosesAndReportIsProduced) {
  const fs::path out = fs::temp_directory_path() / ("cosim-plasma-ci-" + std::to_string(getpid()));
  fs::remove_all(out);
  Scenario sc = loadScenario(fs::path(COSIM_SOURCE_DIR) / "scenarios/plasma-coating-bed/ci.yaml");
  RunOptions o;
  o.quiet = true;
  o.output = out;
  Coupler c(std::move(sc), o);
  RunResult r = c.run();
  ASSERT_EQ(r.exit_code, 0) << r.message;

  const double in = r.totals.at("precursor_in_kg");
  const double outflow = r.totals.at("precursor_out_kg");
  const double held = r.totals.at("precursor_held_kg");
  const double removed = r.totals.at("precursor_removed_kg");
  const double credited = r.totals.at("coating_credited_kg");
  const double on_particles = r.totals.at("coating_on_particles_kg");
  ASSERT_GT(in, 0.0);
  // The gas balance (paper Table 3): expected coating = in - out - accumulation.
  const double expected = in - outflow - held;
  EXPECT_LT(std::fabs(expected - removed), 1e-4 * in)
      << "in " << in << " out " << outflow << " held " << held << " removed " << removed;
  // What left the gas is what the particles received.
  EXPECT_NEAR(credited, removed, 1e-12 * std::max(removed, 1e-30));
  EXPECT_NEAR(on_particles, credited, 1e-9 * std::max(credited, 1e-30));
  EXPECT_GT(removed, 0.0) << "no coating in the CI run: the zone or the feed is wrong";

  // A miniature of the real bed, not grains resting in the bottom cell: 1500 parcels of 1.5 mm
  // over the 20 x 20 mm plate less the 4 x 4 mm nozzle at a packed voidage of about 0.42 make a
  // bed 1500 * pi/6 * (1.5e-3)^3 / ((0.02^2 - 0.004^2) * 0.58) = 11.9 mm deep, three 4 mm cells.
  // Fluidized at 0.21 m/s (about 3 u_mf) with the jet through its centre, a real share of the
  // parcels passes the afterglow within 0.05 s.
  const auto& x = r.final_state.get(cosim::field::position);
  const auto& m = r.final_state.get(cosim::field::coating_mass);
  const std::size_t n = r.final_state.size();
  ASSERT_EQ(n, 1500u);
  std::vector<double> z;
  std::size_t coated = 0;
  for (std::size_t i = 0; i < n; ++i) {
    z.push_back(x[3 * i + 2]);
    coated += m[i] > 0.0 ? 1 : 0;
  }
  std::sort(z.begin(), z.end());
  const double z90 = z[n * 9 / 10];
  std::printf("CI bed: 90th percentile of parcel height %.2f mm, coated %.1f %% of the parcels\n",
              1e3 * z90, 100.0 * double(coated) / double(n));
  EXPECT_GT(z90, 0.008) << "the bed must span more than two cells";
  EXPECT_GT(double(coated), 0.08 * double(n)) << "too few parcels pass the coating zone";
  EXPECT_LT(coated, n) << "every parcel coated in 0.05 s: the zone covers the whole bed";

  // The passes through the coating zone (zone_passes.csv). The fluid's sink removes
  // k_i dt Y_i from parcel i over a step, and the orchestrator gives k_i = 0 to every parcel
  // outside the zone at the step's start: coating accrues only in the zone. So every parcel with
  // coating has a pass, every parcel without a pass has exactly the coating it started with (0),
  // and each parcel's coating is the sum of its passes' coating.
  const auto passes = cosim::analysis::readZonePasses(r.folder / cosim::analysis::kZonePassesFile);
  ASSERT_FALSE(passes.empty());
  std::map<std::int64_t, double> inPasses;
  std::map<std::int64_t, int> count;
  for (const auto& p : passes) {
    EXPECT_LT(p.entry_time, p.exit_time) << "parcel " << p.parcel_id;
    EXPECT_GE(p.entry_time, 0.0);
    EXPECT_LE(p.exit_time, 0.05 + 1e-12);
    // Whole coupling steps of 1e-4 s.
    EXPECT_NEAR(p.duration() / 1e-4, std::round(p.duration() / 1e-4), 1e-6);
    inPasses[p.parcel_id] += p.coating;
    ++count[p.parcel_id];
  }
  std::size_t withPass = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto id = r.final_state.ids[i];
    if (count.count(id) == 0) {
      EXPECT_EQ(m[i], 0.0) << "parcel " << id << " has coating but never was in the zone";
      continue;
    }
    ++withPass;
    EXPECT_NEAR(m[i], inPasses[id], 1e-12 * std::max(m[i], 1e-30)) << "parcel " << id;
  }
  EXPECT_GE(withPass, coated) << "a coated parcel without a pass";
  std::printf("CI bed: %zu passes of %zu parcels; %zu parcels never in the zone\n", passes.size(),
              withPass, n - withPass);

  // The LIGGGHTS dumps are on the run's clock: one at t = 0 and one every write_interval
  // (0.05 s = 10,000 DEM steps of 5e-6 s), named and stamped with the step counted from the start
  // of the coupling (not of the 0.1 s of settling before it); the last one, at the final time,
  // holds the parcels where the run ended (to the dump's 6 significant digits).
  EXPECT_EQ(dumpFiles(r.folder), (std::set<std::string>{"grains_0.dump", "grains_10000.dump"}));
  std::map<long long, std::vector<double>> dumped;
  EXPECT_EQ(dumpStep(r.folder / "particles/post/grains_10000.dump", dumped), 10000);
  ASSERT_EQ(dumped.size(), n);
  double dx = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& d = dumped[r.final_state.ids[i]];
    for (int c = 0; c < 3; ++c) dx = std::max(dx, std::fabs(d[c] - x[3 * i + c]));
  }
  EXPECT_LT(dx, 1e-6) << "final dump against the final state [m]";

  // Analytics and report.
  cosim::analysis::ReportOptions ro;
  ro.runs = {r.folder};
  ro.output = out / "report";
  ro.plots = true;
  EXPECT_EQ(cosim::analysis::runReport(ro), 0);
  EXPECT_TRUE(fs::exists(out / "report" / "report.html"));
  EXPECT_TRUE(fs::exists(out / "report" / "report.json"));
  const auto report = cosim::analysis::readJsonFile(out / "report" / "report.json");
  const auto& zp = report.at("zone_passes");
  ASSERT_TRUE(zp.at("recorded").get<bool>());
  EXPECT_EQ(zp.at("passes").get<std::size_t>(), passes.size());
  EXPECT_EQ(zp.at("never_entered").get<std::size_t>(), n - withPass);
  EXPECT_TRUE(fs::exists(out / "report" / "zone_passes_per_parcel.csv"));

  // The whole batch from this record (cosim batch): at the record's end the record's own
  // statistics; later the mean grows and the never-coated share falls, never the other way; and
  // the model says that 0.05 s of record cannot hold this bed's slow motion.
  BatchOptions bo;
  bo.run = r.folder.string();
  bo.until = 60.0;
  std::ostringstream said, errs;
  ASSERT_EQ(runBatchCommand(bo, said, errs), 0) << errs.str();
  std::printf("%s", said.str().c_str());
  const auto batch = cosim::analysis::readJsonFile(r.folder / "batch" / "batch.json");
  const auto& points = batch.at("points");
  ASSERT_GE(points.size(), 3u);
  EXPECT_NEAR(points[0].at("mean_kg").get<double>(), on_particles / double(n),
              1e-9 * on_particles / double(n));
  EXPECT_NEAR(points[0].at("never_coated_share").get<double>(), 1.0 - double(coated) / double(n),
              1e-12);
  for (std::size_t i = 1; i < points.size(); ++i) {
    EXPECT_GE(points[i].at("mean_kg").get<double>(), points[i - 1].at("mean_kg").get<double>());
    EXPECT_LE(points[i].at("never_coated_share").get<double>(),
              points[i - 1].at("never_coated_share").get<double>());
  }
  EXPECT_FALSE(batch.at("long_time_model").at("warnings").empty());
  EXPECT_TRUE(fs::exists(r.folder / "batch" / "batch.csv"));
  // --step must be a whole number of the record's interval: refused, naming the two nearest
  {
    BatchOptions odd = bo;
    odd.step = 1.5 * batch.at("long_time_model").at("interval_s").get<double>();
    odd.output = (out / "batch-odd-step").string();
    std::ostringstream said_odd, errs_odd;
    EXPECT_EQ(runBatchCommand(odd, said_odd, errs_odd), 1);
    EXPECT_NE(errs_odd.str().find("--step"), std::string::npos) << errs_odd.str();
    EXPECT_NE(errs_odd.str().find("whole number of the record's interval"), std::string::npos)
        << errs_odd.str();
  }

  // The model held against the rest of its own run (--to): fitted on the record's first half,
  // its prediction beside the run's later snapshots; the last of them is the record's end, whose
  // statistics the batch above read from the record itself.
  const double end = points[0].at("time_s").get<double>();
  BatchOptions half = bo;
  half.to = 0.5 * end;
  half.output = (out / "batch-check").string();
  std::ostringstream said2, errs2;
  ASSERT_EQ(runBatchCommand(half, said2, errs2), 0) << errs2.str();
  std::printf("%s", said2.str().c_str());
  const auto checked = cosim::analysis::readJsonFile(out / "batch-check" / "batch.json");
  ASSERT_TRUE(checked.contains("check"));
  const auto& rows = checked.at("check").at("rows");
  ASSERT_FALSE(rows.empty());
  EXPECT_NEAR(rows.back().at("time_s").get<double>(), end, 1e-9);
  EXPECT_NEAR(rows.back().at("run").at("mean_kg").get<double>(),
              points[0].at("mean_kg").get<double>(), 1e-12 * points[0].at("mean_kg").get<double>());
  EXPECT_NEAR(rows.back().at("run").at("never_coated_share").get<double>(),
              points[0].at("never_coated_share").get<double>(), 1e-12);
  EXPECT_EQ(checked.at("check").at("parcels").get<std::size_t>(), n);
  // the report holds the same check on the record's second half, for each grid of compartments
  // it tried, and uses one of them
  const auto& model = report.at("batch_model");
  const auto& trials = model.at("check_on_second_half");
  ASSERT_FALSE(trials.empty()) << model.dump();
  // and the check on held-out parcels over the whole record, ending at the record's end; the
  // model used is the trial with the least distance among those that settle to the record's rate
  bool used = false;
  double least = std::numeric_limits<double>::infinity(), used_distance = -1;
  for (const auto& t : trials) {
    EXPECT_NEAR(t.at("rows").back().at("run").at("mean_kg").get<double>(),
                points[0].at("mean_kg").get<double>(),
                1e-12 * points[0].at("mean_kg").get<double>());
    EXPECT_LT(t.at("record_to_s").get<double>(), end);
    ASSERT_TRUE(t.contains("held_out_parcels")) << t.dump();
    const auto& held = t.at("held_out_parcels").at("rows").back();
    EXPECT_NEAR(held.at("time_s").get<double>(), end, 1e-9);
    EXPECT_NEAR(held.at("run").at("mean_kg").get<double>(), points[0].at("mean_kg").get<double>(),
                1e-12 * points[0].at("mean_kg").get<double>());
    const double distance = t.at("distance").get<double>();
    if (!t.at("settles_off").get<bool>()) least = std::min(least, distance);
    const bool this_one =
        t.at("rings") == model.at("rings") && t.at("layers") == model.at("layers") &&
        std::fabs(t.at("step_s").get<double>() - model.at("step_s").get<double>()) < 1e-9;
    if (this_one) used_distance = distance;
    used = used || this_one;
  }
  EXPECT_TRUE(used);
  if (std::isfinite(least)) EXPECT_DOUBLE_EQ(used_distance, least);
}

// Resume with the real solvers (docs/restarts.md): the bed run to 0.05 s with checkpoints every
// 0.01 s, its folder cut back to the checkpoint at 0.03 s (as after a kill), resumed. The
// orchestrator's state comes back exactly (the balance closes across the restart), and so does the
// particles' (the resume checks its digest bit for bit, or stops). The fluid's
// checkpoint carries the last step's voidage and eps rho, so the first step after the resume has
// the parcels' displacement flow as in the uninterrupted run, and LIGGGHTS starts from the forces
// and torques the step would have started from: its row of the time series agrees to round-off
// (measured at commit time: 1.4e-12 relative in the pressure drop, 1e-15 in the rest). From there
// round-off grows as the bed's contacts amplify it: at 0.05 s, measured 2e-8 to 2.5e-7 relative in
// the coated mass and 1.1e-6 to 1.6e-6 m in the parcels' positions (before the checkpoint held
// those fields: 1.6e-4 and 1.8e-5 m).
TEST(PlasmaCoatingCi, ResumedFromACheckpointAgreesWithTheUninterruptedRun) {
  const fs::path base =
      fs::temp_directory_path() / ("cosim-plasma-resume-" + std::to_string(getpid()));
  fs::remove_all(base);
  // The scene's own scheme (overlapped): the checkpoint keeps where the fluid sampled the gas
  // ahead for the next interval, and the resumed run samples it there first
  ASSERT_EQ(loadScenario(fs::path(COSIM_SOURCE_DIR) / "scenarios/plasma-coating-bed/ci.yaml")
                .coupling.scheme,
            "overlapped");
  const std::vector<std::string> sets = {"checkpoint.interval=0.01"};
  const fs::path scene = fs::path(COSIM_SOURCE_DIR) / "scenarios/plasma-coating-bed/ci.yaml";
  RunOptions o;
  o.quiet = true;
  o.output = base / "full";
  RunResult full = Coupler(loadScenario(scene, sets), o).run();
  ASSERT_EQ(full.exit_code, 0) << full.message;
  ASSERT_TRUE(fs::exists(base / "full/checkpoints/0.03/orchestrator.json"));

  fs::copy(base / "full", base / "cut", fs::copy_options::recursive);
  fs::remove_all(base / "cut/checkpoints/0.04");
  fs::remove_all(base / "cut/checkpoints/0.05");
  fs::remove(base / "cut/particles/post/grains_10000.dump");  // written after 0.03 s
  RunOptions ro;
  ro.quiet = true;
  ro.resume = base / "cut";
  RunResult resumed = Coupler(loadScenario(scene, sets), ro).run();
  ASSERT_EQ(resumed.exit_code, 0) << resumed.message;
  EXPECT_EQ(resumed.steps, full.steps);

  const auto& t = resumed.totals;
  expectBalanceCloses(t);
  const double coated = full.totals.at("coating_credited_kg");
  EXPECT_NEAR(t.at("coating_credited_kg"), coated, 2e-6 * coated);

  // The first step after the resume (t = 0.0301 s) as the uninterrupted run's, to round-off
  expectFirstStepAgrees(base / "full", base / "cut", 0.0301);
  const auto ta = cosim::analysis::readTimeSeries(base / "full/timeseries.csv");
  // Writing a checkpoint barely changes the run: the step after the one at 0.01 s against a run
  // without checkpoints. LIGGGHTS re-initialises at write_restart; the forces and torques the
  // next step starts from are kept (before: 1e-5 relative in that step's pressure drop), what
  // remains is 1e-7 (measured at commit time)
  {
    RunOptions no;
    no.quiet = true;
    no.output = base / "no-checkpoints";
    RunResult plain = Coupler(loadScenario(scene, {"coupling.end_time=0.0102"}), no).run();
    ASSERT_EQ(plain.exit_code, 0) << plain.message;
    const auto tp = cosim::analysis::readTimeSeries(base / "no-checkpoints/timeseries.csv");
    const double pa = ta.at("pressure_drop")[rowAt(ta, 0.0102)];
    const double pp = tp.at("pressure_drop")[rowAt(tp, 0.0102)];
    std::printf("step after a checkpoint vs no checkpoint: pressure drop %.3g relative\n",
                std::fabs(pa - pp) / pp);
    EXPECT_LE(std::fabs(pa - pp), 5e-7 * std::fabs(pp));
  }

  const auto& a = full.final_state;
  const auto& b = resumed.final_state;
  ASSERT_EQ(a.ids, b.ids);
  const auto& xa = a.get(cosim::field::position);
  const auto& xb = b.get(cosim::field::position);
  double dx = 0.0;
  for (std::size_t i = 0; i < xa.size(); ++i) dx = std::max(dx, std::fabs(xa[i] - xb[i]));
  const double dm = std::fabs(t.at("coating_credited_kg") - coated) / coated;
  std::printf("resumed vs uninterrupted: coated mass %.3g relative, positions %.3g m\n", dm, dx);
  EXPECT_LT(dx, 5e-6) << "largest position difference [m]";

  // The passes continue across the restart (the open ones are part of the checkpoint): each
  // parcel's coating is still the sum of its passes', and a parcel without a pass has none.
  std::map<std::int64_t, double> inPasses;
  for (const auto& p : cosim::analysis::readZonePasses(base / "cut" / "zone_passes.csv")) {
    EXPECT_LT(p.entry_time, p.exit_time);
    inPasses[p.parcel_id] += p.coating;
  }
  const auto& mb = b.get(cosim::field::coating_mass);
  for (std::size_t i = 0; i < b.size(); ++i) {
    const auto it = inPasses.find(b.ids[i]);
    if (it == inPasses.end()) {
      EXPECT_EQ(mb[i], 0.0) << "parcel " << b.ids[i];
    } else {
      EXPECT_NEAR(mb[i], it->second, 1e-12 * mb[i]) << "parcel " << b.ids[i];
    }
  }
  // The resumed run's dumps carry on the run's clock: the same files as the uninterrupted run's,
  // the final one written again by the resumed run at step 10,000 (t = 0.05 s).
  EXPECT_EQ(dumpFiles(base / "cut"), dumpFiles(base / "full"));
  std::map<long long, std::vector<double>> dumped;
  EXPECT_EQ(dumpStep(base / "cut/particles/post/grains_10000.dump", dumped), 10000);
  EXPECT_EQ(dumped.size(), b.size());

  // The same checkpoint resumed with half the coupling step (10 DEM steps of the same 5e-6 s
  // each), as through a stiff stretch: LIGGGHTS and OpenFOAM continue on the run's clock (its
  // steps done keep their times, 400 steps of 0.05 ms follow), the balance closes as before
  fs::copy(base / "full", base / "finer", fs::copy_options::recursive);
  fs::remove_all(base / "finer/checkpoints/0.04");
  fs::remove_all(base / "finer/checkpoints/0.05");
  fs::remove(base / "finer/particles/post/grains_10000.dump");
  RunOptions fo;
  fo.quiet = true;
  fo.resume = base / "finer";
  RunResult finer =
      Coupler(loadRunScene(base / "finer", {"coupling.dt=5e-5", "coupling.dem_steps=10"}), fo)
          .run();
  ASSERT_EQ(finer.exit_code, 0) << finer.message;
  EXPECT_EQ(finer.steps, 300u + 400u);
  const auto& f = finer.totals;
  expectBalanceCloses(f);
  const auto tf = cosim::analysis::readTimeSeries(base / "finer/timeseries.csv");
  EXPECT_EQ(tf.at("time")[rowAt(tf, 0.03005)], 0.03005);
  EXPECT_EQ(tf.at("time").back(), 0.05);
  // LIGGGHTS went the same DEM steps to 0.05 s, OpenFOAM wrote its time there
  dumped.clear();
  EXPECT_EQ(dumpStep(base / "finer/particles/post/grains_10000.dump", dumped), 10000);
  EXPECT_EQ(dumped.size(), finer.final_state.size());
  const double df = std::fabs(f.at("coating_credited_kg") - coated) / coated;
  std::printf(
      "half the coupling step from 0.03 s vs the run at 0.1 ms: coated mass %.3g relative\n", df);
  EXPECT_LT(df, 1e-3) << "half the step moved the coated mass by 1.8e-4 (measured at commit time)";
  fs::remove_all(base);
}

// checks.step_halvings with the real solvers (docs/restarts.md, "Through a stiff stretch by
// itself"): the CI bed's gas runs at a Courant number of 0.1-0.2 at the scene's 0.1 ms (its jet
// alone about 0.15), so a limit of 0.11 stops the 0.1 ms steps now and then and lets the 0.05 ms
// ones through (as in a stiff stretch where half the step is enough). Resumed from 0.02 s to
// 0.04 s, the run goes back to its newest checkpoint at each stop and on at 0.05 ms to the first
// checkpoint half an interval past the stop, then at 0.1 ms again: it ends at 0.04 s with every
// step after a stop at 0.05 ms, the balance closed. Far below the half step's Courant number
// (0.03) one halving is not enough: the run stops, saying so and how to go on as the scene was.
TEST(PlasmaCoatingCi, AStiffStretchIsGoneThroughWithHalfTheStepByItself) {
  const fs::path base =
      fs::temp_directory_path() / ("cosim-plasma-halve-" + std::to_string(getpid()));
  fs::remove_all(base);
  const fs::path scene = fs::path(COSIM_SOURCE_DIR) / "scenarios/plasma-coating-bed/ci.yaml";
  RunOptions o;
  o.quiet = true;
  o.output = base / "run";
  const RunResult first =
      Coupler(loadScenario(scene, {"checkpoint.interval=0.01", "coupling.end_time=0.02"}), o).run();
  ASSERT_EQ(first.exit_code, 0) << first.message;
  fs::copy(base / "run", base / "too-stiff", fs::copy_options::recursive);

  RunOptions ro;
  ro.quiet = true;
  ro.resume = base / "run";
  const RunResult r = runThroughStiffStretches(
      loadRunScene(base / "run",
                   {"coupling.end_time=0.04", "checks.max_courant=0.11", "checks.step_halvings=1"}),
      ro);
  ASSERT_EQ(r.exit_code, 0) << r.message;
  EXPECT_EQ(r.time, 0.04);
  // A row a step: each at 0.1 ms or 0.05 ms after the one before, some at 0.05 ms, every one on
  // the 0.05 ms grid, the steps those of the rows
  const auto ts = cosim::analysis::readTimeSeries(base / "run/timeseries.csv");
  std::size_t after = 0, half = 0;
  double before = 0.02;
  for (double t : ts.at("time")) {
    if (t <= 0.02) continue;
    ++after;
    EXPECT_NEAR(t / 5e-5, std::round(t / 5e-5), 1e-6) << "a row at " << t;
    const double step = t - before;
    EXPECT_TRUE(std::fabs(step - 5e-5) < 1e-9 || std::fabs(step - 1e-4) < 1e-9)
        << "a step of " << step << " s before " << t;
    if (std::fabs(step - 5e-5) < 1e-9) ++half;
    before = t;
  }
  EXPECT_EQ(r.steps, 200u + after);
  EXPECT_GE(half, 100u) << "no stretch at half the step";
  expectBalanceCloses(r.totals);
  EXPECT_EQ(cosim::analysis::readJsonFile(base / "run/summary.json").at("status"), "completed");
  {  // each change of step is in the run's log
    std::ifstream in(base / "run/cosim.log");
    const std::string log((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(log.find("with a coupling step of 5e-05 s to"), std::string::npos) << log;
  }

  ro.resume = base / "too-stiff";
  const RunResult stiff = runThroughStiffStretches(
      loadRunScene(base / "too-stiff",
                   {"coupling.end_time=0.04", "checks.max_courant=0.03", "checks.step_halvings=1"}),
      ro);
  EXPECT_NE(stiff.exit_code, 0);
  EXPECT_NE(stiff.message.find("halved 1 times in a row and the run still stopped"),
            std::string::npos)
      << stiff.message;
  EXPECT_NE(stiff.message.find("--set coupling.dt=0.0001 --set coupling.dem_steps=20 --set "
                               "coupling.end_time=0.04"),
            std::string::npos)
      << stiff.message;
  fs::remove_all(base);
}

// cosim pack with the real solvers (docs/restarts.md, "Moving a run"): the bed run to 0.02 s with
// checkpoints every 0.01 s, packed (its fluid time folders, dumps and logs left out), and both the
// copy and the run itself resumed to 0.03 s from that checkpoint: the copy continues exactly as
// the run does (the same time series rows to the bit, the same final particle state), so what
// pack leaves out is not needed to continue.
TEST(PlasmaCoatingCi, APackedCopyContinuesAsTheRunItself) {
  const fs::path base =
      fs::temp_directory_path() / ("cosim-plasma-pack-" + std::to_string(getpid()));
  fs::remove_all(base);
  const fs::path scene = fs::path(COSIM_SOURCE_DIR) / "scenarios/plasma-coating-bed/ci.yaml";
  const std::vector<std::string> sets = {"checkpoint.interval=0.01", "coupling.end_time=0.02",
                                         "coupling.scheme=parallel", "write_interval=0.01"};
  RunOptions o;
  o.quiet = true;
  o.output = base / "run";
  RunResult first = Coupler(loadScenario(scene, sets), o).run();
  ASSERT_EQ(first.exit_code, 0) << first.message;
  ASSERT_TRUE(fs::exists(base / "run/fluid/0.01")) << "the fluid writes a time folder at 0.01 s";
  ASSERT_FALSE(dumpFiles(base / "run").empty());

  const PackResult p = packRun(base / "run", base / "moved", loadRunScene(base / "run"));
  EXPECT_EQ(p.checkpoint.filename(), "0.02");
  EXPECT_GT(p.left_out.at("older checkpoints"), 0u);
  EXPECT_GT(p.left_out.at("the fluid's time folders after the first"), 0u);
  EXPECT_GT(p.left_out.at("the particles' dump files"), 0u);
  EXPECT_FALSE(fs::exists(base / "moved/fluid/0.01"));
  EXPECT_TRUE(fs::exists(base / "moved/fluid/0"));
  EXPECT_TRUE(fs::exists(base / "moved/fluid/constant/polyMesh"));
  EXPECT_TRUE(fs::exists(base / "run/fluid/0.01")) << "pack changed the run folder";

  const std::vector<std::string> longer = {"coupling.end_time=0.03"};
  RunOptions ra;
  ra.quiet = true;
  ra.resume = base / "run";
  RunResult a = Coupler(loadRunScene(base / "run", longer), ra).run();
  ASSERT_EQ(a.exit_code, 0) << a.message;
  RunOptions rb;
  rb.quiet = true;
  rb.resume = base / "moved";
  RunResult b = Coupler(loadRunScene(base / "moved", longer), rb).run();
  ASSERT_EQ(b.exit_code, 0) << b.message;

  const auto ta = cosim::analysis::readTimeSeries(base / "run/timeseries.csv");
  const auto tb = cosim::analysis::readTimeSeries(base / "moved/timeseries.csv");
  ASSERT_EQ(ta.rows(), tb.rows());
  for (const auto& c : ta.columns) {
    if (c == "wall_seconds") continue;
    for (std::size_t r = 0; r < ta.rows(); ++r) {
      const double x = ta.at(c)[r], y = tb.at(c)[r];
      if (std::isnan(x) && std::isnan(y)) continue;
      ASSERT_EQ(x, y) << c << " row " << r;
    }
  }
  ASSERT_EQ(a.final_state.ids, b.final_state.ids);
  for (const char* f : {cosim::field::position, cosim::field::velocity, cosim::field::coating_mass})
    EXPECT_EQ(a.final_state.get(f), b.final_state.get(f)) << f;
  EXPECT_EQ(a.totals.at("coating_credited_kg"), b.totals.at("coating_credited_kg"));
  fs::remove_all(base);
}

// The same with the fluid decomposed over 2 MPI ranks: each rank's time folder is in the
// checkpoint (fluid/processorN/<time>) and comes back; the first step after the resume agrees with
// the uninterrupted run's to round-off (measured at commit time: 1e-15 relative) and the precursor
// balance closes across the restart.
TEST(PlasmaCoatingCi, DecomposedFluidResumesToRoundOff) {
  const fs::path base =
      fs::temp_directory_path() / ("cosim-plasma-mpi-resume-" + std::to_string(getpid()));
  fs::remove_all(base);
  const std::vector<std::string> sets = {"checkpoint.interval=0.01", "participants.fluid.mpi=2",
                                         "coupling.end_time=0.02", "coupling.scheme=parallel"};
  const fs::path scene = fs::path(COSIM_SOURCE_DIR) / "scenarios/plasma-coating-bed/ci.yaml";
  RunOptions o;
  o.quiet = true;
  o.output = base / "full";
  RunResult full = Coupler(loadScenario(scene, sets), o).run();
  ASSERT_EQ(full.exit_code, 0) << full.message;
  for (const char* rank : {"processor0", "processor1"})
    ASSERT_TRUE(fs::exists(base / "full/checkpoints/0.01/fluid" / rank / "0.01" / "epsRho"))
        << rank;

  fs::copy(base / "full", base / "cut", fs::copy_options::recursive);
  fs::remove_all(base / "cut/checkpoints/0.02");
  RunOptions ro;
  ro.quiet = true;
  ro.resume = base / "cut";
  RunResult resumed = Coupler(loadScenario(scene, sets), ro).run();
  ASSERT_EQ(resumed.exit_code, 0) << resumed.message;
  EXPECT_EQ(resumed.steps, full.steps);

  EXPECT_EQ(cosim::analysis::readTimeSeries(base / "full/timeseries.csv").rows(),
            cosim::analysis::readTimeSeries(base / "cut/timeseries.csv").rows());
  expectFirstStepAgrees(base / "full", base / "cut", 0.0101);
  const auto& t = resumed.totals;
  const double in = t.at("precursor_in_kg");
  EXPECT_LT(std::fabs(t.at("coating_on_particles_kg") - t.at("coating_credited_kg")), 1e-12 * in);
  EXPECT_LT(std::fabs(in - t.at("precursor_out_kg") - t.at("precursor_held_kg") -
                      t.at("precursor_removed_kg")),
            1e-4 * in);
  fs::remove_all(base);
}

// coupling.scheme: overlapped (the fluid samples the gas during its own step, at position +
// velocity dt) against the parallel scheme on the same CI bed. The precursor balance must close
// exactly as before: the fluid's voidage, sink and samples all follow the one placement it made.
// The coating differs only by where the parcels were placed (a dt^2 effect) and the divergence of
// two chaotic bed histories; measured 0.12 % after 0.05 s (commit of this test).
TEST(PlasmaCoatingCi, OverlappedSchemeKeepsTheBalanceAndAgreesWithParallel) {
  const fs::path scene = fs::path(COSIM_SOURCE_DIR) / "scenarios/plasma-coating-bed/ci.yaml";
  const fs::path base =
      fs::temp_directory_path() / ("cosim-plasma-scheme-" + std::to_string(getpid()));
  fs::remove_all(base);
  std::map<std::string, RunResult> runs;
  for (const std::string scheme : {"parallel", "overlapped"}) {
    RunOptions o;
    o.quiet = true;
    o.output = base / scheme;
    runs[scheme] = Coupler(loadScenario(scene, {"coupling.scheme=" + scheme}), o).run();
    ASSERT_EQ(runs[scheme].exit_code, 0) << runs[scheme].message;
  }
  const auto& t = runs["overlapped"].totals;
  const double in = t.at("precursor_in_kg");
  const double removed = t.at("precursor_removed_kg");
  EXPECT_LT(std::fabs(in - t.at("precursor_out_kg") - t.at("precursor_held_kg") - removed),
            1e-4 * in);
  EXPECT_NEAR(t.at("coating_credited_kg"), removed, 1e-12 * removed);
  EXPECT_NEAR(t.at("coating_on_particles_kg"), removed, 1e-9 * removed);
  const double parallel = runs["parallel"].totals.at("coating_credited_kg");
  EXPECT_NEAR(t.at("coating_credited_kg"), parallel, 5e-3 * parallel);
  // The fluid sampled during its steps (Advanced.ahead)
  const auto summary =
      nlohmann::json::parse(std::ifstream(runs["overlapped"].folder / "summary.json"));
  EXPECT_GT(summary.at("timings_s").at("fluid_sample_ahead_compute").get<double>(), 0.0);
  fs::remove_all(base);
}

// Ctrl-C while LIGGGHTS pours and settles the bed (before the first step, with no step to finish):
// cosim stops at once, not after the settling, with status interrupted and exit code 130, its
// participants gone. The settling here is made long (2 s of DEM at 5e-6 s, minutes of wall time)
// so that the run could only stop in time by not waiting for it.
TEST(PlasmaCoatingCi, CtrlCDuringTheSettlingStopsAtOnce) {
  const fs::path out =
      fs::temp_directory_path() / ("cosim-plasma-ctrlc-" + std::to_string(getpid()));
  fs::remove_all(out);
  fs::create_directories(out);
  cosim::util::ChildProcess run(
      {std::string(COSIM_BINARY_DIR) + "/cosim", "run",
       std::string(COSIM_SOURCE_DIR) + "/scenarios/plasma-coating-bed/ci.yaml", "-o",
       (out / "run").string(), "--set", "settle_time=2"},
      out, out / "run.out", {});
  // LIGGGHTS is settling once its log shows its first thermo rows
  for (int i = 0; i < 600; ++i) {
    std::ifstream log(out / "run" / "particles" / "liggghts.log");
    const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
    if (text.find("KinEng") != std::string::npos) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  std::this_thread::sleep_for(std::chrono::seconds(1));
  ASSERT_TRUE(run.running());
  const auto t0 = std::chrono::steady_clock::now();
  ::kill(run.pid(), SIGINT);
  const int code = run.wait();
  const double waited =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("Ctrl-C during the settling: cosim stopped after %.2f s\n", waited);
  EXPECT_EQ(code, 130);
  EXPECT_LT(waited, 20.0) << "cosim waited for the settling to end";
  const auto summary = cosim::analysis::readJsonFile(out / "run" / "summary.json");
  EXPECT_EQ(summary.at("status"), "interrupted");
  // no participant left running in the run's folders
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  for (const auto& e : fs::directory_iterator("/proc")) {
    std::error_code ec;
    const auto cwd = fs::read_symlink(e.path() / "cwd", ec);
    if (!ec) EXPECT_EQ(cwd.string().rfind(out.string(), 0), std::string::npos) << e.path();
  }
  fs::remove_all(out);
}

// LIGGGHTS on two MPI ranks (dem_ranks 2) with the coating bed and its own scheme: run to 0.03 s
// with checkpoints every 0.01 s, the folder cut back to 0.02 s, resumed. The first step after the
// resume agrees with the uninterrupted run's to round-off in the pressure drop and the precursor
// columns, as on one rank; each parcel's coating stays the sum of its passes.
TEST(PlasmaCoatingCi, ResumedOnTwoParticleRanksAgreesToRoundOff) {
  const fs::path base =
      fs::temp_directory_path() / ("cosim-plasma-2ranks-" + std::to_string(getpid()));
  fs::remove_all(base);
  const fs::path scene = fs::path(COSIM_SOURCE_DIR) / "scenarios/plasma-coating-bed/ci.yaml";
  const std::vector<std::string> sets = {"checkpoint.interval=0.01", "coupling.end_time=0.03",
                                         "dem_ranks=2"};
  RunOptions o;
  o.quiet = true;
  o.output = base / "full";
  RunResult full = Coupler(loadScenario(scene, sets), o).run();
  ASSERT_EQ(full.exit_code, 0) << full.message;
  fs::copy(base / "full", base / "cut", fs::copy_options::recursive);
  fs::remove_all(base / "cut/checkpoints/0.03");
  RunOptions ro;
  ro.quiet = true;
  ro.resume = base / "cut";
  RunResult resumed = Coupler(loadScenario(scene, sets), ro).run();
  ASSERT_EQ(resumed.exit_code, 0) << resumed.message;
  expectFirstStepAgrees(base / "full", base / "cut", 0.0201);
  std::map<std::int64_t, double> inPasses;
  for (const auto& p : cosim::analysis::readZonePasses(base / "cut" / "zone_passes.csv"))
    inPasses[p.parcel_id] += p.coating;
  const auto& b = resumed.final_state;
  const auto& mb = b.get(cosim::field::coating_mass);
  for (std::size_t i = 0; i < b.size(); ++i) {
    const auto it = inPasses.find(b.ids[i]);
    EXPECT_NEAR(mb[i], it == inPasses.end() ? 0.0 : it->second, 1e-12 * mb[i]) << b.ids[i];
  }
  fs::remove_all(base);
}

// cosim itself killed with SIGKILL five times (once while it writes a checkpoint, once right after
// a particle snapshot appeared, three times at random moments), resumed after each: the records
// of the whole run pass every ledger check. The precursor balance closes and what left the gas
// is on the parcels to round-off; each parcel's coating is the sum of its passes (report); the
// snapshots are the output times, each once; each parcel's passes follow each other without
// overlap; the time series has one row per step; summary.json is complete.
TEST(PlasmaCoatingCi, KilledFiveTimesAndResumedTheRecordsAgree) {
  const fs::path base =
      fs::temp_directory_path() / ("cosim-plasma-kills-" + std::to_string(getpid()));
  fs::remove_all(base);
  fs::create_directories(base);
  const fs::path run = base / "run";
  const std::string cosim = std::string(COSIM_BINARY_DIR) + "/cosim";
  const std::vector<std::string> sets = {"--set", "checkpoint.interval=0.004",
                                         "--set", "output.interval=0.005",
                                         "--set", "coupling.end_time=0.08"};
  std::mt19937 rng(20261205);
  std::uniform_int_distribution<int> after(20, 120);  // steps past where the piece resumed
  const auto rows = [&] {
    std::ifstream in(run / "timeseries.csv");
    return static_cast<int>(
        std::count(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>(), '\n'));
  };
  const auto snapshots = [&] {
    if (!fs::exists(run / "particles.h5")) return std::size_t{0};
    return cosim::analysis::ParticleFile(run / "particles.h5").snapshots().size();
  };
  int kills = 0;
  for (int piece = 0; piece < 6; ++piece) {
    std::vector<std::string> argv = {cosim};
    if (piece == 0) {
      argv.insert(argv.end(),
                  {"run", std::string(COSIM_SOURCE_DIR) + "/scenarios/plasma-coating-bed/ci.yaml",
                   "-o", run.string(), "--quiet"});
      argv.insert(argv.end(), sets.begin(), sets.end());
    } else {
      argv.insert(argv.end(), {"resume", run.string(), "--quiet"});
    }
    cosim::util::ChildProcess p(argv, base, base / ("piece" + std::to_string(piece) + ".out"), {});
    if (piece == 5) {  // the last piece runs to the end
      ASSERT_EQ(p.wait(), 0) << "piece " << piece;
      break;
    }
    // wait for the coupled steps to run (the first checkpoint of this piece's run), then aim
    const auto t0 = std::chrono::steady_clock::now();
    const auto waited = [&] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    };
    bool aimed = false;
    if (piece == 0) {  // while a checkpoint is being written, one complete already there
      aimed = awaitCheckpointBeingWritten(run, p, 120);
    } else if (piece == 1) {  // right after a snapshot appeared
      const std::size_t before = snapshots();
      while (p.running() && waited() < 120 && !aimed) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        try {
          aimed = snapshots() > before;
        } catch (const std::exception&) {
          aimed = true;  // the file is being written: the moment to aim at
        }
      }
    } else {  // at a random step: once the piece has run some steps past its resume
      std::this_thread::sleep_for(std::chrono::seconds(1));  // the resume cuts the series back
      int target = -1;
      while (p.running() && waited() < 120 && !aimed) {
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
        const int n = rows();
        if (target < 0 && n > 0) target = n + after(rng);
        aimed = target > 0 && n >= target;
      }
    }
    if (!p.running()) {  // finished before it could be killed: nothing more to test
      ADD_FAILURE() << "piece " << piece << " ended before the kill: " << p.exitDescription();
      break;
    }
    ::kill(p.pid(), SIGKILL);
    p.wait();
    ++kills;
    // its participants notice that cosim is gone and stop; wait for them before resuming
    std::this_thread::sleep_for(std::chrono::seconds(4));
  }
  EXPECT_EQ(kills, 5);

  const auto summary = cosim::analysis::readJsonFile(run / "summary.json");
  ASSERT_EQ(summary.at("status"), "completed");
  const auto& t = summary.at("headline");
  const double in = t.at("precursor_in_kg");
  EXPECT_LT(std::fabs(in - t.at("precursor_out_kg").get<double>() -
                      t.at("precursor_held_kg").get<double>() -
                      t.at("precursor_removed_kg").get<double>()),
            1e-4 * in);
  EXPECT_NEAR(t.at("coating_credited_kg").get<double>(), t.at("precursor_removed_kg").get<double>(),
              1e-12 * in);
  EXPECT_NEAR(t.at("coating_on_particles_kg").get<double>(),
              t.at("coating_credited_kg").get<double>(), 1e-12 * in);

  // snapshots: the output times 0, 0.005, ..., 0.08, each once
  const cosim::analysis::ParticleFile file(run / "particles.h5");
  ASSERT_EQ(file.snapshots().size(), 17u);
  for (std::size_t i = 0; i < 17; ++i) EXPECT_NEAR(file.snapshots()[i].time, 0.005 * i, 1e-9);
  // the time series: one row per step after the initial one
  const auto ts = cosim::analysis::readTimeSeries(run / "timeseries.csv");
  const auto& times = ts.at("time");
  ASSERT_EQ(times.size(), 801u);
  for (std::size_t i = 1; i < times.size(); ++i) EXPECT_NEAR(times[i], 1e-4 * i, 1e-9) << i;
  // passes: per parcel in order, none overlapping the next
  std::map<std::int64_t, std::vector<cosim::analysis::ZonePass>> byParcel;
  for (const auto& p : cosim::analysis::readZonePasses(run / cosim::analysis::kZonePassesFile))
    byParcel[p.parcel_id].push_back(p);
  for (auto& [id, ps] : byParcel) {
    std::sort(ps.begin(), ps.end(), [](auto& a, auto& b) { return a.entry_time < b.entry_time; });
    for (std::size_t i = 0; i + 1 < ps.size(); ++i)
      EXPECT_LE(ps[i].exit_time, ps[i + 1].entry_time + 1e-12) << "parcel " << id;
  }
  // the report's ledger check: every parcel's coating equals its passes'
  cosim::analysis::ReportOptions ro;
  ro.runs = {run};
  ro.output = base / "report";
  ro.plots = false;
  ASSERT_EQ(cosim::analysis::runReport(ro), 0);
  const auto report = cosim::analysis::readJsonFile(base / "report" / "report.json");
  const auto& zp = report.at("zone_passes");
  EXPECT_TRUE(zp.at("ledgers_agree").get<bool>()) << zp.value("ledger_problem", "");
  const double passes = zp.at("coating_in_passes_kg"), parcels = zp.at("coating_on_parcels_kg");
  EXPECT_NEAR(parcels, passes, 1e-12 * passes);
  fs::remove_all(base);
}

// Ctrl-C in the phases not covered above: while a checkpoint is being written, and while `cosim
// report` analyses the stopped run. The run stops with the checkpoint it was writing (status
// interrupted, exit 130, its summary ending where that checkpoint is, no partial checkpoint left)
// and resumes from it to the end; the report stops at once (exit 130) leaving no half-written or
// temporary file, the run's records as they were, and a later report complete.
TEST(PlasmaCoatingCi, CtrlCDuringACheckpointOrAReportStopsCleanly) {
  const fs::path base =
      fs::temp_directory_path() / ("cosim-plasma-ctrlc2-" + std::to_string(getpid()));
  fs::remove_all(base);
  fs::create_directories(base);
  const fs::path run = base / "run";
  const std::string cosim = std::string(COSIM_BINARY_DIR) + "/cosim";
  const auto since = [](std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  {
    cosim::util::ChildProcess p(
        {cosim, "run", std::string(COSIM_SOURCE_DIR) + "/scenarios/plasma-coating-bed/ci.yaml",
         "-o", run.string(), "--quiet", "--set", "checkpoint.interval=0.004", "--set",
         "coupling.end_time=0.06", "--set", "output.interval=0.005"},
        base, base / "run.out", {});
    const auto t0 = std::chrono::steady_clock::now();
    // past t = 0.025 s (250 steps: snapshots enough for the report's fits and bootstrap), a
    // checkpoint being written while an earlier one is complete
    const auto rows = [&] {
      std::ifstream in(run / "timeseries.csv");
      return std::count(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>(), '\n');
    };
    while (p.running() && since(t0) < 180 && rows() < 250)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const bool aimed = awaitCheckpointBeingWritten(run, p, 180);
    ASSERT_TRUE(aimed && p.running()) << "no checkpoint write to aim at: " << p.exitDescription();
    const auto t1 = std::chrono::steady_clock::now();
    ::kill(p.pid(), SIGINT);
    const int code = p.wait();
    const double waited = since(t1);
    std::printf("Ctrl-C during a checkpoint write: cosim stopped after %.2f s\n", waited);
    EXPECT_EQ(code, 130);
    EXPECT_LT(waited, 5.0);
  }
  const auto summary = cosim::analysis::readJsonFile(run / "summary.json");
  EXPECT_EQ(summary.at("status"), "interrupted");
  double newest = -1;
  for (const auto& e : fs::directory_iterator(run / "checkpoints")) {
    const std::string name = e.path().filename().string();
    EXPECT_NE(name.rfind(".partial", 0), 0u) << "a partial checkpoint was left: " << name;
    if (name.front() != '.') newest = std::max(newest, std::stod(name));
  }
  // stopped with the checkpoint it was writing (not a step later, with another)
  EXPECT_NEAR(summary.at("end_time_s").get<double>(), newest, 1e-9);

  // Ctrl-C while the report analyses the run (made long by many bootstrap resamples)
  const auto bytes = [](const fs::path& f) {
    std::ifstream in(f, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  const std::string series = bytes(run / "timeseries.csv"), passes = bytes(run / "zone_passes.csv");
  {
    cosim::util::ChildProcess r({cosim, "report", run.string(), "--no-plots", "--bootstrap",
                                 "2000000", "-o", (base / "report").string()},
                                base, base / "report.out", {});
    for (int i = 0; i < 300 && bytes(base / "report.out").find("analysing") == std::string::npos;
         ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    std::this_thread::sleep_for(std::chrono::seconds(1));
    ASSERT_TRUE(r.running()) << "the report ended before the Ctrl-C: " << r.exitDescription();
    const auto t1 = std::chrono::steady_clock::now();
    ::kill(r.pid(), SIGINT);
    const int code = r.wait();
    const double waited = since(t1);
    std::printf("Ctrl-C during cosim report: stopped after %.2f s\n", waited);
    EXPECT_EQ(code, 130);
    EXPECT_LT(waited, 5.0);
  }
  for (const auto& e : fs::recursive_directory_iterator(base))
    EXPECT_NE(e.path().extension(), ".tmp") << e.path();
  EXPECT_EQ(bytes(run / "timeseries.csv"), series);
  EXPECT_EQ(bytes(run / "zone_passes.csv"), passes);
  EXPECT_EQ(cosim::analysis::readJsonFile(run / "summary.json"), summary);

  // the run resumes from that checkpoint to its end, and its report is complete
  cosim::util::ChildProcess resumed({cosim, "resume", run.string(), "--quiet"}, base,
                                    base / "resume.out", {});
  ASSERT_EQ(resumed.wait(), 0) << bytes(base / "resume.out");
  cosim::analysis::ReportOptions ro;
  ro.runs = {run};
  ro.output = base / "report";
  ro.plots = false;
  ASSERT_EQ(cosim::analysis::runReport(ro), 0);
  const auto report = cosim::analysis::readJsonFile(base / "report" / "report.json");
  EXPECT_TRUE(report.at("zone_passes").at("ledgers_agree").get<bool>());
  fs::remove_all(base);
}

// coupling.data_path: peer with the real solvers: LIGGGHTS' participant samples the gas from
// OpenFOAM's, evaluates the scene's laws over its parcels and keeps their coating ledger and zone
// passes, OpenFOAM takes its exchange terms from the particles; the orchestrator sends the
// schedule and keeps the ledger's totals. Both solvers get
// the same numbers as on the central path, so the run is the central one bit for bit: every
// time-series column but the wall clock, every snapshot's fields, the zone passes, the totals.
// `sets`: the layout (ranks) both runs share.
static void expectPeerPathIsTheCentralRun(const std::vector<std::string>& sets,
                                          const std::string& tag) {
  const fs::path scene = fs::path(COSIM_SOURCE_DIR) / "scenarios/plasma-coating-bed/ci.yaml";
  const fs::path base =
      fs::temp_directory_path() / ("cosim-plasma-peer-" + tag + std::to_string(getpid()));
  fs::remove_all(base);
  std::map<std::string, RunResult> runs;
  for (const std::string path : {"central", "peer"}) {
    RunOptions o;
    o.quiet = true;
    o.output = base / path;
    std::vector<std::string> these = {"coupling.scheme=parallel"};  // unless `sets` says
    these.insert(these.end(), sets.begin(), sets.end());
    these.push_back("coupling.data_path=" + path);
    runs[path] = Coupler(loadScenario(scene, these), o).run();
    ASSERT_EQ(runs[path].exit_code, 0) << runs[path].message;
  }
  ASSERT_GT(runs["peer"].totals.at("coating_credited_kg"), 0.0);
  EXPECT_EQ(runs["peer"].totals, runs["central"].totals);
  const auto ta = cosim::analysis::readTimeSeries(base / "central" / "timeseries.csv");
  const auto tb = cosim::analysis::readTimeSeries(base / "peer" / "timeseries.csv");
  ASSERT_EQ(ta.columns, tb.columns);
  ASSERT_EQ(ta.rows(), tb.rows());
  for (const auto& c : ta.columns) {
    if (c == "wall_seconds") continue;
    for (std::size_t r = 0; r < ta.rows(); ++r) {
      const double x = ta.at(c)[r], y = tb.at(c)[r];
      if (!(std::isnan(x) && std::isnan(y))) ASSERT_EQ(x, y) << c << " row " << r;
    }
  }
  const cosim::analysis::ParticleFile pa(base / "central" / "particles.h5");
  const cosim::analysis::ParticleFile pb(base / "peer" / "particles.h5");
  ASSERT_EQ(pa.snapshots().size(), pb.snapshots().size());
  for (std::size_t s = 0; s < pa.snapshots().size(); ++s) {
    ASSERT_EQ(pa.ids(s), pb.ids(s));
    for (const auto& name : pa.fields())
      ASSERT_EQ(pa.read(s, name), pb.read(s, name)) << name << " at " << pa.snapshots()[s].time;
  }
  auto text = [](const fs::path& f) {
    std::ifstream in(f);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  EXPECT_EQ(text(base / "central" / "zone_passes.csv"), text(base / "peer" / "zone_passes.csv"));
  const auto summary = nlohmann::json::parse(std::ifstream(base / "peer" / "summary.json"));
  EXPECT_GT(summary.at("timings_s").at("particles_models_compute").get<double>(), 0.0);
  fs::remove_all(base);
}

TEST(PlasmaCoatingCi, PeerDataPathGivesTheCentralRunBitForBit) {
  expectPeerPathIsTheCentralRun({}, "1-");
}

// The peer path resumed with the real solvers: the coating owed to each parcel and the open zone
// passes come back from LIGGGHTS' part of the checkpoint (peer_ledger.pb), so the ledger closes
// across the resume (what the parcels took is what they hold, the passes hold what the parcels
// hold) and the run agrees with the uninterrupted one as a central resume does.
TEST(PlasmaCoatingCi, PeerDataPathResumedKeepsTheParticlesLedger) {
  const fs::path scene = fs::path(COSIM_SOURCE_DIR) / "scenarios/plasma-coating-bed/ci.yaml";
  const fs::path base =
      fs::temp_directory_path() / ("cosim-plasma-peer-resume-" + std::to_string(getpid()));
  fs::remove_all(base);
  const std::vector<std::string> sets = {"checkpoint.interval=0.01", "coupling.data_path=peer"};
  RunOptions o;
  o.quiet = true;
  o.output = base / "full";
  const RunResult full = Coupler(loadScenario(scene, sets), o).run();
  ASSERT_EQ(full.exit_code, 0) << full.message;
  ASSERT_TRUE(fs::exists(base / "full/checkpoints/0.03/particles" / cosim::link::kPeerLedgerFile))
      << "the particles' part holds their ledger";
  fs::copy(base / "full", base / "cut", fs::copy_options::recursive);
  fs::remove_all(base / "cut/checkpoints/0.04");
  fs::remove_all(base / "cut/checkpoints/0.05");
  fs::remove(base / "cut/particles/post/grains_10000.dump");  // written after 0.03 s
  RunOptions ro;
  ro.quiet = true;
  ro.resume = base / "cut";
  const RunResult resumed = Coupler(loadScenario(scene, sets), ro).run();
  ASSERT_EQ(resumed.exit_code, 0) << resumed.message;
  const auto& t = resumed.totals;
  const double in = t.at("precursor_in_kg");
  ASSERT_GT(t.at("coating_credited_kg"), 0.0);
  EXPECT_LT(std::fabs(t.at("precursor_removed_kg") - t.at("coating_credited_kg")), 1e-12 * in);
  EXPECT_LT(std::fabs(t.at("coating_on_particles_kg") - t.at("coating_credited_kg")), 1e-12 * in);
  const double coated = full.totals.at("coating_credited_kg");
  EXPECT_NEAR(t.at("coating_credited_kg"), coated, 2e-6 * coated);
  cosim::analysis::ReportOptions rep;
  rep.runs = {base / "cut"};
  rep.output = base / "report";
  rep.plots = false;
  ASSERT_EQ(cosim::analysis::runReport(rep), 0);
  const auto report = cosim::analysis::readJsonFile(base / "report" / "report.json");
  EXPECT_TRUE(report.at("zone_passes").at("ledgers_agree").get<bool>()) << report.dump();
  fs::remove_all(base);
}

// Two OpenFOAM ranks and two LIGGGHTS ranks, each solver's first rank talking for its ranks.
TEST(PlasmaCoatingCi, PeerDataPathOnTwoPlusTwoRanksGivesTheCentralRunBitForBit) {
  expectPeerPathIsTheCentralRun(
      {"participants.fluid.mpi=2", "dem_ranks=2", "coupling.end_time=0.02"}, "2-");
}

// Across nodes, as on one: the orchestrator's link over tcp:// with CurveZMQ, and the fluid's
// peer socket on a port of its own, with a key pair of this run for each side.
TEST(PlasmaCoatingCi, PeerDataPathOverTcpGivesTheCentralRunBitForBit) {
  const fs::path keys = fs::temp_directory_path() / ("cosim-peer-keys-" + std::to_string(getpid()));
  fs::remove_all(keys);
  cosim::link::writeKeyPairFile(keys / "orchestrator.key", cosim::link::newCurveKeyPair());
  expectPeerPathIsTheCentralRun(
      {"coupling.end_time=0.02",
       "transport.bind=tcp://127.0.0.1:" + std::to_string(cosim::test::freeLoopbackPort()),
       "transport.key_file=" + (keys / "orchestrator.key").string()},
      "tcp-");
  fs::remove_all(keys);
}

// The overlapped scheme on the peer path: the fluid samples the gas where the parcels will be at
// the end of its step and sends it to the particles with its results; the same run as the central
// path's overlapped scheme.
TEST(PlasmaCoatingCi, PeerDataPathOverlappedGivesTheCentralRunBitForBit) {
  expectPeerPathIsTheCentralRun({"coupling.scheme=overlapped", "coupling.end_time=0.02"}, "ovl-");
}

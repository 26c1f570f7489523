#include "bench.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <ostream>

#include "checkpoints.h"
#include "cosim/analysis/files.h"
#include "cosim/analysis/summary.h"
#include "cosim/util/format.h"
#include "coupler.h"
#include "plan.h"
#include "run_pack.h"
#include "scenario.h"

namespace cosim::orchestrator {

namespace {

const char* const kPhases[] = {"fluid_sample", "models", "advance", "bookkeeping"};

std::string schemeOf(const std::string& stage) {
  if (stage == "dem") return "frozen-fluid";
  if (stage == "cfd") return "frozen-particles";
  if (stage == "coupled" || stage == "peer") return "";  // the scene's coupling.scheme
  throw std::invalid_argument("cosim bench: unknown stage '" + stage +
                              "' (coupled, dem, cfd, peer)");
}

double at(const std::map<std::string, double>& m, const std::string& key) {
  const auto it = m.find(key);
  return it == m.end() ? 0.0 : it->second;
}

}  // namespace

double BenchStage::total() const {
  double s = 0;
  for (const auto& [phase, v] : phases) s += v;
  return s;
}

double BenchStage::serial() const { return total() - at(phases, "advance"); }

BenchRatios benchRatios(const std::map<std::string, BenchStage>& stages) {
  auto total = [&](const char* n) {
    const auto it = stages.find(n);
    return it == stages.end() ? 0.0 : it->second.total();
  };
  const double alone = std::max(total("dem"), total("cfd"));
  // R and the serial share of one coupled stage (coupled or peer); zeros without it.
  auto ratios = [&](const char* n, double& over_max, double& serial) {
    const auto it = stages.find(n);
    if (it == stages.end() || !(it->second.total() > 0)) return;
    over_max = alone > 0 ? it->second.total() / alone : 0.0;
    serial = 100.0 * it->second.serial() / it->second.total();
  };
  BenchRatios r;
  ratios("coupled", r.coupled_over_max, r.serial_percent);
  ratios("peer", r.peer_over_max, r.peer_serial_percent);
  return r;
}

namespace {

// Where the stages start: the scene's initial state, or (--from RUN) the run's newest checkpoint.
struct BenchStart {
  Scenario scene;
  double time = 0;
};

BenchStart benchStart(const BenchOptions& opt) {
  if (opt.scenario.empty() && opt.from.empty())
    throw std::invalid_argument("cosim bench: give a scenario (file or folder) or --from RUN");
  if (opt.from.empty()) {
    Scenario sc = loadScenario(opt.scenario, opt.sets, opt.unsets);
    const double t = sc.coupling.start_time;
    return {std::move(sc), t};
  }
  if (!opt.scenario.empty() || !opt.unsets.empty())
    throw std::invalid_argument(
        "cosim bench --from " + opt.from.string() +
        ": the run's own scene is benched; give no scenario and no --unset (--set may change "
        "only what cosim resume lets change)");
  Scenario sc = loadRunScene(opt.from, opt.sets);
  const auto newest = CheckpointStore(opt.from).newest();
  if (!newest)
    throw std::runtime_error("cosim bench --from " + opt.from.string() +
                             ": the run has no complete checkpoint to start from (a run writes "
                             "one every checkpoint.interval and when Ctrl-C stops it)");
  return {std::move(sc), readCoupledState(*newest).time};
}

// The stages to run: the asked ones, and the peer stage when asked for or the scene's own path.
// A run's data path stays the one it began with (cosim resume), so `from` takes a central run
// and no peer stage.
std::vector<std::string> stagesOf(const BenchOptions& opt, const Scenario& probe) {
  std::vector<std::string> names = opt.stages;
  const bool scene_peer = probe.coupling.data_path == "peer";
  const bool want_peer =
      opt.peer || scene_peer || std::find(names.begin(), names.end(), "peer") != names.end();
  if (!opt.from.empty() && scene_peer)
    throw std::invalid_argument(
        "cosim bench --from " + opt.from.string() +
        ": the run takes coupling.data_path: peer, and a run keeps its data path, while the "
        "bench's coupled stage records the central path's terms for the solvers alone; bench "
        "the scene instead (cosim bench SCENE --peer)");
  if (!opt.from.empty() && want_peer)
    throw std::invalid_argument("cosim bench --from " + opt.from.string() +
                                ": the peer stage needs the scene: a run keeps the data path it "
                                "began with");
  if (want_peer && !makePlan(probe, makeModels(probe)).fluid)
    throw std::invalid_argument(
        "cosim bench --peer: the scene has no fluid participant, so no per-parcel data goes "
        "between the solvers and there is no peer path to time (coupling.data_path: peer runs "
        "it on the central path); leave out --peer");
  if (want_peer && std::find(names.begin(), names.end(), "peer") == names.end())
    names.emplace_back("peer");
  return names;
}

}  // namespace

int runBench(const BenchOptions& opt, std::ostream& out) {
  if (!opt.from.empty() && opt.peer)
    throw std::invalid_argument("cosim bench --from " + opt.from.string() +
                                " --peer: the peer stage needs the scene (cosim bench SCENE "
                                "--peer): a run keeps the data path it began with");
  const BenchStart start = benchStart(opt);
  const Scenario& probe = start.scene;
  const bool from_run = !opt.from.empty();
  const std::filesystem::path folder =
      opt.output.empty() ? std::filesystem::path("runs") / (probe.name + "-bench") : opt.output;
  const double end = start.time + static_cast<double>(opt.steps + opt.warmup) * probe.coupling.dt;
  std::vector<std::string> sets = opt.sets;
  sets.push_back(fmt::format("coupling.end_time={}", end));
  // No checkpoints: a solver-alone stage's state is no coupled state to continue from (the idle
  // solver stays where it began).
  sets.emplace_back("checkpoint.interval=0");

  double load[3] = {0, 0, 0};
  const bool have_load = getloadavg(load, 3) == 3;
  out << "cosim bench: " << probe.name;
  if (from_run) out << " from " << opt.from.string() << " at t = " << start.time << " s";
  out << ", " << opt.steps << " steps of " << probe.coupling.dt << " s per stage after "
      << opt.warmup << " untimed";
  if (have_load) out << fmt::format("; load average {:.2f}", load[0]);
  out << "\n  run folders under " << folder.string() << std::endl;

  const std::vector<std::string> names = stagesOf(opt, probe);
  // The stages' run folders are written over (as with cosim run --overwrite): each must be new,
  // empty or a run folder of cosim's, checked before the first stage runs.
  for (const auto& name : names)
    analysis::claimOutputFolder(folder / name, analysis::kSummaryFile, "\"cosim-summary\"",
                                "cosim bench -o");

  std::map<std::string, BenchStage> stages;
  // The coupled stage runs first and records its terms; the solver-alone stages replay them.
  std::vector<std::string> order = names;
  std::stable_partition(order.begin(), order.end(), [](const auto& n) { return n == "coupled"; });
  const bool recorded = !order.empty() && order.front() == "coupled";
  auto recording = std::make_shared<TermsRecording>();
  for (const auto& name : order) {
    RunOptions ro;
    ro.quiet = true;
    ro.stop = opt.stop;
    ro.scheme = schemeOf(name);
    ro.untimed_steps = opt.warmup;
    if (name == "coupled")
      ro.record_terms = recording;
    else if (recorded && name != "peer")  // the peer stage couples; the alone stages replay
      ro.replay_terms = recording;
    const std::filesystem::path stage = folder / name;
    std::vector<std::string> stage_sets = sets;
    stage_sets.emplace_back(name == "peer" ? "coupling.data_path=peer"
                                           : "coupling.data_path=central");
    std::optional<Coupler> c;
    if (from_run) {
      // A copy of the run as `cosim pack` makes it, resumed: the run itself is never written.
      std::filesystem::remove_all(stage);
      packRun(opt.from, stage, probe);
      ro.resume = std::filesystem::absolute(stage);
      c.emplace(loadRunScene(stage, sets), ro);  // a central run (stagesOf)
    } else {
      ro.overwrite = true;
      ro.output = stage;
      c.emplace(loadScenario(opt.scenario, stage_sets, opt.unsets), ro);
    }
    const RunResult r = c->run();
    if (r.exit_code != 0) {
      out << "cosim bench: stage " << name << " failed\n" << r.message << std::endl;
      return r.exit_code;
    }
    BenchStage st;
    st.name = name;
    st.steps = r.timed_steps;
    const double n = static_cast<double>(std::max<std::uint64_t>(r.timed_steps, 1));
    for (const auto& [p, s] : r.phase_seconds) st.phases[p] = s / n;
    for (const auto& [p, s] : r.compute_seconds) st.compute[p] = s / n;
    stages[name] = st;
  }

  out << "\nms per step   total";
  for (const char* p : kPhases) out << "  " << std::setw(12) << p;
  out << "  particles_compute  fluid_compute  fluid_sample_compute  send  particles_reply  "
         "fluid_reply\n";
  for (const auto& name : names) {
    const auto& st = stages.at(name);
    out << std::left << std::setw(10) << name << std::right << std::setw(8)
        << util::fixed(1e3 * st.total(), 2);
    for (const char* p : kPhases)
      out << "  " << std::setw(12) << util::fixed(1e3 * at(st.phases, p), 2);
    out << "  " << std::setw(17) << util::fixed(1e3 * at(st.compute, "particles"), 2) << "  "
        << std::setw(13) << util::fixed(1e3 * at(st.compute, "fluid"), 2) << "  " << std::setw(20)
        << util::fixed(1e3 * at(st.compute, "fluid_sample"), 2) << "  " << std::setw(4)
        << util::fixed(1e3 * at(st.compute, "advance_send"), 2) << "  " << std::setw(15)
        << util::fixed(1e3 * at(st.compute, "advance_particles_reply"), 2) << "  " << std::setw(11)
        << util::fixed(1e3 * at(st.compute, "advance_fluid_reply"), 2) << "\n";
  }
  const BenchRatios r = benchRatios(stages);
  auto total = [&](const char* n) { return stages.count(n) ? stages.at(n).total() : 0.0; };
  out << "\n";
  if (total("dem") > 0 && total("coupled") > 0)
    out << fmt::format("coupled/dem = {:.3f}\n", total("coupled") / total("dem"));
  if (total("cfd") > 0 && total("coupled") > 0)
    out << fmt::format("coupled/cfd = {:.3f}\n", total("coupled") / total("cfd"));
  if (total("peer") > 0)
    out << fmt::format("peer/max(dem,cfd) = {:.3f}; serial share = {:.1f} %\n", r.peer_over_max,
                       r.peer_serial_percent);
  out << fmt::format("coupled/max(dem,cfd) = {:.3f}; serial share = {:.1f} %", r.coupled_over_max,
                     r.serial_percent)
      << std::endl;
  return 0;
}

}  // namespace cosim::orchestrator

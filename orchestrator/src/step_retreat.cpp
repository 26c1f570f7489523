#include "step_retreat.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "checkpoints.h"
#include "cosim/analysis/files.h"
#include "run_log.h"

namespace cosim::orchestrator {

namespace {

std::string number(double v) { return analysis::formatShortest(v); }

// The run in `folder` resumed with `sets` on top of its own scene.
RunResult resumeWith(const RunOptions& base, const std::filesystem::path& folder,
                     const std::vector<std::string>& sets) {
  RunOptions o = base;
  o.resume = folder;
  o.resume_from.reset();
  o.output.clear();
  o.overwrite = false;
  return Coupler(loadRunScene(folder, sets), o).run();
}

}  // namespace

double stretchEnd(double checkpoint, double stopped, double interval, double end) {
  const double k =
      std::max(1.0, std::ceil((stopped + 0.5 * interval - checkpoint) / interval - 1e-9));
  return std::min(checkpoint + k * interval, end);
}

RunResult runThroughStiffStretches(Scenario sc, RunOptions opt) {
  const unsigned allowed = sc.checks.step_halvings;
  const double dt = sc.coupling.dt;
  const unsigned dem_steps = sc.coupling.dem_steps;
  const double end = sc.coupling.end_time;
  const double interval = sc.checkpoint.interval;
  RunResult r = Coupler(std::move(sc), opt).run();
  RunLog log(opt.quiet);  // the changes of step, on the console and in the run's cosim.log
  unsigned halvings = 0;  // in a row, in the stretch being gone through
  bool changed = false;   // the run folder's scene holds a stretch's step and end
  while (r.unstable_step && allowed > 0) {
    const auto stop = [&](const std::string& why) {
      r.message += "\n  (checks.step_halvings: " + why + ")";
    };
    if (interval <= 0) {
      stop("not applied: the run writes no checkpoints to go back to; set checkpoint.interval");
      break;
    }
    if (halvings == allowed) {
      stop("the step was halved " + std::to_string(halvings) +
           " times in a row and the run still stopped; the stretch may not be a matter of the "
           "step: see docs/when-things-go-wrong.md");
      break;
    }
    const unsigned parts = 1U << (halvings + 1);
    if (dem_steps % parts != 0) {
      stop("coupling.dem_steps " + std::to_string(dem_steps) + " cannot be halved " +
           std::to_string(halvings + 1) + " times keeping the DEM step");
      break;
    }
    const auto newest = CheckpointStore(r.folder).newest();
    if (!newest) {
      stop("no checkpoint was written before the stop to go back to");
      break;
    }
    ++halvings;
    changed = true;
    const double from = std::strtod(newest->filename().c_str(), nullptr);
    const double until = stretchEnd(from, r.time, interval, end);
    const double small = dt / parts;
    log.open(r.folder / "cosim.log");  // appended to, as the runs' own lines
    log.warn("the Courant check stopped the run at t = " + number(r.time) +
             " s; going on from the checkpoint at " + number(from) + " s with a coupling step of " +
             number(small) + " s to " + number(until) + " s (checks.step_halvings: " +
             std::to_string(halvings) + " of " + std::to_string(allowed) + ")");
    r = resumeWith(
        opt, r.folder,
        {"coupling.dt=" + number(small), "coupling.dem_steps=" + std::to_string(dem_steps / parts),
         "coupling.end_time=" + number(until)});
    if (r.exit_code != 0 || until >= end) continue;  // a stop in the stretch halves again
    halvings = 0;
    log.show("past the stiff stretch at t = " + number(r.time) +
             " s: on with the coupling step of " + number(dt) + " s");
    r = resumeWith(opt, r.folder,
                   {"coupling.dt=" + number(dt), "coupling.dem_steps=" + std::to_string(dem_steps),
                    "coupling.end_time=" + number(end)});
    changed = false;  // the scene's own step and end again
  }
  // Stopped (Ctrl-C, a failure) inside a stretch: its scene says the stretch's step and end
  if (changed && r.exit_code != 0 && !r.message.empty())
    r.message +=
        "\n  (the run folder's scene holds the smaller step's stretch; to go on as the "
        "scene was: cosim resume " +
        r.folder.string() + " --set coupling.dt=" + number(dt) +
        " --set coupling.dem_steps=" + std::to_string(dem_steps) +
        " --set coupling.end_time=" + number(end) + ")";
  return r;
}

}  // namespace cosim::orchestrator

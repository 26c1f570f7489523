#include "scenario/coupling_section.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "scenario/limits.h"

namespace cosim::orchestrator {

const std::vector<KeySpec>& CouplingSection::keys() {
  static const std::vector<KeySpec> k = {
      {"dt", "required",
       "coupling interval = CFD time step [s]; > 0, and (end_time - start_time) / dt at most 1e9 "
       "steps"},
      {"dem_steps", "1", "DEM steps per coupling interval; a whole number in 1 .. 1e7"},
      {"end_time", "required", "simulated time at the end [s]; later than start_time"},
      {"start_time", "0", "simulated time at the start [s]"},
      {"scheme", "parallel",
       "parallel (sample the gas between the intervals, both solvers waiting) | overlapped (the "
       "fluid samples at the end of its step where the parcels will be, position + velocity dt, "
       "while the particles advance: faster where sampling is a large part of the step; the "
       "placement "
       "is off by the change of velocity over one interval, a dt^2/2; the mass balance is "
       "unchanged; docs/performance.md)"},
      {"data_path", "central",
       "central (every parcel's data passes through cosim: the gas sampled at the parcels, the "
       "laws evaluated, the terms sent to both solvers) | peer (the particle participant samples "
       "the gas from the fluid participant and evaluates the laws over its own parcels; cosim "
       "sends both only the schedule and the coating owed and keeps the ledger, the checks and the "
       "records; the same answers bit for bit, with either scheme; over tcp:// the fluid "
       "listens on a port of its own, with CurveZMQ keys of the run; docs/design.md section 5)"},
      {"cpus", "off",
       "off (the processes run wherever the system puts them) | auto (with 2 or more CPUs and both "
       "solvers started here as single processes (launch local, mpi 1): the particles and the "
       "orchestrator bound to the first CPU the run may use, the fluid (every thread, set before "
       "the adapter starts) to the others; otherwise the run log says why it was not applied; "
       "docs/performance.md, \"Bound to CPUs\")"},
  };
  return k;
}

std::uint64_t CouplingSection::steps() const {
  return static_cast<std::uint64_t>(std::llround((end_time - start_time) / dt));
}

CouplingSection parseCoupling(const YAML::Node& coupling, const Context& ctx) {
  if (!coupling)
    ctx.failTop("coupling",
                "missing section; expected { dt: SECONDS, dem_steps: N, end_time: SECONDS }");
  ctx.section(coupling, "coupling", "{ dt: SECONDS, dem_steps: N, end_time: SECONDS }");
  ctx.allowOnly(coupling, "coupling", CouplingSection::keys());
  CouplingSection c;
  c.dt =
      ctx.positive(coupling["dt"], "coupling.dt", "(coupling interval = CFD time step, seconds)");
  c.end_time = ctx.positive(coupling["end_time"], "coupling.end_time", "(seconds)");
  if (coupling["start_time"])
    c.start_time = ctx.number(coupling["start_time"], "coupling.start_time");
  if (coupling["dem_steps"]) {
    double n = ctx.number(coupling["dem_steps"], "coupling.dem_steps");
    if (n < 1 || n != std::floor(n) || n > 1e7) {
      ctx.fail(coupling["dem_steps"], "coupling.dem_steps",
               "expected a whole number of DEM steps per coupling interval, 1 to 1e7, got " +
                   coupling["dem_steps"].Scalar());
    }
    c.dem_steps = static_cast<unsigned>(n);
  }
  if (coupling["scheme"]) {
    c.scheme = ctx.text(coupling["scheme"], "coupling.scheme");
    if (c.scheme != "parallel" && c.scheme != "overlapped")
      ctx.fail(coupling["scheme"], "coupling.scheme",
               "expected 'parallel' or 'overlapped', got '" + c.scheme + "'");
  }
  if (coupling["data_path"]) {
    c.data_path = ctx.text(coupling["data_path"], "coupling.data_path");
    if (c.data_path != "central" && c.data_path != "peer")
      ctx.fail(coupling["data_path"], "coupling.data_path",
               "expected 'central' or 'peer', got '" + c.data_path + "'");
  }
  if (coupling["cpus"]) {
    c.cpus = ctx.text(coupling["cpus"], "coupling.cpus");
    if (c.cpus != "off" && c.cpus != "auto")
      ctx.fail(coupling["cpus"], "coupling.cpus", "expected 'off' or 'auto', got '" + c.cpus + "'");
  }
  if (c.end_time <= c.start_time) {
    ctx.fail(coupling["end_time"], "coupling.end_time", "must be later than start_time");
  }
  const double span = c.end_time - c.start_time;
  if (!std::isfinite(span)) {
    ctx.fail(coupling["end_time"], "coupling.end_time",
             "end_time - start_time is not a finite number of seconds; give a shorter run");
  }
  if (c.dt > span) {
    ctx.fail(coupling["dt"], "coupling.dt", "is longer than the whole run (end_time - start_time)");
  }
  const double steps = span / c.dt;
  if (!(steps <= limits::kMaxSteps)) {
    std::ostringstream os;
    if (std::isfinite(steps))
      os << "gives " << steps;
    else
      os << "gives more than " << std::numeric_limits<double>::max();
    os << " coupling steps ((end_time - start_time) / dt); a run may take at most "
       << limits::kMaxSteps << ": use a larger dt or a shorter run";
    ctx.fail(coupling["dt"], "coupling.dt", os.str());
  }
  return c;
}

}  // namespace cosim::orchestrator

// coupling: the coupling interval, the DEM steps in it and the simulated time span.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scenario/context.h"

namespace cosim::orchestrator {

struct CouplingSection {
  double dt = 0.0;         // coupling interval = CFD time step [s]
  unsigned dem_steps = 1;  // DEM steps per coupling interval
  double end_time = 0.0;   // [s]
  double start_time = 0.0;
  // How the solvers share an interval (coupling_scheme.h): "parallel" samples the gas at the
  // parcels between the intervals, while both solvers wait; "overlapped" has the fluid sample it
  // at the end of its own step, where the parcels will be (position + velocity dt)
  std::string scheme = "parallel";
  // Where the per-parcel data of an interval goes: "central" (through the orchestrator, which
  // samples, evaluates the laws and sends the terms) or "peer" (between the participants; the
  // particle participant evaluates the laws; docs/design.md section 5)
  std::string data_path = "central";
  // Where the processes run: "off" (wherever the system puts them) or "auto" (with two or more
  // CPUs and both solvers local single processes: the particles and the orchestrator on the
  // first CPU, the fluid on the others; docs/performance.md, "Bound to CPUs")
  std::string cpus = "off";

  // Coupling steps of the run: (end_time - start_time) / dt rounded.
  std::uint64_t steps() const;

  static const std::vector<KeySpec>& keys();
};

CouplingSection parseCoupling(const YAML::Node& node, const Context& ctx);

}  // namespace cosim::orchestrator

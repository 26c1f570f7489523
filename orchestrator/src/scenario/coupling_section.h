// coupling: the coupling interval, the DEM steps in it and the simulated time span.
#pragma once

#include <cstdint>
#include <vector>

#include "scenario/context.h"

namespace cosim::orchestrator {

struct CouplingSection {
  double dt = 0.0;         // coupling interval = CFD time step [s]
  unsigned dem_steps = 1;  // DEM steps per coupling interval
  double end_time = 0.0;   // [s]
  double start_time = 0.0;

  // Coupling steps of the run: (end_time - start_time) / dt rounded.
  std::uint64_t steps() const;

  static const std::vector<KeySpec>& keys();
};

CouplingSection parseCoupling(const YAML::Node& node, const Context& ctx);

}  // namespace cosim::orchestrator

// checks: whether unstable settings are refused or only reported, and the monitors' limits.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "scenario/context.h"

namespace cosim::orchestrator {

struct ChecksSection {
  // "refuse" (default) stops unstable settings; "warn" only reports.
  std::string stability = "refuse";
  double max_particle_speed = 50.0;      // m/s; a faster particle stops the run
  double mass_balance_tolerance = 1e-4;  // relative drift that stops the run (coating scenes)
  double max_courant = 5.0;              // fluid Courant number that stops the run
  // A run the Courant check stops goes back to its newest checkpoint and through the stretch
  // with half the coupling step, at most this many halvings in a row (0: it stops; step_retreat.h)
  unsigned step_halvings = 0;
  // Particles the particle participant must hold when coupling starts (a scene's n_grains):
  // fewer, or more, stops the run before its first step. Absent: not checked.
  std::optional<std::uint64_t> particle_count;

  static const std::vector<KeySpec>& keys();
};

ChecksSection parseChecks(const YAML::Node& node, const Context& ctx);

}  // namespace cosim::orchestrator

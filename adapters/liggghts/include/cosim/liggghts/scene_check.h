// What the LIGGGHTS adapter can tell about a scene before LIGGGHTS starts (`cosim validate`,
// through cosim-liggghts --check-options): its options, the script and the files the script
// reads, and the script's time step against the coupling. The run checks the same again.
#pragma once

#include <optional>
#include <string>

#include "cosim.pb.h"

namespace cosim::liggghts {

// Throws std::runtime_error naming the option, the script line or the file on refusal.
void checkScene(const cosim::wire::Welcome& welcome);

// The refusal when a DEM step of `dt` does not fit the coupling (cfd_dt / dem_steps); nullopt
// when it fits or the coupling is not given. Shared by the check and the run.
std::optional<std::string> timestepMismatch(const std::string& script, double dt, double cfd_dt,
                                            unsigned dem_steps);

}  // namespace cosim::liggghts

// `cosim pack RUN DEST`: a copy of a stopped run that continues on another machine or disk
// (docs/restarts.md, "Moving a run"). It holds what `cosim resume` and `cosim report` need: the
// scene, the records (time series, particle snapshots, zone passes, summary, log, report), the
// newest checkpoint and each participant's case without its outputs. Left out, and counted: older
// checkpoints, the participants' logs, the fluid's time folders after its first (each one is
// written again from the checkpoint where the run continues), the particles' dump files and the
// run's lock and key files. The copy is made under a temporary name beside DEST and renamed when
// complete, so a failed pack leaves no half-made DEST and never touches RUN.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

#include "scenario.h"

namespace cosim::orchestrator {

struct PackResult {
  std::filesystem::path checkpoint;  // the checkpoint the copy continues from (RUN/checkpoints/t)
  std::uintmax_t copied_bytes = 0;
  std::uintmax_t copied_files = 0;
  // What was left out, by kind ("older checkpoints", "participants' logs", ...): bytes
  std::map<std::string, std::uintmax_t> left_out;
};

// `sc` is the run's scene (loadRunScene(run)): it names the participants and their adapters.
// Throws std::runtime_error saying what to do when RUN is in use by a live run, has no complete
// checkpoint, or DEST exists (and is not an empty folder) or lies inside RUN.
PackResult packRun(const std::filesystem::path& run, const std::filesystem::path& dest,
                   const Scenario& sc);

}  // namespace cosim::orchestrator

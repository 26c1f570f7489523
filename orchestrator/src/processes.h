// Participant processes: `util::ChildProcess` (cosim/util/child_process.h) starts each from an
// argument vector in its own process group with its output in a log file, watches it without
// blocking, stops it as a group (mpirun and all its ranks) and never orphans it. Here: what the
// orchestrator adds on top (finding executables, log tails for its messages).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "cosim/util/child_process.h"

namespace cosim::orchestrator {

using util::ChildProcess;

// Last n lines of a text file, each prefixed "    | " (for error messages).
std::string tailOfFile(const std::filesystem::path& file, int lines);

// Finds an executable: absolute/relative path as given, next to the running cosim, or in PATH.
std::optional<std::filesystem::path> findExecutable(const std::string& name);

}  // namespace cosim::orchestrator

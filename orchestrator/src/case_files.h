// Copies a participant's case folder (OpenFOAM case, LIGGGHTS script, ...) into the run folder,
// replacing ${expr} in every text file with the scenario parameters' values.
#pragma once

#include <filesystem>

#include "expression.h"

namespace cosim::orchestrator {

// Returns the number of files in which something was substituted. Binary files are copied as
// they are. Errors name the file and line; a file that cannot be written (disk full) is named
// with the reason and not left behind half written.
int copyCaseFiles(const std::filesystem::path& from, const std::filesystem::path& to,
                  const Variables& vars);

}  // namespace cosim::orchestrator

// `cosim keys`: creates the orchestrator's key file if it does not exist and shows a key file
// (the orchestrator's, or a participant's of a run): its public keys, never a secret one.
#pragma once

#include <filesystem>
#include <iosfwd>

namespace cosim::orchestrator {

// `file` empty: the default key file (link_security.h). Returns the exit code; errors (a file
// that is no key file, or others may read) are thrown as std::runtime_error.
int keysCommand(const std::filesystem::path& file, std::ostream& out);

}  // namespace cosim::orchestrator

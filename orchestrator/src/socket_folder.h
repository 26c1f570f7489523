// The folder of this user's ipc:// sockets, /tmp/cosim-<uid>: the orchestrator binds its
// socket there (<run id>.ipc) unless the scenario sets transport.bind.
#pragma once

#include <filesystem>

namespace cosim::orchestrator {

// Creates the folder (mode 0700) or checks it: refused with what to do if another user owns it
// or others may enter it. Removes the socket files in it that runs killed with `kill -9` left
// behind: those nothing accepts connections on and that are older than a minute (a socket is
// bound and listened on at once, so a young one may belong to a run just starting).
std::filesystem::path privateSocketFolder();

// True if `path` is a socket file on which no process accepts connections (connect refused).
bool isDeadSocket(const std::filesystem::path& path);

}  // namespace cosim::orchestrator

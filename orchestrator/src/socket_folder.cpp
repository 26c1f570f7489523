#include "socket_folder.h"

#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

#include "participants.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;

namespace {
// Younger socket files are never removed, whatever connect says.
constexpr std::chrono::seconds kStaleAfter{60};
}  // namespace

bool isDeadSocket(const fs::path& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0 || !S_ISSOCK(st.st_mode)) return false;
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  if (path.native().size() >= sizeof(addr.sun_path)) return false;
  std::memcpy(addr.sun_path, path.c_str(), path.native().size() + 1);
  // Without waiting: a run that is suspended (Ctrl-Z, a stopped job) accepts no connection,
  // and once its backlog is full a blocking connect would wait for as long as it stays
  // suspended (EAGAIN: alive)
  const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd < 0) return false;
  const bool refused = ::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0 &&
                       errno == ECONNREFUSED;
  ::close(fd);
  return refused;
}

fs::path privateSocketFolder() {
  const fs::path dir = fs::temp_directory_path() / ("cosim-" + std::to_string(getuid()));
  if (::mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST)
    throw RunFailure(
        "", "cannot create " + dir.string() + " for the ipc:// socket: " + std::strerror(errno));
  struct stat st {};
  if (::lstat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != getuid() ||
      (st.st_mode & 077) != 0) {
    throw RunFailure("", dir.string() +
                             " must be a folder of yours that only you can enter (mode 0700), "
                             "since the run's ipc:// socket goes there; remove it or fix it "
                             "(or set transport.bind)");
  }
  // Sockets of killed runs: nothing listens on them any more.
  std::error_code ec;
  const auto now = fs::file_time_type::clock::now();
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const auto written = fs::last_write_time(entry.path(), ec);
    if (ec || now - written < kStaleAfter) continue;
    if (isDeadSocket(entry.path())) fs::remove(entry.path(), ec);
  }
  return dir;
}

}  // namespace cosim::orchestrator

#include "run_token.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <random>
#include <stdexcept>

#include "cosim/util/errors.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;

std::string newRunToken() {
  std::random_device rd;  // the kernel's random source (getrandom)
  std::string token;
  for (int i = 0; i < 4; ++i) token += fmt::format("{:08x}", rd());
  return token;
}

bool sameToken(const std::string& given, const std::string& expected) {
  if (expected.empty() || given.size() != expected.size()) return false;
  unsigned char diff = 0;
  for (std::size_t i = 0; i < given.size(); ++i)
    diff |= static_cast<unsigned char>(given[i] ^ expected[i]);
  return diff == 0;
}

fs::path writeRunTokenFile(const fs::path& folder, const std::string& token) {
  const fs::path file = folder / kRunTokenFile;
  ::unlink(file.c_str());  // an earlier run's (or resume's) token
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) {
    const int err = errno;
    throw Error(kindOfErrno(err),
                "cannot write the run token to " + file.string() + ": " + std::strerror(err));
  }
  const std::string text = token + "\n";
  const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  const int err = errno;
  ::close(fd);
  if (!ok) {
    ::unlink(file.c_str());
    throw Error(kindOfErrno(err),
                "cannot write the run token to " + file.string() + ": " + std::strerror(err));
  }
  return file;
}

}  // namespace cosim::orchestrator

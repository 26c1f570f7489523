#include "link_security.h"

#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdlib>
#include <stdexcept>

#include "cosim/util/errors.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;

fs::path defaultKeyFile() {
  if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg != nullptr && *xdg == '/')
    return fs::path(xdg) / "cosim" / "orchestrator.key";
  const char* home = std::getenv("HOME");
  return fs::path(home != nullptr && *home != '\0' ? home : ".") / ".config" / "cosim" /
         "orchestrator.key";
}

fs::path keyFileOf(const TransportSection& t) {
  return t.key_file.empty() ? defaultKeyFile() : t.key_file;
}

bool isTcp(const std::string& endpoint) { return endpoint.rfind("tcp://", 0) == 0; }

std::string bindAddress(const std::string& bind) {
  if (bind.rfind("tcp://:", 0) != 0) return bind;
  char name[256] = {0};
  if (::gethostname(name, sizeof name - 1) != 0)
    throw InputError("transport.bind " + bind + ": cannot read this host's name");
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  if (::getaddrinfo(name, nullptr, &hints, &found) != 0 || found == nullptr) {
    throw InputError("transport.bind " + bind + ": this host's name '" + name +
                     "' has no IPv4 address; name the interface participants reach "
                     "(tcp://HOST:PORT)");
  }
  char address[NI_MAXHOST] = {0};
  const int rc = ::getnameinfo(found->ai_addr, found->ai_addrlen, address, sizeof address, nullptr,
                               0, NI_NUMERICHOST);
  ::freeaddrinfo(found);
  if (rc != 0)
    throw InputError("transport.bind " + bind + ": cannot read the address of '" + name + "'");
  return "tcp://" + std::string(address) + bind.substr(6);
}

fs::path participantKeyFile(const fs::path& run_folder, const std::string& participant) {
  return run_folder / (".cosim-" + participant + ".key");
}

std::optional<link::CurveKeyPair> orchestratorKeys(const TransportSection& t,
                                                   const std::string& bind) {
  if (!isTcp(bind) || t.insecure) return std::nullopt;
  const fs::path file = keyFileOf(t);
  const std::string why =
      "a tcp:// link is encrypted with CurveZMQ under the orchestrator's key pair";
  try {
    link::requireCurve();
  } catch (const std::exception& e) {
    throw Error(kindOf(e, ErrorKind::resource), why + ", but " + e.what());
  }
  if (!fs::exists(file)) {
    throw InputError(why + ", and its key file " + file.string() +
                     " does not exist: create it with 'cosim keys' (or 'cosim keys FILE' "
                     "and name FILE in transport.key_file); to run tcp:// "
                     "without encryption on a network you trust, set "
                     "transport.insecure: true");
  }
  return link::readKeyPairFile(file);
}

std::string linkDescription(const TransportSection& t) {
  if (t.bind.empty() || !isTcp(t.bind)) {
    return (t.bind.empty() ? std::string("ipc:// in /tmp/cosim-") + std::to_string(getuid()) + "/"
                           : t.bind) +
           " (this host only; not encrypted, the socket's folder only you can enter)";
  }
  if (t.insecure) {
    return t.bind +
           " NOT encrypted, no authentication (transport.insecure: true): anyone who reaches the "
           "port can read the particle data";
  }
  const fs::path file = keyFileOf(t);
  std::string state;
  if (!link::curveAvailable())
    state = "; but this libzmq has no CurveZMQ: the run will be refused";
  else if (!fs::exists(file))
    state = "; the key file does not exist yet: create it with 'cosim keys'";
  return t.bind + " encrypted and authenticated with CurveZMQ (orchestrator key " + file.string() +
         state + "; each participant gets keys of its own for the run)";
}

}  // namespace cosim::orchestrator

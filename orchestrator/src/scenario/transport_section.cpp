#include "scenario/transport_section.h"

#include <cstdlib>
#include <filesystem>

#include "scenario/limits.h"

namespace cosim::orchestrator {

const std::vector<KeySpec>& TransportSection::keys() {
  static const std::vector<KeySpec> k = {
      {"bind", "ipc:///tmp/cosim-UID/RUN.ipc",
       "the orchestrator's socket: ipc://PATH (a file that does not exist yet) or "
       "tcp://HOST:PORT (port 1 .. 65535 or *; HOST an address, host name or interface that "
       "participants reach, not * (every interface); tcp://:PORT binds the address of this "
       "host's name). tcp:// is encrypted with CurveZMQ unless insecure is true"},
      {"connect", "the bind address",
       "the address participants connect to, if not the bind address; a tcp:// one needs a HOST"},
      {"heartbeat_timeout", "10",
       "seconds without a sign of life from a participant before it counts as gone; > 0, <= 1e6"},
      {"handshake_timeout", "60",
       "seconds for every participant to connect and say Hello; > 0, <= 1e6"},
      {"insecure", "false",
       "true: a tcp:// link without CurveZMQ, neither encrypted nor authenticated (anyone who "
       "reaches the port can read the particle data); every run then warns. Only for a network "
       "you trust, or a libzmq without CurveZMQ"},
      {"key_file",
       "$XDG_CONFIG_HOME/cosim/orchestrator.key (else ~/.config/cosim/orchestrator.key)",
       "the orchestrator's long-term CurveZMQ key pair for tcp:// (mode 0600; `cosim keys` "
       "creates it); relative to the scenario's folder, ~/ for the home folder"},
  };
  return k;
}

std::string endpointProblem(const std::string& ep, bool binding) {
  if (ep.rfind("ipc://", 0) == 0) {
    const std::string path = ep.substr(6);
    if (path.empty()) return "has no socket file after ipc://";
    std::error_code ec;
    if (binding &&
        std::filesystem::symlink_status(path, ec).type() != std::filesystem::file_type::not_found) {
      return "names '" + path +
             "', which exists; cosim binds only a socket file it creates (and removes at the "
             "end): give a path that does not exist";
    }
    return "";
  }
  if (ep.rfind("tcp://", 0) == 0) {
    const std::string rest = ep.substr(6);
    const auto colon = rest.rfind(':');
    if (colon == std::string::npos) return "expected tcp://HOST:PORT, e.g. tcp://127.0.0.1:5555";
    const std::string port = rest.substr(colon + 1);
    const std::string host = rest.substr(0, colon);
    if (host.empty() && !binding)
      return "has no host; give the host participants connect to, e.g. tcp://node01:5555";
    if (binding && (host == "*" || host == "0.0.0.0" || host == "[::]" || host == "::")) {
      return "binds every interface of this host; name the one participants reach "
             "(tcp://HOST:PORT with an address, a host name or an interface such as eth0), or "
             "leave HOST out (tcp://:PORT) for the address of this host's name";
    }
    if (port == "*") {
      if (binding) return "";
      return "a participant cannot connect to port '*'; give the port the orchestrator binds";
    }
    if (port.empty() || port.size() > 5 ||
        port.find_first_not_of("0123456789") != std::string::npos)
      return "port '" + port + "' is not a number; expected 1 .. 65535";
    const long p = std::stol(port);
    if (p < 1 || p > 65535)
      return "port " + port + " is outside 1 .. 65535; give a port in that range";
    return "";
  }
  return "must start with ipc:// or tcp://";
}

TransportSection parseTransport(const YAML::Node& t, const Context& ctx,
                                const std::filesystem::path& dir) {
  TransportSection out;
  if (!ctx.section(t, "transport", "{ bind: ..., connect: ..., heartbeat_timeout: ... }"))
    return out;
  ctx.allowOnly(t, "transport", TransportSection::keys());
  if (t["bind"]) out.bind = ctx.text(t["bind"], "transport.bind");
  if (t["connect"]) out.connect = ctx.text(t["connect"], "transport.connect");
  for (const auto* key : {"bind", "connect"}) {
    const std::string& ep = std::string(key) == "bind" ? out.bind : out.connect;
    if (ep.empty()) continue;
    if (const std::string why = endpointProblem(ep, std::string(key) == "bind"); !why.empty()) {
      ctx.fail(t[key], std::string("transport.") + key, "endpoint '" + ep + "' " + why);
    }
  }
  if (t["heartbeat_timeout"])
    out.heartbeat_timeout = ctx.inRange(t["heartbeat_timeout"], "transport.heartbeat_timeout", 1e-3,
                                        limits::kMaxTimeout, "seconds");
  if (t["handshake_timeout"])
    out.handshake_timeout = ctx.inRange(t["handshake_timeout"], "transport.handshake_timeout", 1e-3,
                                        limits::kMaxTimeout, "seconds");
  if (t["insecure"]) {
    const std::string v = ctx.text(t["insecure"], "transport.insecure");
    if (v != "true" && v != "false")
      ctx.fail(t["insecure"], "transport.insecure", "expected true or false, got '" + v + "'");
    out.insecure = v == "true";
  }
  if (t["key_file"]) {
    const std::string f = ctx.text(t["key_file"], "transport.key_file");
    if (f.empty()) ctx.fail(t["key_file"], "transport.key_file", "expected a file name");
    const char* home = std::getenv("HOME");
    if (f.rfind("~/", 0) == 0 && home != nullptr)
      out.key_file = std::filesystem::path(home) / f.substr(2);
    else
      out.key_file = std::filesystem::path(f).is_absolute() ? std::filesystem::path(f) : dir / f;
  }
  return out;
}

}  // namespace cosim::orchestrator

#include "scenario/transport_section.h"

#include <filesystem>

#include "scenario/limits.h"

namespace cosim::orchestrator {

const std::vector<KeySpec>& TransportSection::keys() {
  static const std::vector<KeySpec> k = {
      {"bind", "ipc:///tmp/cosim-RUN.ipc",
       "the orchestrator's socket: ipc://PATH (a file that does not exist yet) or "
       "tcp://HOST:PORT (port 1 .. 65535 or *)"},
      {"connect", "bind", "the address participants connect to, if not the bind address"},
      {"heartbeat_timeout", "10", "seconds without a sign of life from a participant; > 0"},
      {"handshake_timeout", "60", "seconds for every participant to connect and say Hello; > 0"},
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
    if (colon == std::string::npos || colon == 0)
      return "expected tcp://HOST:PORT, e.g. tcp://127.0.0.1:5555";
    const std::string port = rest.substr(colon + 1);
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

TransportSection parseTransport(const YAML::Node& t, const Context& ctx) {
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
  return out;
}

}  // namespace cosim::orchestrator

// transport: the orchestrator's socket (the one address every participant needs), how a tcp://
// link is secured (link_security.h) and how long cosim waits for participants.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "scenario/context.h"

namespace cosim::orchestrator {

struct TransportSection {
  std::string bind;                 // empty: ipc in /tmp
  std::string connect;              // what participants connect to (defaults to bind)
  double heartbeat_timeout = 10.0;  // s without any sign of life from a participant
  double handshake_timeout = 60.0;  // s for every participant to connect and say Hello
  bool insecure = false;            // tcp:// without CurveZMQ (a warning at every run)
  std::filesystem::path key_file;   // the orchestrator's key pair; empty: defaultKeyFile()

  static const std::vector<KeySpec>& keys();
};

// `dir`: the scenario's folder, which a relative key_file is taken from.
TransportSection parseTransport(const YAML::Node& node, const Context& ctx,
                                const std::filesystem::path& dir);

// Empty if `endpoint` is an ipc:// or tcp:// address cosim can use (`binding`: the
// orchestrator's own, where a tcp port may be '*', the host may be left out (the address of this
// host's name) but not be every interface, and an ipc file must not exist yet), else what is
// wrong with it.
std::string endpointProblem(const std::string& endpoint, bool binding);

}  // namespace cosim::orchestrator

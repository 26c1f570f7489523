// How the orchestrator's link is secured (docs/protocol.md, "Security on tcp://"): ipc:// in
// the user's own folder; tcp:// with CurveZMQ under the orchestrator's long-term key pair and
// keys issued to each participant for one run, or, with transport.insecure, plain.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "cosim/link/curve_keys.h"
#include "scenario/transport_section.h"

namespace cosim::orchestrator {

// $XDG_CONFIG_HOME/cosim/orchestrator.key, else ~/.config/cosim/orchestrator.key.
std::filesystem::path defaultKeyFile();
// transport.key_file, or the default.
std::filesystem::path keyFileOf(const TransportSection& t);

bool isTcp(const std::string& endpoint);

// The address to bind: tcp://:PORT becomes tcp://<the address of this host's name>:PORT; any
// other endpoint is returned as it is. Throws std::runtime_error if the name has no address.
std::string bindAddress(const std::string& bind);

// The file in the run folder that holds the keys of a participant of launch: external.
std::filesystem::path participantKeyFile(const std::filesystem::path& run_folder,
                                         const std::string& participant);

// The orchestrator's key pair when the link `bind` is tcp:// and not insecure; nullopt for
// ipc:// and insecure tcp://. Throws std::runtime_error saying what to do (cosim keys,
// transport.key_file, transport.insecure) when the keys cannot be had.
std::optional<link::CurveKeyPair> orchestratorKeys(const TransportSection& t,
                                                   const std::string& bind);

// One line for `cosim validate`: where the link is and whether it is encrypted.
std::string linkDescription(const TransportSection& t);

}  // namespace cosim::orchestrator

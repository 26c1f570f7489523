// The run token: a random secret the orchestrator makes for each run (and each resume). A
// participant proves it belongs to the run by carrying it in every message (Header.token); the
// orchestrator hands it to the processes it starts through the environment variable
// COSIM_RUN_TOKEN and, for participants of `launch: external`, writes it to a file in the run
// folder that only the user can read (--token-file). Anything else that reaches the
// orchestrator's socket is a stranger: dropped, never able to abort or join the run.
#pragma once

#include <filesystem>
#include <string>

namespace cosim::orchestrator {

// The file in the run folder that holds the token for external participants.
inline constexpr const char* kRunTokenFile = ".cosim-run-token";

// 128 random bits as 32 hexadecimal digits.
std::string newRunToken();

// Compares in time independent of where the two differ. An empty token never matches.
bool sameToken(const std::string& given, const std::string& expected);

// Writes `token` to folder/.cosim-run-token, readable by the user only (mode 0600; a file left
// there by an earlier run is replaced). Returns the path; throws std::runtime_error naming it.
std::filesystem::path writeRunTokenFile(const std::filesystem::path& folder,
                                        const std::string& token);

}  // namespace cosim::orchestrator

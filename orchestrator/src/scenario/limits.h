// Limits on scenario input that no real scene comes near; each refuses a hostile or broken file
// with a clear error instead of a crash, a hang or a run that never ends. Listed with what each
// bad input gives in docs/when-things-go-wrong.md.
#pragma once

#include <cstddef>

namespace cosim::orchestrator::limits {

inline constexpr std::size_t kMaxFileBytes = 1 << 20;  // a scenario file (or --set value)
inline constexpr std::size_t kMaxNodes = 100'000;      // YAML nodes, aliases expanded
inline constexpr int kMaxNesting = 64;                 // maps and lists inside each other
inline constexpr double kMaxSteps = 1e9;               // coupling steps of one run
inline constexpr double kMaxTimeout = 1e6;             // seconds (about 11 days)
inline constexpr std::size_t kMaxNameLength = 100;     // a scene name or output folder part
inline constexpr double kRankBytes = 50e6;  // the least memory one MPI rank of a solver takes

}  // namespace cosim::orchestrator::limits

// A request to stop, handed to what must answer it (the coupling loop, the wait for the
// participants) instead of being read from a global. The process's own one is set by the
// Ctrl-C/SIGTERM handler (orchestrator/src/commands/common.cpp); a test or an embedding program
// makes its own and requests the stop from any thread. Lock-free: safe to set from a signal
// handler.
#pragma once

#include <atomic>

namespace cosim::util {

class StopRequest {
 public:
  // Asked to stop by `signal` (or 0 for a request from code); counts the requests (a second
  // Ctrl-C stops at once).
  void request(int signal = 0) noexcept {
    signal_.store(signal);
    count_.fetch_add(1);
  }
  bool requested() const noexcept { return count_.load() > 0; }
  int count() const noexcept { return count_.load(); }
  int signal() const noexcept { return signal_.load(); }

 private:
  std::atomic<int> signal_{0};
  std::atomic<int> count_{0};
};
static_assert(std::atomic<int>::is_always_lock_free, "set from a signal handler");

}  // namespace cosim::util

// The terms of every coupling interval of a run, in order (cosim bench: the coupled stage
// records them, the solver-alone stages replay them, so each solver alone does the work it did
// coupled).
//
// Each interval is kept as the wire would carry it, in a block of memory mapped for it alone and
// never in the process heap: recorded there (6-9 MB an interval at 65,000 parcels), the terms
// would take the heap's free space, so that every timed step's messages were built in pages
// fresh from the kernel and the bench's coupled stage paid page faults a run never pays (a send
// of 25 ms a step against 4 ms in the same bed's run; docs/performance.md, "cosim bench --from").
#pragma once

#include <cstddef>
#include <vector>

#include "cosim/models/coupling_terms.h"

namespace cosim::orchestrator {

class TermsRecording {
 public:
  TermsRecording() = default;
  TermsRecording(const TermsRecording&) = delete;
  TermsRecording& operator=(const TermsRecording&) = delete;
  ~TermsRecording();

  void push_back(const models::CouplingTerms& terms);
  // A copy of interval k's terms (k < size()).
  models::CouplingTerms operator[](std::size_t k) const;
  std::size_t size() const { return blocks_.size(); }
  bool empty() const { return blocks_.empty(); }

 private:
  struct Block {
    void* data = nullptr;
    std::size_t bytes = 0;  // mapped
  };
  std::vector<Block> blocks_;
};

}  // namespace cosim::orchestrator

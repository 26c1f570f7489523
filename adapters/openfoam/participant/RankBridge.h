// Forwards rank 0's commands to the other MPI ranks of a decomposed cosimFoam, so the
// orchestrator talks to one participant. Root sends, the others receive, with the same calls.
// Without MPI (serial run) every call is a no-op. C++17, MPI only (no OpenFOAM header).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace cosim::foam {

enum class RankCommand : int {
  configure = 1,
  place = 2,
  sample = 3,
  advance = 4,
  checkpoint = 5,
  finish = 6,
  quit = 7
};

class RankBridge {
 public:
  // parallel: MPI has been initialised and the run is decomposed.
  explicit RankBridge(bool parallel);

  bool parallel() const { return parallel_; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }

  // Root: sends cmd. Others: return the command the root sent.
  RankCommand command(RankCommand cmd = RankCommand::quit) const;

  // Root's value is copied to every rank.
  void share(double& value) const;
  void share(std::string& value) const;
  void share(std::vector<double>& values) const;
  void share(std::vector<std::int64_t>& values) const;
  void share(std::vector<std::string>& values) const;

  // Stops every rank at once (used when rank 0 fails mid-run so nobody waits forever).
  [[noreturn]] void abortAll(int code) const;

 private:
  bool parallel_ = false;
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace cosim::foam

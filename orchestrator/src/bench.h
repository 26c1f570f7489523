// cosim bench: what a coupled step costs against its solvers alone, on the same scene.
//   coupled  the scene as `cosim run` runs it (its coupling.scheme); runs first and records the
//            terms of every interval
//   dem      the particles alone under the recorded forcing, interval by interval; the fluid
//            idles (FrozenScheme, particles alone)
//   cfd      the fluid alone with the recorded particle terms; the particles never advance
//            (FrozenScheme, fluid alone)
//   peer     the coupled step again on the rank-to-rank data path (coupling.data_path: peer),
//            unrecorded: the particles sample the gas and evaluate the laws themselves; run when
//            the scene takes that path or `peer` is asked for, never with `from` (a run keeps the
//            data path it began with)
// Each from the scene's initial state, or with `from` each from a copy of that run's newest
// checkpoint (cosim pack's copy, resumed; the run itself is not written), timed per step after
// `warmup` untimed steps, with its phases. Without the coupled stage the alone stages replay their
// first interval's terms. The last line printed is `coupled/max(dem,cfd) = R; serial share = S %`,
// after `peer/max(dem,cfd) = R; serial share = S %` when the peer stage ran.
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "cosim/util/stop_request.h"

namespace cosim::orchestrator {

struct BenchOptions {
  std::filesystem::path scenario;  // empty with `from`
  std::filesystem::path from;      // a stopped run: the stages continue copies of it
  std::vector<std::string> sets, unsets;
  std::uint64_t steps = 50;      // timed coupling steps per stage
  std::uint64_t warmup = 5;      // untimed steps before them
  std::filesystem::path output;  // default runs/<scenario>-bench; one run folder per stage
  std::vector<std::string> stages{"coupled", "dem", "cfd"};
  bool peer = false;  // add the peer stage (added anyway when the scene's data_path is peer)
  const util::StopRequest* stop = nullptr;  // Ctrl-C: the stage under way stops
};

// Seconds per step of one stage: its phases (fluid_sample, models, advance, bookkeeping) and the
// compute time each participant reported.
struct BenchStage {
  std::string name;
  std::uint64_t steps = 0;
  std::map<std::string, double> phases;
  std::map<std::string, double> compute;
  double total() const;
  double serial() const;  // everything but the advance
};

struct BenchRatios {
  double coupled_over_max = 0;     // coupled / max(dem, cfd)
  double serial_percent = 0;       // serial part of the coupled step, %
  double peer_over_max = 0;        // peer / max(dem, cfd), 0 without the peer stage
  double peer_serial_percent = 0;  // what of the peer stage's step is not the advance, %
};
BenchRatios benchRatios(const std::map<std::string, BenchStage>& stages);

// Runs the stages, prints the table and the ratios to `out`; non-zero if a stage failed.
int runBench(const BenchOptions& options, std::ostream& out);

}  // namespace cosim::orchestrator

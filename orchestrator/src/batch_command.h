// `cosim batch`: a whole coating batch (minutes to an hour) from a recorded run, by the long-time
// model of analysis/long_time.h (docs/physics.md, "Coating over a whole batch").
//   cosim batch RUN [--until 3600] [--times 20,60,1200] [--from T] [--rings R] [--layers L] [--step
//   S]
//                   [--seed 1] [--to T] [-o FOLDER]
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace cosim::orchestrator {

struct BatchOptions {
  std::string run;
  double until = 3600;        // [s] the batch's length
  std::vector<double> times;  // [s] more times to report (besides a grid up to `until`)
  double from = 0;            // [s] the record used starts here (skip the start-up)
  double to = -1;  // [s] the record used ends here; the run's later snapshots check the model
  // The compartments; 0 for both: the grid the record holds best, each candidate checked on the
  // record's second half (long_time_check.h). One given: the other 6 rings or 8 layers.
  int rings = 0;
  int layers = 0;
  // The model's step [s]; 0: the step the record holds best (with the grid, chosen together).
  double step = 0;
  std::uint64_t seed = 1;
  std::string output;  // folder for batch.json and batch.csv (default RUN/batch)
};

CLI::App* addBatchCommand(CLI::App& app, BatchOptions& options);
int runBatchCommand(const BatchOptions& options, std::ostream& out, std::ostream& err);

}  // namespace cosim::orchestrator

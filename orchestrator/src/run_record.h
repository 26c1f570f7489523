// What a run leaves behind, in its run folder: scenario.resolved.yaml, the time series (one row
// per coupling step, columns by name), the particle snapshots, the log, and at the end
// summary.json with the observables. It also keeps the series in memory for the observables.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cosim/analysis/summary.h"
#include "cosim/link/particle_data.h"
#include "observables.h"
#include "plan.h"
#include "run_log.h"
#include "scenario.h"

namespace cosim::analysis {
class ParticleRecorder;
class TimeSeriesRecorder;
}  // namespace cosim::analysis

namespace cosim::orchestrator {

// A time-series row by column name; a column without a value is recorded as 0.
using Row = std::map<std::string, double>;

// Whether a run that is alive holds `folder` (its lock file): the holder ("pid 1234") if so.
std::optional<std::string> runFolderInUse(const std::filesystem::path& folder);

// Whether `a` is `b` or lies inside it (paths made absolute and normalised, links resolved as
// far as they exist).
bool within(const std::filesystem::path& a, const std::filesystem::path& b);

class RunRecord {
 public:
  RunRecord(const Scenario& sc, const Plan& plan, RunLog& log);
  ~RunRecord();

  // The run folder. `output` (cosim run -o) if given: refused with a std::runtime_error saying
  // what to do if it exists and is not empty, unless `overwrite`. Else the scenario's
  // output.folder, never overwritten: the next free "-2", "-3" ... is taken (unless
  // `overwrite`). Writes scenario.resolved.yaml and opens cosim.log there.
  const std::filesystem::path& open(const std::filesystem::path& output, bool overwrite);
  const std::filesystem::path& folder() const { return folder_; }
  void writeResolvedScene() const;

  // Resume: the run continues in `folder` (cosim.log appended to; scenario.resolved.yaml is
  // rewritten once the checkpoint has accepted the scene, writeResolvedScene).
  const std::filesystem::path& reopen(const std::filesystem::path& folder);

  // Opens particles.h5 (with `run_id` and the scene's cg at its root) and timeseries.csv with the
  // columns this scene records.
  void startRecorders(const std::string& run_id);
  // Resume: cuts timeseries.csv back to `rows` rows and particles.h5 back to `time`, then
  // continues both; the observables see the rows kept. The run keeps the id particles.h5 was
  // created with (`run_id` only for a file recorded without one).
  void resumeRecorders(std::size_t rows, double time, double next_output,
                       const std::string& run_id);
  // The run's id as recorded at the root of particles.h5; "" before the recorders start.
  std::string runId() const;
  std::size_t rows() const { return series_time_.size(); }
  double nextOutput() const { return next_output_; }
  const std::vector<std::string>& columns() const { return columns_; }

  void row(double time, const Row& values);
  // A particle snapshot every output.interval (and whenever `force`).
  void snapshot(double time, const link::ParticleData& held, bool force);
  // Whether snapshot(time, ..., force) would write one.
  bool snapshotDue(double time, bool force) const;
  bool recording() const { return particles_ != nullptr; }  // the particle file is open

  // The scenario's observables over the final state, the recorded series and the totals.
  // Throws std::runtime_error naming the observable that cannot be evaluated.
  std::vector<ObservableValue> observables(const link::ParticleData& final_state,
                                           const std::map<std::string, double>& totals) const;

  // summary.json; a failure to write it is reported, not thrown (the run's own outcome counts).
  void summary(const analysis::Summary& s);

 private:
  void makeColumns();
  // Claims `folder` for this run (an flock on its lock file, held and then removed when the
  // record is destroyed); false if a run that is still alive holds it.
  bool claim(const std::filesystem::path& folder);
  // Gives a claim up again (removes the lock file).
  void release();
  const Scenario& sc_;
  const Plan& plan_;
  RunLog& log_;
  std::filesystem::path folder_;
  std::filesystem::path lock_;
  int lock_fd_ = -1;
  std::vector<std::string> columns_;
  std::unique_ptr<analysis::ParticleRecorder> particles_;
  std::unique_ptr<analysis::TimeSeriesRecorder> series_file_;
  std::vector<double> series_time_;
  std::map<std::string, std::vector<double>> series_;
  double next_output_ = 0.0;
};

}  // namespace cosim::orchestrator

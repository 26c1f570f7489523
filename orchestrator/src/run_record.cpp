#include "run_record.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "cosim/analysis/files.h"
#include "cosim/analysis/particle_recorder.h"
#include "cosim/analysis/time_series.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;

RunRecord::RunRecord(const Scenario& sc, const Plan& plan, RunLog& log)
    : sc_(sc), plan_(plan), log_(log) {}

RunRecord::~RunRecord() {
  if (!lock_.empty()) {
    std::error_code ec;
    fs::remove(lock_, ec);
  }
}

namespace {

constexpr const char* kLockFile = ".cosim-run.lock";

// Pid in a lock file; 0 if unreadable.
long lockHolder(const fs::path& lock) {
  std::ifstream in(lock);
  long pid = 0;
  in >> pid;
  return pid;
}

}  // namespace

// The run folder is claimed with a lock file created exclusively (O_EXCL): two runs can never
// share a folder. A lock left by a run that no longer exists (kill -9) is taken over.
bool RunRecord::claim(const fs::path& folder) {
  fs::create_directories(folder);
  const fs::path lock = folder / kLockFile;
  for (int attempt = 0; attempt < 2; ++attempt) {
    const int fd = ::open(lock.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
    if (fd >= 0) {
      const std::string pid = std::to_string(::getpid()) + "\n";
      const bool ok = ::write(fd, pid.data(), pid.size()) == static_cast<ssize_t>(pid.size());
      ::close(fd);
      if (!ok) throw std::runtime_error("cannot write " + lock.string() + " (disk full?)");
      lock_ = lock;
      return true;
    }
    if (errno != EEXIST) {
      throw std::runtime_error("cannot claim the run folder " + folder.string() + ": " +
                               std::strerror(errno));
    }
    const long holder = lockHolder(lock);
    if (holder > 0 && (::kill(static_cast<pid_t>(holder), 0) == 0 || errno == EPERM))
      return false;  // a run that is alive holds it
    std::error_code ec;
    fs::remove(lock, ec);  // stale: its run is gone
  }
  return false;
}

const fs::path& RunRecord::open(const fs::path& output, bool overwrite) {
  const fs::path base = output.empty() ? sc_.output.folder : fs::absolute(output);
  // Never overwrite a previous result, never share a folder with a run going on: the first
  // free one of base, base-2, base-3, ... (with overwrite: base itself, if no run holds it).
  for (int i = 1;; ++i) {
    const fs::path candidate = i == 1 ? base : fs::path(base.string() + "-" + std::to_string(i));
    const bool had_files = fs::exists(candidate) && !fs::is_empty(candidate);
    if (had_files && !overwrite) continue;
    if (claim(candidate)) {
      folder_ = candidate;
      break;
    }
    if (overwrite) {
      throw std::runtime_error("the run folder " + candidate.string() +
                               " is in use by another run (pid " +
                               std::to_string(lockHolder(candidate / kLockFile)) +
                               "); wait for it or choose another folder");
    }
  }
  writeResolvedScene();
  log_.open(folder_ / "cosim.log");
  next_output_ = sc_.coupling.start_time;
  return folder_;
}

const fs::path& RunRecord::reopen(const fs::path& folder) {
  if (!claim(folder)) {
    throw std::runtime_error("the run folder " + folder.string() +
                             " is in use by another run (pid " +
                             std::to_string(lockHolder(folder / kLockFile)) +
                             "); a run can be resumed once it has stopped");
  }
  folder_ = folder;
  log_.open(folder_ / "cosim.log");
  return folder_;
}

void RunRecord::writeResolvedScene() const {
  std::ostringstream os;
  os << "# " << sc_.file.string() << " as run (parameters substituted, --set applied)\n";
  os << sc_.resolved << "\n";
  analysis::writeFileAtomically(folder_ / "scenario.resolved.yaml", os.str());
}

void RunRecord::resumeRecorders(std::size_t rows, double time, double next_output) {
  makeColumns();
  const fs::path csv = folder_ / analysis::kTimeSeriesFile;
  analysis::truncateTimeSeries(csv, rows);
  const analysis::TimeSeries kept = analysis::readTimeSeries(csv);
  series_time_ = kept.rows() ? kept.at(analysis::column::time) : std::vector<double>{};
  for (const auto& c : columns_) series_[c] = kept.rows() ? kept.at(c) : std::vector<double>{};
  series_file_ = std::make_unique<analysis::TimeSeriesRecorder>(
      csv, columns_, analysis::TimeSeriesRecorder::Mode::append);
  particles_ = std::make_unique<analysis::ParticleRecorder>(
      folder_, plan_.particles_send, analysis::ParticleRecorder::Mode::append);
  particles_->truncateAfter(time);
  next_output_ = next_output;
}

void RunRecord::startRecorders() {
  particles_ = std::make_unique<analysis::ParticleRecorder>(folder_, plan_.particles_send);
  makeColumns();
  series_file_ =
      std::make_unique<analysis::TimeSeriesRecorder>(folder_ / analysis::kTimeSeriesFile, columns_);
}

void RunRecord::makeColumns() { columns_ = timeSeriesColumns(plan_); }

void RunRecord::row(double time, const Row& values) {
  std::vector<double> r;
  r.reserve(columns_.size());
  for (const auto& c : columns_) {
    auto it = values.find(c);
    r.push_back(it == values.end() ? 0.0 : it->second);
  }
  series_file_->write(time, r);
  series_time_.push_back(time);
  for (std::size_t c = 0; c < r.size(); ++c) series_[columns_[c]].push_back(r[c]);
}

void RunRecord::snapshot(double time, const link::ParticleData& held, bool force) {
  if (!force && time + 1e-12 * std::max(1.0, std::fabs(time)) < next_output_) return;
  particles_->write(time, held);
  next_output_ = time + sc_.output.interval;
}

std::vector<ObservableValue> RunRecord::observables(
    const link::ParticleData& final_state, const std::map<std::string, double>& totals) const {
  std::vector<ObservableValue> values;
  for (const auto& spec : sc_.observables) {
    ObservableValue v;
    v.name = spec.name;
    try {
      v.value =
          evaluateQuantity(spec.quantity, final_state, series_time_, series_, totals, spec.after);
    } catch (const UndefinedQuantity& e) {
      v.value = std::numeric_limits<double>::quiet_NaN();
      v.undefined = e.what();
    } catch (const std::exception& e) {
      throw std::runtime_error("observables." + spec.name + ": " + e.what());
    }
    v.reference = spec.reference;
    if (v.undefined.empty()) v.relative_error = relativeError(v.value, v.reference);
    values.push_back(v);
  }
  return values;
}

void RunRecord::summary(const analysis::Summary& s) {
  try {
    analysis::writeSummary(folder_ / analysis::kSummaryFile, s);
  } catch (const std::exception& e) {
    log_.warn(std::string("could not write the summary: ") + e.what() +
              "; the run's status: " + s.status + (s.message.empty() ? "" : ": " + s.message));
  }
}

}  // namespace cosim::orchestrator

#include "run_record.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "checkpoints.h"
#include "cosim/analysis/files.h"
#include "cosim/analysis/particle_recorder.h"
#include "cosim/analysis/time_series.h"
#include "cosim/util/errors.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;

RunRecord::RunRecord(const Scenario& sc, const Plan& plan, RunLog& log)
    : sc_(sc), plan_(plan), log_(log) {}

RunRecord::~RunRecord() { release(); }

namespace {

constexpr const char* kLockFile = ".cosim-run.lock";

// Pid in a lock file; 0 if unreadable (or not yet written by the run that holds it).
long lockHolder(const fs::path& lock) {
  std::ifstream in(lock);
  long pid = 0;
  in >> pid;
  return pid;
}

// Whether a live run holds the lock file: the kernel drops a run's flock when the run ends in
// any way (kill -9 included), so a lock left behind by a dead run is free.
bool lockIsHeld(const fs::path& lock) {
  const int fd = ::open(lock.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool held = ::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  ::close(fd);
  return held;
}

std::string holderText(const fs::path& lock) {
  const long pid = lockHolder(lock);
  return pid > 0 ? "pid " + std::to_string(pid) : "pid unknown";
}

// Whether `folder` holds anything besides our lock file.
bool holdsRunFiles(const fs::path& folder) {
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.path().filename() != kLockFile) return true;
  return false;
}

// Why `folder`, given with -o, is not used, and what to do instead.
std::string refusal(const fs::path& folder) {
  const std::string f = folder.string();
  if (!fs::is_directory(folder))
    return "cannot record the run in " + f +
           ": it exists and is not a folder; choose another run folder with -o";
  std::string what = "the run folder " + f + " already exists and is not empty";
  std::string how = "choose another folder with -o, remove this one first (rm -r " + f +
                    "), or add --overwrite to write into it anyway";
  if (lockIsHeld(folder / kLockFile))
    return what + "; a run (" + holderText(folder / kLockFile) +
           ") is writing into it now: choose another folder with -o";
  try {
    const auto summary = analysis::readJsonFile(folder / analysis::kSummaryFile);
    what += " (it holds a " + summary.at("status").get<std::string>() + " run of '" +
            summary.at("scenario").get<std::string>() + "')";
  } catch (const std::exception&) {
  }
  if (const auto checkpoint = CheckpointStore(folder).newest()) {
    how += "; it holds a checkpoint at t = " + checkpoint->filename().string() +
           " s: to continue that run instead, cosim resume " + f;
  }
  return what + ", and cosim never records a run over another one: " + how;
}

// Why recording a run in `folder` would write over the scene itself (its folder, its scenario
// file, a participant's files: folder, which the run copies into folder/<participant>), or
// nothing if it would not.
std::optional<std::string> overScene(const fs::path& folder, const Scenario& sc) {
  const std::string f = folder.string();
  if (!sc.dir.empty() && within(sc.dir, folder) && within(folder, sc.dir))
    return "the run folder " + f + " is the scene's own folder (" + sc.dir.string() +
           "): a run is never recorded over the scene it runs; choose another folder with -o";
  for (const auto& [name, p] : sc.participants) {
    const fs::path target = folder / name;
    for (const fs::path& source : {p.files, sc.file}) {
      if (source.empty()) continue;
      if (within(source, target) || within(target, source))
        return "the run folder " + f + " would put participant '" + name + "' in " +
               target.string() + ", over the scene's " + source.string() +
               ": a run is never recorded over the scene it runs; choose another folder with -o";
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> runFolderInUse(const fs::path& folder) {
  const fs::path lock = folder / kLockFile;
  if (!lockIsHeld(lock)) return std::nullopt;
  return holderText(lock);
}

// Whether `a` is `b` or lies inside it (paths made absolute and normalised, links resolved as
// far as they exist).
bool within(const fs::path& a, const fs::path& b) {
  const fs::path rel = fs::weakly_canonical(a).lexically_relative(fs::weakly_canonical(b));
  return !rel.empty() && *rel.begin() != "..";
}

// The run folder is claimed with an exclusive flock on its lock file, held for the whole run:
// two runs can never share a folder, and the lock of a run that died (kill -9) is free again
// because the kernel drops it with the process. The file is unlinked while still locked when
// the run ends; a run that locked the file just before it was unlinked sees that its file is no
// longer the one at the path and tries again.
bool RunRecord::claim(const fs::path& folder) {
  std::error_code made;
  fs::create_directories(folder, made);
  if (made)
    throw Error(kindOfErrno(made.value()),
                "cannot create the run folder " + folder.string() + ": " + made.message() +
                    "; choose a folder you can write to with -o (or output.folder)");
  const fs::path lock = folder / kLockFile;
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
      const int err = errno;
      throw Error(kindOfErrno(err),
                  "cannot claim the run folder " + folder.string() + ": " + std::strerror(err));
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      ::close(fd);
      if (err == EWOULDBLOCK) return false;  // a run that is alive holds it
      throw Error(kindOfErrno(err), "cannot lock " + lock.string() + ": " + std::strerror(err));
    }
    struct stat held {};
    struct stat at_path {};
    if (::fstat(fd, &held) != 0 || ::stat(lock.c_str(), &at_path) != 0 ||
        held.st_ino != at_path.st_ino || held.st_dev != at_path.st_dev) {
      ::close(fd);  // the run that held it removed it meanwhile: lock the new one
      continue;
    }
    const std::string pid = std::to_string(::getpid()) + "\n";
    const bool ok = ::ftruncate(fd, 0) == 0 &&
                    ::pwrite(fd, pid.data(), pid.size(), 0) == static_cast<ssize_t>(pid.size());
    if (!ok) {
      ::close(fd);
      throw ResourceError("cannot write " + lock.string() + " (disk full?)");
    }
    lock_ = lock;
    lock_fd_ = fd;
    return true;
  }
  return false;
}

// The file is removed while still locked, so no run can lock it after we let it go.
void RunRecord::release() {
  if (lock_fd_ < 0) return;
  std::error_code ec;
  fs::remove(lock_, ec);
  ::close(lock_fd_);
  lock_fd_ = -1;
  lock_.clear();
}

const fs::path& RunRecord::open(const fs::path& output, bool overwrite) {
  const fs::path base = output.empty() ? sc_.output.folder : fs::absolute(output);
  if (const auto why = overScene(base, sc_)) throw InputError(*why);
  // A folder the user named (-o) is that run's folder or none: refused if it holds anything
  // (or a run holds it), never replaced by another name the user would not look in.
  if (!output.empty()) {
    const bool used = fs::exists(base) && (!fs::is_directory(base) || !fs::is_empty(base));
    if (used && !overwrite) throw InputError(refusal(base));
    if (!claim(base)) {
      throw InputError(overwrite
                           ? "the run folder " + base.string() + " is in use by another run (" +
                                 holderText(base / kLockFile) +
                                 "); wait for it or choose another folder with -o"
                           : refusal(base));
    }
    // A run that held the folder may have finished between the look above and our claim.
    if (!overwrite && holdsRunFiles(base)) {
      release();
      throw InputError(refusal(base));
    }
    folder_ = base;
    writeResolvedScene();
    log_.open(folder_ / "cosim.log");
    next_output_ = sc_.coupling.start_time;
    return folder_;
  }
  // The scene's own folder: never overwrite a previous result, never share a folder with a run
  // going on: the first free one of base, base-2, base-3, ... (with overwrite: base itself, if
  // no run holds it).
  for (int i = 1;; ++i) {
    const fs::path candidate = i == 1 ? base : fs::path(base.string() + "-" + std::to_string(i));
    const bool had_files = fs::exists(candidate) && !fs::is_empty(candidate);
    if (had_files && !overwrite) continue;
    if (claim(candidate)) {
      // A run that held it may have finished between the look above and our claim.
      if (!overwrite && holdsRunFiles(candidate)) {
        release();
        continue;
      }
      folder_ = candidate;
      break;
    }
    if (overwrite) {
      throw InputError("the run folder " + candidate.string() + " is in use by another run (" +
                       holderText(candidate / kLockFile) +
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
    throw InputError("the run folder " + folder.string() + " is in use by another run (" +
                     holderText(folder / kLockFile) +
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

void RunRecord::resumeRecorders(std::size_t rows, double time, double next_output,
                                const std::string& run_id) {
  makeColumns();
  const fs::path csv = folder_ / analysis::kTimeSeriesFile;
  analysis::truncateTimeSeries(csv, rows);
  const analysis::TimeSeries kept = analysis::readTimeSeries(csv);
  series_time_ = kept.rows() ? kept.at(analysis::column::time) : std::vector<double>{};
  for (const auto& c : columns_) series_[c] = kept.rows() ? kept.at(c) : std::vector<double>{};
  series_file_ = std::make_unique<analysis::TimeSeriesRecorder>(
      csv, columns_, analysis::TimeSeriesRecorder::Mode::append);
  particles_ = std::make_unique<analysis::ParticleRecorder>(
      folder_, plan_.particles_send, analysis::RunIdentity{run_id, sc_.constants.cg},
      analysis::ParticleRecorder::Mode::append);
  // Snapshots after the checkpoint go, and so does one a stopped run wrote off the output times
  // (the parcels at the stop, so that its records ended together): the resumed run's file reads
  // as one that never stopped. The last one on the output times is at next_output - interval.
  const double scheduled = next_output - sc_.output.interval;
  particles_->truncateAfter(std::min(
      time, scheduled + 1e-9 * std::max({1.0, std::fabs(scheduled), sc_.output.interval})));
  next_output_ = next_output;
}

std::string RunRecord::runId() const { return particles_ ? particles_->identity().run_id : ""; }

void RunRecord::startRecorders(const std::string& run_id) {
  particles_ = std::make_unique<analysis::ParticleRecorder>(
      folder_, plan_.particles_send, analysis::RunIdentity{run_id, sc_.constants.cg});
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

bool RunRecord::snapshotDue(double time, bool force) const {
  return force || time + 1e-12 * std::max(1.0, std::fabs(time)) >= next_output_;
}

void RunRecord::snapshot(double time, const link::ParticleData& held, bool force) {
  if (!snapshotDue(time, force)) return;
  particles_->write(time, held);
  // The next time on the grid start_time + k interval: a snapshot forced off the grid (a run's
  // end, a stop) or a step that does not divide the interval does not shift the ones after it
  const double start = sc_.coupling.start_time;
  const double interval = sc_.output.interval;
  next_output_ = interval > 0
                     ? start + (std::floor((time - start) / interval + 1e-9) + 1.0) * interval
                     : time;  // every step
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
      throw Error(kindOf(e, ErrorKind::input), "observables." + spec.name + ": " + e.what());
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

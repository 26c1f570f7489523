// cosim pack: what a stopped run needs to continue elsewhere (run_pack.h).
#include "run_pack.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <vector>

#include "checkpoints.h"
#include "cosim/util/errors.h"
#include "run_record.h"
#include "stability.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;

namespace {

// An OpenFOAM time folder's name: a number ("0", "0.25", "1e-05")
std::optional<double> timeName(const fs::path& name) {
  const std::string s = name.string();
  if (s.empty()) return std::nullopt;
  char* end = nullptr;
  const double t = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size()) return std::nullopt;
  return t;
}

class Packer {
 public:
  explicit Packer(PackResult& r) : r_(r) {}

  void copy(const fs::path& from, const fs::path& to) {
    if (fs::is_directory(fs::symlink_status(from))) {
      fs::create_directories(to);
      for (const auto& e : fs::directory_iterator(from)) copy(e.path(), to / e.path().filename());
      return;
    }
    // files as they are, links as links (never followed out of the run)
    fs::copy(from, to, fs::copy_options::copy_symlinks);
    r_.copied_bytes += bytesOnDisk(from);
    ++r_.copied_files;
  }
  void leaveOut(const std::string& kind, const fs::path& p) { r_.left_out[kind] += bytesOnDisk(p); }

  // A fluid case (OpenFOAM): its time folders after the first one left out, in the case and in
  // each processorN folder of a decomposed one; the rest (mesh, settings, initial fields) copied
  void copyFoamCase(const fs::path& from, const fs::path& to) {
    fs::create_directories(to);
    std::optional<double> first;
    for (const auto& e : fs::directory_iterator(from)) {
      const auto t = e.is_directory() ? timeName(e.path().filename()) : std::nullopt;
      if (t && (!first || *t < *first)) first = t;
    }
    for (const auto& e : fs::directory_iterator(from)) {
      const fs::path name = e.path().filename();
      const auto t = e.is_directory() ? timeName(name) : std::nullopt;
      if (t && *t != *first) {
        leaveOut("the fluid's time folders after the first", e.path());
      } else if (e.is_directory() && !e.is_symlink() && name.string().rfind("processor", 0) == 0) {
        copyFoamCase(e.path(), to / name);
      } else {
        copy(e.path(), to / name);
      }
    }
  }

  // A particle case (LIGGGHTS): its dump files and its logs left out
  void copyDemCase(const fs::path& from, const fs::path& to) {
    fs::create_directories(to);
    for (const auto& e : fs::directory_iterator(from)) {
      const fs::path name = e.path().filename();
      const std::string ext = name.extension().string();
      if (e.is_directory() && !e.is_symlink()) {
        copyDemCase(e.path(), to / name);
      } else if (ext == ".dump" || ext == ".vtk" || ext == ".vtp" || ext == ".vtu") {
        leaveOut("the particles' dump files", e.path());
      } else if (ext == ".log" || ext == ".screen") {
        leaveOut("the participants' logs", e.path());
      } else {
        copy(e.path(), to / name);
      }
    }
  }

 private:
  PackResult& r_;
};

}  // namespace

PackResult packRun(const fs::path& run, const fs::path& dest, const Scenario& sc) {
  const std::string r = run.string(), d = dest.string();
  if (const auto holder = runFolderInUse(run)) {
    throw InputError("a run (" + *holder + ") is writing into " + r +
                     " now: stop it first (Ctrl-C, or kill -INT with that pid: it writes "
                     "a checkpoint and stops), then pack it");
  }
  const CheckpointStore store(run);
  const auto newest = store.newest();
  if (!newest) {
    throw InputError(r +
                     " holds no complete checkpoint, so a copy could not continue it; "
                     "runs write checkpoints with checkpoint.interval (docs/restarts.md)");
  }
  if (fs::exists(dest) && !(fs::is_directory(dest) && fs::is_empty(dest))) {
    throw InputError(d +
                     " already exists and is not an empty folder; cosim never writes "
                     "over it: choose another destination");
  }
  if (within(dest, run)) {
    throw InputError(d + " lies inside the run folder " + r + ": choose a destination outside it");
  }

  PackResult result;
  result.checkpoint = *newest;
  Packer packer(result);
  fs::path target = fs::absolute(dest).lexically_normal();
  if (target.filename().empty()) target = target.parent_path();  // "DEST/"
  const fs::path partial = target.parent_path() / (".partial-" + target.filename().string() + "-" +
                                                   std::to_string(::getpid()));
  try {
    fs::create_directories(partial);
    for (const auto& e : fs::directory_iterator(run)) {
      const fs::path name = e.path().filename();
      const std::string n = name.string();
      const auto participant = sc.participants.find(n);
      if (n == "checkpoints") {
        fs::create_directories(partial / name);
        for (const auto& c : fs::directory_iterator(e.path())) {
          if (c.path() == *newest) {
            packer.copy(c.path(), partial / name / c.path().filename());
          } else {
            packer.leaveOut("older checkpoints", c.path());
          }
        }
      } else if (participant != sc.participants.end() && e.is_directory()) {
        if (participant->second.adapter == "openfoam") {
          packer.copyFoamCase(e.path(), partial / name);
        } else if (participant->second.adapter == "liggghts") {
          packer.copyDemCase(e.path(), partial / name);
        } else {
          packer.copy(e.path(), partial / name);
        }
      } else if (name.extension() == ".log" && sc.participants.count(name.stem().string())) {
        packer.leaveOut("the participants' logs", e.path());
      } else if (n == ".cosim-run.lock" ||
                 (n.rfind(".cosim-", 0) == 0 && name.extension() == ".key")) {
        packer.leaveOut("the run's lock and key files", e.path());
      } else {
        packer.copy(e.path(), partial / name);
      }
    }
    if (fs::exists(target)) fs::remove(target);  // the empty folder checked above
    fs::rename(partial, target);
  } catch (const fs::filesystem_error& e) {
    std::error_code ec;
    fs::remove_all(partial, ec);
    throw Error(kindOfErrno(e.code().value()),
                "copying " + r + " to " + d + " failed (" + e.code().message() + " at " +
                    e.path1().string() + "); nothing was written to " + d + " and " + r +
                    " is unchanged");
  }
  return result;
}

}  // namespace cosim::orchestrator

#include "cosim/liggghts/engine.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <numeric>
#include <set>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "atom.h"
#include "cosim/liggghts/drag_relaxation_fix.h"
#include "cosim/liggghts/hertz_contact_time.h"
#include "cosim/liggghts/liggghts_error.h"
#include "cosim/liggghts/order_by_id.h"
#include "cosim/util/all_finite.h"
#include "cosim/util/errors.h"
#include "dump.h"
#include "fix.h"
#include "fix_property_atom.h"
#include "fix_property_global.h"
#include "input.h"
#include "lammps.h"
#include "memory.h"
#include "modify.h"
#include "output.h"
#include "update.h"

namespace cosim::liggghts {

using LAMMPS_NS::Fix;

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

// Line number (1-based) of the first line of `script` whose text is `command`; 0 if not found.
int lineOf(const std::filesystem::path& script, const std::string& command) {
  std::ifstream in(script);
  std::string line;
  const std::string wanted = trim(command);
  if (wanted.empty()) return 0;
  for (int n = 1; std::getline(in, line); ++n) {
    auto hash = line.find('#');
    if (trim(hash == std::string::npos ? line : line.substr(0, hash)) == wanted) return n;
  }
  return 0;
}

// Input::line (the command being executed) is protected; a derived class may name it.
struct InputLine : LAMMPS_NS::Input {
  static const char* of(LAMMPS_NS::Input* in) { return in->*(&InputLine::line); }
};

Fix* findProperty(LAMMPS_NS::Modify* modify, const char* name, const char* style,
                  const char* shape) {
  return modify->find_fix_property(name, style, shape, 0, 0, "cosim", false);
}

}  // namespace

Engine::Engine(MPI_Comm comm, const std::filesystem::path& workdir)
    : comm_(comm), workdir_(workdir) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
  const std::string screen = (workdir_ / "liggghts.screen").string();
  const std::string log = (workdir_ / "liggghts.log").string();
  // -screen none crashes LIGGGHTS 3.8 in region code: the screen always goes to a file.
  std::vector<std::string> args = {"liggghts", "-screen", screen, "-log", log, "-echo", "both"};
  std::vector<char*> argv;
  argv.reserve(args.size());
  for (auto& a : args) argv.push_back(a.data());
  guarded("starting LIGGGHTS",
          [&] { lmp_ = new LAMMPS_NS::LAMMPS(static_cast<int>(argv.size()), argv.data(), comm_); });
}

Engine::~Engine() {
  // After a LIGGGHTS error its screen/log files are closed and its output object deleted:
  // destroying the instance would free them twice, so a broken instance is left to the OS.
  if (!broken_ && lmp_) {
    LiggghtsCall call;
    try {
      delete lmp_;
    } catch (const LiggghtsStop&) {
    }
  }
}

template <class F>
void Engine::guarded(const std::string& what, F&& f) {
  if (broken_) throw SolverError("LIGGGHTS already stopped on an earlier error; cannot " + what);
  try {
    LiggghtsCall call;
    f();
  } catch (const LiggghtsStop& stop) {
    broken_ = true;
    failWithLiggghtsMessage(what, stop.aborted);
  }
}

void Engine::failWithLiggghtsMessage(const std::string& what, bool aborted) {
  std::string message;
  std::string last_command;
  if (rank_ == 0) {
    if (aborted && lmp_ && lmp_->screen) std::fflush(lmp_->screen);  // error->one leaves it open
    message = lastErrorLine(screenFile().string());
    if (lmp_ && lmp_->input && InputLine::of(lmp_->input))
      last_command = trim(InputLine::of(lmp_->input));
  }
  std::ostringstream out;
  out << "LIGGGHTS stopped with an error while " << what;
  if (!script_.empty()) {
    out << " (script " << script_.string();
    if (int n = lineOf(script_, last_command); n > 0) out << ", line " << n;
    out << ")";
  }
  out << ": " << (message.empty() ? std::string("(no ERROR line in the screen file)") : message);
  if (!last_command.empty()) out << "\n  last command: " << last_command;
  out << "\n  full LIGGGHTS output: " << screenFile().string();
  if (aborted && size_ > 1)
    out << " (the error was raised on one MPI rank; if it was not rank 0 its text is only in the"
           " job's standard error)";
  throw LiggghtsError(out.str(), aborted);
}

void Engine::runScript(const std::filesystem::path& script) {
  if (!std::filesystem::exists(script))
    throw InputError("LIGGGHTS script '" + script.string() +
                     "' does not exist (option `script` of the particles participant; "
                     "the path is relative to the participant's folder)");
  script_ = script;
  const std::string path = script.string();
  guarded("running " + path, [&] { lmp_->input->file(path.c_str()); });
  need_setup_ = true;
}

namespace {

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> w;
  for (std::string x; in >> x;) w.push_back(x);
  return w;
}

// The command a logical line of the script asks for, rewritten for a resume; "" leaves it out.
// `dropped`: ids of the fixes left out so far (their `unfix` is left out too).
std::string forResume(const std::string& command, const std::filesystem::path& restart,
                      std::set<std::string>& dropped) {
  const auto w = words(command);
  if (w.empty()) return command;
  const std::string& verb = w[0];
  if (verb == "create_box" || verb == "read_data" || verb == "read_restart")
    return "read_restart " + restart.string();
  // reset_timestep: the restart file holds the step counter of the run's clock.
  if (verb == "create_atoms" || verb == "run" || verb == "write_restart" ||
      verb == "reset_timestep")
    return "";
  // fix ID group STYLE args
  if (verb == "fix" && w.size() > 3 && w[3].rfind("insert/", 0) == 0) {
    for (std::size_t i = 4; i + 1 < w.size(); ++i) {
      if (w[i] == "insert_every" && w[i + 1] == "once") {
        dropped.insert(w[1]);
        return "";
      }
    }
  }
  if (verb == "unfix" && w.size() > 1 && dropped.count(w[1])) return "";
  return command;
}

}  // namespace

void Engine::resumeScript(const std::filesystem::path& script,
                          const std::filesystem::path& restart) {
  if (!std::filesystem::exists(script))
    throw InputError("LIGGGHTS script '" + script.string() + "' does not exist");
  if (!std::filesystem::exists(restart))
    throw InputError("cannot resume: the checkpoint has no LIGGGHTS restart file " +
                     restart.string());
  script_ = script;
  keep_restored_forces_ = std::filesystem::exists(restart.parent_path() / kOtherForcesMarker);
  // The script rewritten line for line (a left-out command becomes an empty line, a continued
  // one keeps its continuation lines as empty ones), so that LIGGGHTS reads it as a file: its
  // own flow control (label, jump SELF, next, if) works as in the run that wrote the
  // checkpoint, and every line keeps its number. Only rank 0 reads the file (LIGGGHTS
  // broadcasts its lines), so only rank 0 writes it.
  std::ifstream in(script);
  std::ostringstream out;
  std::string logical, line;
  int continued = 0;
  std::set<std::string> dropped;
  auto flush = [&] {
    const auto hash = logical.find('#');
    const std::string cmd = trim(hash == std::string::npos ? logical : logical.substr(0, hash));
    logical.clear();
    out << (cmd.empty() ? std::string() : forResume(cmd, restart, dropped)) << "\n";
    for (; continued > 0; --continued) out << "\n";
  };
  while (std::getline(in, line)) {
    const std::string t = trim(line);
    if (!t.empty() && t.back() == '&') {
      logical += t.substr(0, t.size() - 1) + " ";
      ++continued;
      continue;
    }
    logical += line;
    flush();
  }
  if (!logical.empty() || continued > 0) flush();
  const std::filesystem::path resumed =
      script.parent_path() / (script.filename().string() + ".resume");
  if (rank_ == 0) {
    std::ofstream f(resumed);
    f << out.str();
    if (!f.flush())
      throw cosim::Error(kindOfErrno(errno),
                         "cannot resume: cannot write " + resumed.string() +
                             " (the script rewritten for the resume) in the participant's "
                             "folder; is the disk full or the folder read-only?");
  }
  const std::string path = resumed.string();
  guarded("running " + script.string() + " for the resume (as " + path + ")",
          [&] { lmp_->input->file(path.c_str()); });
  need_setup_ = true;
}

void Engine::command(const std::string& line) {
  guarded("executing '" + line + "'", [&] { lmp_->input->one(line.c_str()); });
  need_setup_ = true;  // the command may have changed fixes or atoms: next run re-initialises
}

void Engine::installCoupling() {
  if (coupled_) return;
  if (!lmp_->atom->rmass_flag || !lmp_->atom->radius_flag)
    throw InputError("LIGGGHTS script " + script_.string() +
                     ": the coupling needs spherical particles with per-particle mass and "
                     "radius; use `atom_style granular` (or sphere)");
  if (!findProperty(lmp_->modify, kCoatingMassProperty, "property/atom", "scalar"))
    command(std::string("fix ") + kCoatingMassProperty + " all property/atom " +
            kCoatingMassProperty + " scalar yes no no 0");
  command(std::string("fix cosim_drag_k all property/atom ") + kDragCoefficientProperty +
          " scalar no no no 0");
  command(std::string("fix cosim_fluid_vel all property/atom ") + kFluidVelocityProperty +
          " vector no no no 0 0 0");
  command(std::string("fix cosim_explicit_f all property/atom ") + kExplicitForceProperty +
          " vector no no no 0 0 0");
  // Saved in restart files: the first step after a checkpoint or a resume starts from them
  command(std::string("fix cosim_other_f all property/atom ") + kOtherForceProperty +
          " vector yes no no 0 0 0");
  command(std::string("fix cosim_last_torque all property/atom ") + kLastTorqueProperty +
          " vector yes no no 0 0 0");

  // The drag fix is not a registered LIGGGHTS style: append it to the fix list ourselves, as
  // Modify::add_fix would, so that it is the last post_force fix.
  guarded("adding the cosim/drag fix", [&] {
    std::string id = "cosim_drag", group = "all", style = "cosim/drag";
    char* args[] = {id.data(), group.data(), style.data()};
    auto* fix = new DragRelaxationFix(lmp_, 3, args);
    drag_fix_ = fix;
    LAMMPS_NS::Modify* modify = lmp_->modify;
    if (modify->nfix == modify->maxfix) {
      modify->maxfix += 4;
      modify->fix = static_cast<Fix**>(lmp_->memory->srealloc(
          modify->fix, static_cast<LAMMPS_NS::bigint>(modify->maxfix * sizeof(Fix*)),
          "modify:fix"));
      modify->fmask = static_cast<int*>(lmp_->memory->srealloc(
          modify->fmask, static_cast<LAMMPS_NS::bigint>(modify->maxfix * sizeof(int)),
          "modify:fmask"));
    }
    modify->fix[modify->nfix] = fix;
    modify->fmask[modify->nfix] = fix->setmask();
    modify->nfix++;
    fix->post_create_pre_restart();
    fix->post_create();
  });
  coupled_ = true;
  if (keep_restored_forces_) drag_fix_->keepOtherForcesAtNextSetup();
  // LIGGGHTS sets a new fix property/atom to its default values at the first setup after its
  // creation: do that setup now, before any forcing or coating is written into them.
  guarded("setting up the coupling (run 0)", [&] { lmp_->input->one("run 0 post no"); });
  need_setup_ = false;
}

double Engine::timestep() const { return lmp_->update->dt; }

std::int64_t Engine::step() const { return lmp_->update->ntimestep; }

int Engine::dumpCount() const { return lmp_->output->ndump; }

void Engine::writeDumpsNow() {
  guarded("writing the dumps of the final state", [&] {
    LAMMPS_NS::Output* out = lmp_->output;
    const LAMMPS_NS::bigint now = lmp_->update->ntimestep;
    for (int i = 0; i < out->ndump; ++i) {
      if (out->last_dump[i] == now) continue;
      // as Output::write does at a dump's step
      if (out->dump[i]->clearstep || out->every_dump[i] == 0) lmp_->modify->clearstep_compute();
      out->dump[i]->write();
      out->last_dump[i] = now;
    }
  });
}

std::int64_t Engine::particleCount() const {
  long long local = lmp_->atom->nlocal, total = 0;
  MPI_Allreduce(&local, &total, 1, MPI_LONG_LONG, MPI_SUM, comm_);
  return total;
}

double Engine::minRadius() const {
  const int ntypes = lmp_->atom->ntypes;
  const LAMMPS_NS::Atom* atom = lmp_->atom;
  double local = std::numeric_limits<double>::max();
  for (int i = 0; i < atom->nlocal; ++i) {
    const int t = atom->type[i];
    if (t < 1 || t > ntypes) continue;
    local = std::min(local, atom->radius[i]);
  }
  double global = local;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_MIN, comm_);
  return global;
}

TimestepReport Engine::timestepReport(double impact_speed) const {
  TimestepReport report;
  report.dt = timestep();
  report.impact_speed = impact_speed;
  auto* E = dynamic_cast<LAMMPS_NS::FixPropertyGlobal*>(
      findProperty(lmp_->modify, "youngsModulus", "property/global", "peratomtype"));
  auto* nu = dynamic_cast<LAMMPS_NS::FixPropertyGlobal*>(
      findProperty(lmp_->modify, "poissonsRatio", "property/global", "peratomtype"));
  if (!E || !nu)
    throw InputError(
        "LIGGGHTS script " + script_.string() +
        " defines no `fix ... property/global youngsModulus peratomtype ...` and "
        "`poissonsRatio`; the adapter needs them to check the DEM time step (or set the option "
        "dt_check: off)");
  const int ntypes = lmp_->atom->ntypes;
  const LAMMPS_NS::Atom* atom = lmp_->atom;
  double local[3] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
                     std::numeric_limits<double>::max()};
  for (int i = 0; i < atom->nlocal; ++i) {
    const int t = atom->type[i];
    if (t < 1 || t > ntypes) continue;
    const double r = atom->radius[i];
    const double density = atom->rmass[i] / (4.0 / 3.0 * std::numbers::pi * r * r * r);
    const double e = E->compute_vector(t - 1), p = nu->compute_vector(t - 1);
    local[0] = std::min(local[0], r);
    local[1] = std::min(local[1], util::rayleighTime(r, density, e, p));
    local[2] = std::min(local[2], hertzContactTimeRigidWall(r, density, e, p, impact_speed));
  }
  double global[3];
  MPI_Allreduce(local, global, 3, MPI_DOUBLE, MPI_MIN, comm_);
  report.has_particles = global[0] < std::numeric_limits<double>::max();
  if (report.has_particles) {
    report.min_radius = global[0];
    report.rayleigh_time = global[1];
    report.hertz_time = global[2];
  }
  return report;
}

void Engine::applyTerms(const Terms& terms) {
  checkTerms(terms);
  applyCheckedTerms(terms, false);
}

void Engine::applyOwnTerms(const Terms& terms) { applyCheckedTerms(terms, true); }

void Engine::checkTerms(const Terms& terms) {
  const std::size_t n = terms.ids.size();
  auto check_size = [&](const std::vector<double>& v, std::size_t per, const char* name) {
    if (!v.empty() && v.size() != n * per)
      throw PeerError(std::string("forcing field ") + name + " has " + std::to_string(v.size()) +
                      " values for " + std::to_string(n) + " particles (expected " +
                      std::to_string(n * per) + ")");
  };
  check_size(terms.drag_coefficient, 1, "drag_coefficient");
  check_size(terms.fluid_velocity, 3, "fluid_velocity");
  check_size(terms.explicit_force, 3, "explicit_force");
  check_size(terms.coating_increment, 1, "coating_increment");

  // One pass over each field; only when it fails, the parcel-by-parcel search for the message
  bool all_clean = util::allFinite(terms.drag_coefficient) &&
                   util::allFinite(terms.fluid_velocity) && util::allFinite(terms.explicit_force) &&
                   util::allFinite(terms.coating_increment);
  for (double k : terms.drag_coefficient) all_clean &= k >= 0;
  for (std::size_t k = 0; k < n && !all_clean; ++k) {
    auto bad = [&](const std::vector<double>& v, std::size_t per) {
      for (std::size_t c = 0; c < per && !v.empty(); ++c)
        if (!std::isfinite(v[k * per + c])) return true;
      return false;
    };
    if (bad(terms.drag_coefficient, 1) || bad(terms.fluid_velocity, 3) ||
        bad(terms.explicit_force, 3) || bad(terms.coating_increment, 1))
      throw SolverError("forcing for particle id " + std::to_string(terms.ids[k]) +
                        " contains a NaN or infinite value");
    if (!terms.drag_coefficient.empty() && terms.drag_coefficient[k] < 0)
      throw SolverError("drag_coefficient of particle id " + std::to_string(terms.ids[k]) +
                        " is negative (" + std::to_string(terms.drag_coefficient[k]) +
                        " kg/s); K must be >= 0");
  }
  auto twice = [&](std::int64_t id) {
    return PeerError("forcing lists particle id " + std::to_string(id) + " twice");
  };
  {  // every id once (the orchestrator sends them in ascending order: then no copy is sorted)
    std::vector<std::int64_t> sorted;
    const std::vector<std::int64_t>* ids = &terms.ids;
    if (!std::is_sorted(ids->begin(), ids->end())) {
      sorted = terms.ids;
      std::sort(sorted.begin(), sorted.end());
      ids = &sorted;
    }
    const auto again = std::adjacent_find(ids->begin(), ids->end());
    if (again != ids->end()) throw twice(*again);
  }
}

void Engine::applyCheckedTerms(const Terms& terms, bool own) {
  const std::size_t n = terms.ids.size();

  LAMMPS_NS::Modify* modify = lmp_->modify;
  double* K =
      findProperty(modify, kDragCoefficientProperty, "property/atom", "scalar")->vector_atom;
  double** uf = findProperty(modify, kFluidVelocityProperty, "property/atom", "vector")->array_atom;
  double** fex =
      findProperty(modify, kExplicitForceProperty, "property/atom", "vector")->array_atom;
  double* coating =
      findProperty(modify, kCoatingMassProperty, "property/atom", "scalar")->vector_atom;

  LAMMPS_NS::Atom* atom = lmp_->atom;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; ++i) {
    K[i] = 0;
    for (int d = 0; d < 3; ++d) uf[i][d] = fex[i][d] = 0;
  }
  auto assign = [&](int i, std::size_t k) {
    if (!terms.drag_coefficient.empty()) K[i] = terms.drag_coefficient[k];
    for (int d = 0; d < 3; ++d) {
      if (!terms.fluid_velocity.empty()) uf[i][d] = terms.fluid_velocity[3 * k + d];
      if (!terms.explicit_force.empty()) fex[i][d] = terms.explicit_force[3 * k + d];
    }
    if (!terms.coating_increment.empty()) coating[i] += terms.coating_increment[k];
  };
  std::vector<int> found(n, 0);
  if (atom->map_style != 0) {
    // the script keeps LIGGGHTS' own id -> index map (atom_modify map array|hash): no map of ours
    for (std::size_t k = 0; k < n; ++k) {
      const std::int64_t id = terms.ids[k];
      if (id <= 0 || id > atom->map_tag_max) continue;  // not an id LIGGGHTS has (reported below)
      const int i = atom->map(static_cast<int>(id));
      if (i < 0 || i >= nlocal) continue;  // on another rank, or only a ghost here
      found[k] = 1;
      assign(i, k);
    }
  } else {
    std::unordered_map<std::int64_t, std::size_t> index;
    index.reserve(n);
    for (std::size_t k = 0; k < n; ++k) index.emplace(terms.ids[k], k);
    for (int i = 0; i < nlocal; ++i) {
      auto it = index.find(atom->tag[i]);
      if (it == index.end()) continue;
      found[it->second] = 1;
      assign(i, it->second);
    }
  }
  guarded("applying the forcing", [&] { drag_fix_->refreshForces(); });
  if (own) {
    // Each rank was sent the terms of the parcels it reported last: it holds every one of them
    // (no DEM step moved a parcel in between); a parcel that is not here is an error on every rank
    const int here = static_cast<int>(std::count(found.begin(), found.end(), 1));
    int missing = static_cast<int>(n) - here;
    if (size_ > 1) MPI_Allreduce(MPI_IN_PLACE, &missing, 1, MPI_INT, MPI_SUM, comm_);
    if (missing > 0)
      throw PeerError("forcing for " + std::to_string(missing) +
                      " particle(s) reached a LIGGGHTS rank that no longer holds them (something "
                      "moved parcels between ranks after the state was gathered: a bug of "
                      "cosim-liggghts to report; one LIGGGHTS rank, participants.NAME.mpi: 1, "
                      "avoids it)");
    return;
  }
  std::vector<int> found_anywhere;
  if (size_ > 1) {
    found_anywhere.assign(n, 0);
    MPI_Allreduce(found.data(), found_anywhere.data(), static_cast<int>(n), MPI_INT, MPI_MAX,
                  comm_);
  } else {
    found_anywhere = std::move(found);
  }
  std::string missing;
  int count = 0;
  for (std::size_t k = 0; k < n; ++k)
    if (!found_anywhere[k] && count++ < 10)
      missing.append(" ").append(std::to_string(terms.ids[k]));
  if (count > 0)
    throw PeerError("forcing names " + std::to_string(count) +
                    " particle id(s) that LIGGGHTS does not have:" + missing +
                    (count > 10 ? " ..." : ""));
}

void Engine::advance(int steps) {
  if (steps <= 0) return;
  const std::string cmd =
      "run " + std::to_string(steps) + (need_setup_ ? " pre yes post no" : " pre no post no");
  guarded("running " + std::to_string(steps) + " DEM steps",
          [&] { lmp_->input->one(cmd.c_str()); });
  need_setup_ = false;
}

State Engine::state() const {
  constexpr int kPer = 11;  // id, x[3], v[3], radius, mass, coating, type
  const LAMMPS_NS::Atom* atom = lmp_->atom;
  const int nlocal = atom->nlocal;
  const double* coating =
      coupled_
          ? findProperty(lmp_->modify, kCoatingMassProperty, "property/atom", "scalar")->vector_atom
          : nullptr;
  std::vector<double> local(static_cast<std::size_t>(nlocal) * kPer);
  for (int i = 0; i < nlocal; ++i) {
    double* p = &local[static_cast<std::size_t>(i) * kPer];
    p[0] = atom->tag[i];
    for (int d = 0; d < 3; ++d) {
      p[1 + d] = atom->x[i][d];
      p[4 + d] = atom->v[i][d];
    }
    p[7] = atom->radius[i];
    p[8] = atom->rmass[i];
    p[9] = coating ? coating[i] : 0.0;
    p[10] = atom->type[i];
  }
  std::vector<double> all;
  std::vector<int> counts(rank_ == 0 && size_ > 1 ? size_ : 0);  // values gathered from each rank
  if (size_ == 1) {
    all = std::move(local);  // one rank: nothing to gather
  } else {
    int count = static_cast<int>(local.size());
    std::vector<int> offsets(rank_ == 0 ? size_ : 0);
    MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm_);
    if (rank_ == 0) {
      std::exclusive_scan(counts.begin(), counts.end(), offsets.begin(), 0);
      all.resize(static_cast<std::size_t>(offsets.back()) +
                 static_cast<std::size_t>(counts.back()));
    }
    MPI_Gatherv(local.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
                MPI_DOUBLE, 0, comm_);
  }
  State s;
  if (rank_ != 0) return s;
  const std::size_t n = all.size() / kPer;
  const std::vector<std::size_t> order = orderById(all, kPer);
  if (size_ > 1) {
    // the rank of each parcel, by its place in the gathered blocks
    std::vector<int> from(n);
    for (int r = 0, j = 0; r < size_; ++r)
      for (int c = 0; c < counts[r] / kPer; ++c) from[j++] = r;
    s.rank.resize(n);
    for (std::size_t k = 0; k < n; ++k) s.rank[k] = from[order[k]];
  }
  s.ids.resize(n);
  s.position.resize(3 * n);
  s.velocity.resize(3 * n);
  s.radius.resize(n);
  s.mass.resize(n);
  s.coating_mass.resize(n);
  s.type.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double* p = &all[order[k] * kPer];
    s.ids[k] = static_cast<std::int64_t>(p[0]);
    for (std::size_t d = 0; d < 3; ++d) {
      s.position[3 * k + d] = p[1 + d];
      s.velocity[3 * k + d] = p[4 + d];
    }
    s.radius[k] = p[7];
    s.mass[k] = p[8];
    s.coating_mass[k] = p[9];
    s.type[k] = p[10];
  }
  return s;
}

std::filesystem::path Engine::writeRestart(const std::filesystem::path& file) {
  if (file.has_parent_path()) {
    std::error_code ec;
    std::filesystem::create_directories(file.parent_path(), ec);
  }
  command("write_restart " + file.string());
  // write_restart re-sorts the atoms, so the next run starts with a setup; it keeps the forces
  // the next step would have started from (DragRelaxationFix::keepOtherForcesAtNextSetup)
  if (drag_fix_) drag_fix_->keepOtherForcesAtNextSetup();
  if (rank_ == 0 && coupled_) {
    std::ofstream marker(file.parent_path() / kOtherForcesMarker);
    marker << "the LIGGGHTS restart file beside holds " << kOtherForceProperty << " and "
           << kLastTorqueProperty
           << ", the last step's forces other than the fluid's and torques\n";
    if (!marker)
      throw cosim::Error(kindOfErrno(errno),
                         "cannot write " + (file.parent_path() / kOtherForcesMarker).string());
  }
  return file;
}

}  // namespace cosim::liggghts

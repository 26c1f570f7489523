#include "cosim/liggghts/liggghts_solver.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <stdexcept>
#include <thread>

#include "cosim/liggghts/liggghts_error.h"
#include "cosim/liggghts/scene_check.h"
#include "cosim/link/errors.h"
#include "cosim/link/fields.h"
#include "cosim/link/particle_wire.h"
#include "cosim/util/errors.h"

namespace cosim::liggghts {

namespace field = cosim::field;
using cosim::link::ParticleData;

LiggghtsSolver::LiggghtsSolver(MPI_Comm comm) : comm_(comm) { MPI_Comm_rank(comm_, &rank_); }

LiggghtsSolver::~LiggghtsSolver() {
  // A broken engine must not be destroyed (see Engine::~Engine); it handles that itself.
}

cosim::link::Capabilities LiggghtsSolver::capabilities() const {
  cosim::link::Capabilities caps;
  caps.role = cosim::wire::PARTICLES;
  caps.adapter = "liggghts";
  caps.provides = {field::position, field::velocity, field::radius, field::coating_mass,
                   field::type};
  caps.accepts = {field::drag_coefficient, field::fluid_velocity, field::explicit_force,
                  field::coating_increment};
  return caps;
}

// The command header travels with a non-blocking broadcast on every rank (non-blocking and
// blocking collectives do not match each other): the waiting ranks test it with short sleeps
// instead of spinning inside MPI_Bcast, so that idle LIGGGHTS ranks do not take CPU from the
// fluid solver while it computes.
void LiggghtsSolver::broadcast(Op op, const std::string& payload) {
  int header[2] = {op, static_cast<int>(payload.size())};
  MPI_Request request;
  MPI_Ibcast(header, 2, MPI_INT, 0, comm_, &request);
  MPI_Wait(&request, MPI_STATUS_IGNORE);
  if (header[1] > 0) MPI_Bcast(const_cast<char*>(payload.data()), header[1], MPI_CHAR, 0, comm_);
  if (op == kFinish || op == kQuit) ranks_released_ = true;
}

// Runs f on this rank as part of a collective command. Errors are the same on every rank
// (LIGGGHTS error->all, or checks on identical data), except LIGGGHTS error->one.
template <class F>
void LiggghtsSolver::collective(F&& f) {
  try {
    f();
  } catch (const LiggghtsError& e) {
    if (e.collectiveBroken()) must_abort_ = true;
    ranks_released_ = true;
    throw;
  } catch (...) {
    ranks_released_ = true;  // every rank failed the same way and stops serving
    throw;
  }
}

void LiggghtsSolver::configure(const cosim::wire::Welcome& welcome) {
  broadcast(kConfigure, welcome.SerializeAsString());
  collective([&] { doConfigure(welcome); });
}

void LiggghtsSolver::advance(const cosim::wire::Advance& cmd, const ParticleData& terms,
                             cosim::wire::Advanced& out, ParticleData& state) {
  if (!last_state_.rank.empty() && terms.size() > 0) {
    // Several ranks: each gets the terms of the parcels it reported last, not the whole bed's,
    // checked here first so that a bad term stops every rank alike
    Terms all = termsOf(terms);
    Engine::checkTerms(all);
    std::vector<int> to = ranksOf(all.ids);
    cosim::wire::Advance header;  // what the ranks need of the command besides their terms
    header.set_dt(cmd.dt());
    header.set_substeps(cmd.substeps());
    broadcast(kAdvanceOwnTerms, header.SerializeAsString());
    collective([&] {
      const Terms mine = scatterTerms(&all, &to);
      doAdvance(header, &mine);
    });
  } else {
    broadcast(kAdvance, cmd.SerializeAsString());
    collective([&] { doAdvance(cmd); });
  }
  // the coating credited now belongs to a particle even if it leaves during this interval
  if (terms.has(field::coating_increment)) {
    const auto& inc = terms.get(field::coating_increment);
    for (std::size_t k = 0; k < terms.size(); ++k) {
      const auto it = std::lower_bound(last_ids_.begin(), last_ids_.end(), terms.ids[k]);
      if (it != last_ids_.end() && *it == terms.ids[k])
        last_coating_[it - last_ids_.begin()] += inc[k];
    }
  }

  // rank 0: the reply
  const State& s = last_state_;
  state.ids = s.ids;
  for (const auto& name : send_) {
    auto& v = state.field(name);
    if (name == field::position)
      v = s.position;
    else if (name == field::velocity)
      v = s.velocity;
    else if (name == field::radius)
      v = s.radius;
    else if (name == field::coating_mass)
      v = s.coating_mass;
    else if (name == field::type)
      v = s.type;
  }
  // Inserted and deleted ids, ascending: one merge of the last and the new id lists (both sorted)
  double deleted_coating = 0;
  if (reported_once_) {
    std::vector<std::int64_t> deleted;
    std::size_t a = 0, b = 0;
    while (a < last_ids_.size() || b < s.ids.size()) {
      if (b == s.ids.size() || (a < last_ids_.size() && last_ids_[a] < s.ids[b])) {
        deleted.push_back(last_ids_[a]);
        deleted_coating += last_coating_[a++];
      } else if (a == last_ids_.size() || s.ids[b] < last_ids_[a]) {
        out.add_inserted_ids(s.ids[b++]);
      } else {
        ++a;
        ++b;
      }
    }
    for (const auto id : deleted) out.add_deleted_ids(id);
  }
  last_ids_ = s.ids;
  last_coating_ = s.coating_mass;
  reported_once_ = true;

  auto& report = *out.mutable_particles();
  report.set_particle_count(s.ids.size());
  report.set_deleted_coating_mass(deleted_coating);
  if (dt_report_ && dt_report_->has_particles) {
    report.set_dt_over_rayleigh_time(dt_report_->dtOverRayleigh());
    report.set_dt_over_hertz_time(dt_report_->dtOverHertz());
  }
}

std::vector<std::string> LiggghtsSolver::checkpoint(const std::string& path) {
  broadcast(kCheckpoint, path);
  std::vector<std::string> files;
  collective([&] { files = doCheckpoint(path); });
  return files;
}

void LiggghtsSolver::finish() {
  broadcast(kFinish, "");
  collective([&] { doFinish(); });
}

void LiggghtsSolver::releaseOtherRanks() {
  if (!ranks_released_ && !must_abort_) broadcast(kQuit, "");
}

int LiggghtsSolver::serve() {
  while (true) {
    int header[2] = {0, 0};
    MPI_Request request;
    MPI_Ibcast(header, 2, MPI_INT, 0, comm_, &request);
    for (int done = 0;;) {
      MPI_Test(&request, &done, MPI_STATUS_IGNORE);
      if (done) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    std::string payload(static_cast<std::size_t>(header[1]), '\0');
    if (header[1] > 0) MPI_Bcast(payload.data(), header[1], MPI_CHAR, 0, comm_);
    try {
      switch (header[0]) {
        case kConfigure: {
          cosim::wire::Welcome w;
          w.ParseFromString(payload);
          doConfigure(w);
          break;
        }
        case kAdvance: {
          cosim::wire::Advance a;
          a.ParseFromString(payload);
          doAdvance(a);
          break;
        }
        case kAdvanceOwnTerms: {
          cosim::wire::Advance a;
          a.ParseFromString(payload);
          const Terms mine = scatterTerms(nullptr, nullptr);
          doAdvance(a, &mine);
          break;
        }
        case kCheckpoint:
          doCheckpoint(payload);
          break;
        case kFinish:
          doFinish();
          return 0;
        case kQuit:
          return 1;
        default:
          throw std::logic_error("unknown command from rank 0");
      }
    } catch (const LiggghtsError& e) {
      if (e.collectiveBroken()) {
        must_abort_ = true;
        std::fprintf(stderr, "[cosim-liggghts rank %d] %s\n", rank_, e.what());
      }
      return 1;
    } catch (const std::exception&) {
      return 1;  // rank 0 hit the same error and reports it
    }
  }
}

void LiggghtsSolver::doConfigure(const cosim::wire::Welcome& welcome) {
  options_ = AdapterOptions::parse(welcome.config_yaml());
  send_.assign(welcome.send().begin(), welcome.send().end());
  if (!welcome.workdir().empty()) {
    std::error_code ec;
    if (std::filesystem::is_directory(welcome.workdir(), ec) &&
        std::filesystem::current_path() != std::filesystem::path(welcome.workdir()))
      std::filesystem::current_path(welcome.workdir());
  }
  // What `cosim validate` checks of the script (files it reads, its timestep, friction), before
  // LIGGGHTS runs a line of it
  checkScene(welcome);
  engine_ = std::make_unique<Engine>(comm_, std::filesystem::current_path());
  // The script's own runs (a settling, an insertion) come before the first coupled step and may
  // take minutes: say where LIGGGHTS writes meanwhile, so that a timeout there is not a blank.
  if (rank_ == 0)
    spdlog::info("[liggghts] running {} {}; LIGGGHTS' own output meanwhile: {}", options_.script,
                 welcome.restart_from().empty() ? "from its start" : "from the checkpoint",
                 (std::filesystem::current_path() / "liggghts.log").string());
  if (welcome.restart_from().empty())
    engine_->runScript(options_.script);
  else
    engine_->resumeScript(options_.script,
                          std::filesystem::path(welcome.restart_from()) / "liggghts.restart");
  engine_->installCoupling();

  if (const auto why = timestepMismatch(options_.script, engine_->timestep(), welcome.cfd_dt(),
                                        welcome.dem_steps()))
    throw InputError(*why);
  warnIfDumpsOffTheRunClock(welcome);
  checkTimestep();
}

// LIGGGHTS names and stamps its dumps by its step counter. After a DEM-only settling in the
// script, that counter is ahead of the coupled run's clock unless the script restarts it
// (docs/liggghts.md); a resumed run continues the counter of its restart file.
void LiggghtsSolver::warnIfDumpsOffTheRunClock(const cosim::wire::Welcome& welcome) const {
  if (rank_ != 0 || engine_->dumpCount() == 0 || !welcome.restart_from().empty()) return;
  const double dt = engine_->timestep();
  const auto expected = static_cast<std::int64_t>(std::llround(welcome.start_time() / dt));
  const std::int64_t step = engine_->step();
  if (step == expected) return;
  spdlog::warn(
      "[liggghts] the script {} leaves LIGGGHTS at step {} while the coupled run starts at t = {} "
      "s (step {}): its dumps are named and stamped {:.6g} s off the run's clock. After the "
      "settling `run`, `unfix` the one-off insertion and write `reset_timestep {}` before the "
      "`dump` command (docs/liggghts.md)",
      options_.script, step, welcome.start_time(), expected,
      static_cast<double>(step - expected) * dt, expected);
}

void LiggghtsSolver::checkTimestep() {
  if (options_.dt_check == DtCheckPolicy::off) return;
  // Judged again only when a smaller particle appears (cheap test first, every step)
  if (dt_reported_ && engine_->minRadius() >= checked_radius_) return;
  const TimestepReport report = engine_->timestepReport(options_.impact_speed);
  if (!report.has_particles) return;
  if (dt_reported_ && report.min_radius >= checked_radius_) return;
  checked_radius_ = report.min_radius;
  dt_report_ = report;
  dt_reported_ = true;
  const TimestepVerdict v = judgeTimestep(report);
  if (v.verdict == Verdict::unstable && options_.dt_check == DtCheckPolicy::refuse)
    throw SolverError(fmt::format(
        "LIGGGHTS script {}: the DEM time step is too large for these particles: {}. Contacts "
        "would be unstable (limits: 0.3 x Rayleigh time, 1/3 x Hertz time). Use `timestep {:.3g}` "
        "(0.2 x Rayleigh time or 1/5 x Hertz time, whichever is smaller) and adjust "
        "coupling.dem_steps, or set options.dt_check: warn to run anyway",
        options_.script, v.summary, v.suggested_dt));
  if (rank_ == 0) {
    if (v.verdict == Verdict::ok)
      spdlog::info("[liggghts] {}", v.summary);
    else
      spdlog::warn("[liggghts] {} -- {}; a safe value is {:.3g} s", v.summary,
                   v.verdict == Verdict::unstable ? "UNSTABLE" : "doubtful", v.suggested_dt);
  }
}

Terms LiggghtsSolver::termsOf(ParticleData terms) {
  Terms t;
  t.ids = std::move(terms.ids);
  t.drag_coefficient = terms.take(field::drag_coefficient);
  t.fluid_velocity = terms.take(field::fluid_velocity);
  t.explicit_force = terms.take(field::explicit_force);
  t.coating_increment = terms.take(field::coating_increment);
  if (!t.drag_coefficient.empty() && t.fluid_velocity.empty())
    throw cosim::link::ProtocolError("Advance carries drag_coefficient without fluid_velocity");
  return t;
}

std::vector<int> LiggghtsSolver::ranksOf(const std::vector<std::int64_t>& ids) const {
  const std::vector<std::int64_t>& known = last_state_.ids;
  std::vector<int> to(ids.size());
  std::string missing;
  int count = 0;
  auto cursor = known.begin();
  for (std::size_t k = 0; k < ids.size(); ++k) {
    // ascending ids (the usual order): the next one is at or after the cursor
    if (cursor == known.end() || *cursor > ids[k]) cursor = known.begin();
    cursor = std::lower_bound(cursor, known.end(), ids[k]);
    if (cursor == known.end() || *cursor != ids[k]) {
      if (count++ < 10) missing.append(" ").append(std::to_string(ids[k]));
      continue;
    }
    to[k] = last_state_.rank[static_cast<std::size_t>(cursor - known.begin())];
  }
  if (count > 0)
    throw PeerError("forcing names " + std::to_string(count) +
                    " particle id(s) that LIGGGHTS does not have:" + missing +
                    (count > 10 ? " ..." : ""));
  return to;
}

// Collective: rank 0 sends each rank the terms `all` of the parcels `to` names it for (ids and
// fields packed as doubles, one block a rank); every rank returns its own.
Terms LiggghtsSolver::scatterTerms(const Terms* all, const std::vector<int>* to) {
  int size = 1;
  MPI_Comm_size(comm_, &size);
  int has[4] = {0, 0, 0, 0};  // drag_coefficient, fluid_velocity, explicit_force, coating
  std::vector<int> counts(rank_ == 0 ? size : 0), offsets(rank_ == 0 ? size : 0);
  std::vector<double> packed;
  if (rank_ == 0) {
    has[0] = !all->drag_coefficient.empty();
    has[1] = !all->fluid_velocity.empty();
    has[2] = !all->explicit_force.empty();
    has[3] = !all->coating_increment.empty();
  }
  MPI_Bcast(has, 4, MPI_INT, 0, comm_);
  const int width = 1 + has[0] + 3 * has[1] + 3 * has[2] + has[3];
  if (rank_ == 0) {
    const std::size_t n = all->ids.size();
    for (std::size_t k = 0; k < n; ++k) counts[static_cast<std::size_t>((*to)[k])] += width;
    std::exclusive_scan(counts.begin(), counts.end(), offsets.begin(), 0);
    packed.resize(n * static_cast<std::size_t>(width));
    std::vector<int> next = offsets;
    for (std::size_t k = 0; k < n; ++k) {
      double* p = &packed[static_cast<std::size_t>(next[static_cast<std::size_t>((*to)[k])])];
      next[static_cast<std::size_t>((*to)[k])] += width;
      *p++ = static_cast<double>(all->ids[k]);  // LIGGGHTS' ids are ints: exact
      if (has[0]) *p++ = all->drag_coefficient[k];
      for (int d = 0; d < 3 && has[1]; ++d) *p++ = all->fluid_velocity[3 * k + d];
      for (int d = 0; d < 3 && has[2]; ++d) *p++ = all->explicit_force[3 * k + d];
      if (has[3]) *p++ = all->coating_increment[k];
    }
  }
  int mine = 0;
  MPI_Scatter(counts.data(), 1, MPI_INT, &mine, 1, MPI_INT, 0, comm_);
  std::vector<double> part(static_cast<std::size_t>(mine));
  MPI_Scatterv(packed.data(), counts.data(), offsets.data(), MPI_DOUBLE, part.data(), mine,
               MPI_DOUBLE, 0, comm_);
  Terms t;
  const std::size_t n = part.size() / static_cast<std::size_t>(width);
  t.ids.resize(n);
  if (has[0]) t.drag_coefficient.resize(n);
  if (has[1]) t.fluid_velocity.resize(3 * n);
  if (has[2]) t.explicit_force.resize(3 * n);
  if (has[3]) t.coating_increment.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double* p = &part[k * static_cast<std::size_t>(width)];
    t.ids[k] = static_cast<std::int64_t>(*p++);
    if (has[0]) t.drag_coefficient[k] = *p++;
    for (int d = 0; d < 3 && has[1]; ++d) t.fluid_velocity[3 * k + d] = *p++;
    for (int d = 0; d < 3 && has[2]; ++d) t.explicit_force[3 * k + d] = *p++;
    if (has[3]) t.coating_increment[k] = *p++;
  }
  return t;
}

void LiggghtsSolver::doAdvance(const cosim::wire::Advance& cmd, const Terms* own) {
  if (!engine_) throw cosim::link::ProtocolError("Advance before configure");
  Terms parsed;
  if (!own) parsed = termsOf(cosim::link::fromWire(cmd.terms()));

  int steps = 0;
  if (cmd.dt() > 0) {
    if (cmd.substeps() == 0)
      throw cosim::link::ProtocolError(
          fmt::format("Advance dt {:.6g} s with substeps = 0", cmd.dt()));
    const double per_step = cmd.dt() / cmd.substeps();
    const double dt = engine_->timestep();
    if (std::abs(per_step - dt) > 1e-9 * dt)
      throw InputError(fmt::format(
          "Advance asks for {} DEM steps in {:.6g} s = {:.6g} s per step, but the LIGGGHTS "
          "script {} uses `timestep {:.6g}`; make coupling.dt / coupling.dem_steps equal the "
          "script's timestep",
          cmd.substeps(), cmd.dt(), per_step, options_.script, dt));
    steps = static_cast<int>(cmd.substeps());
  } else if (cmd.dt() < 0) {
    throw cosim::link::ProtocolError(fmt::format("Advance with negative dt {:.6g}", cmd.dt()));
  }
  if (own)
    engine_->applyOwnTerms(*own);
  else
    engine_->applyTerms(parsed);
  engine_->advance(steps);
  checkTimestep();
  last_state_ = engine_->state();
}

std::vector<std::string> LiggghtsSolver::doCheckpoint(const std::string& path) {
  if (!engine_) throw cosim::link::ProtocolError("Checkpoint before configure");
  std::filesystem::path dir(path.empty() ? "." : path);
  const auto file = engine_->writeRestart(dir / "liggghts.restart");
  // write_restart moves the parcels that left their rank's sub-domain (LIGGGHTS' exchange): the
  // ranks that hold them, for the next terms, are gathered again
  last_state_ = engine_->state();  // collective: every rank gathers
  return {file.string()};
}

void LiggghtsSolver::doFinish() {
  // The run's final state in every dump of the script, also when the end time is not a multiple
  // of the dump interval.
  if (engine_ && !engine_->broken()) engine_->writeDumpsNow();
  engine_.reset();
}

}  // namespace cosim::liggghts

#include "coupler.h"

#include <fmt/format.h>
#include <sched.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <iterator>
#include <limits>
#include <random>
#include <sstream>

#include "cosim/analysis/files.h"
#include "cosim/analysis/time_series.h"
#include "cosim/link/fields.h"
#include "cosim/link/particle_wire.h"
#include "cosim/util/long_quotes.h"
#include "processes.h"

namespace cosim::orchestrator {

namespace {

using Clock = std::chrono::steady_clock;

// cosim bench measures and replays the central path's terms, so its runs take the central path.
Plan planOf(const Scenario& sc, const models::SceneModels& m, const RunOptions& o) {
  Plan p = makePlan(sc, m);
  if (o.record_terms || o.replay_terms || o.scheme.rfind("frozen", 0) == 0) p.peer = false;
  return p;
}

// The threads for the laws: the CPUs this process may run on (coupling.cpus may have bound it
// to one), at most 8; both solvers wait while the laws run, so their cores are free.
unsigned lawThreads() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0) return 1;
  return static_cast<unsigned>(std::clamp(CPU_COUNT(&set), 1, 8));
}

std::string newRunId() {
  std::random_device rd;
  std::ostringstream os;
  os << std::hex << std::setw(8) << std::setfill('0') << rd();
  return os.str();
}

}  // namespace

void Coupler::Phases::lap(const char* phase) {
  const auto now = Clock::now();
  seconds[phase] += std::chrono::duration<double>(now - tick).count();
  tick = now;
}

namespace {
const util::StopRequest kNeverStopped;  // for a caller that gives no stop request
}  // namespace

Coupler::Coupler(Scenario scenario, RunOptions options)
    : sc_(std::move(scenario)),
      opt_(std::move(options)),
      stop_(opt_.stop != nullptr ? *opt_.stop : kNeverStopped),
      log_(opt_.quiet),
      models_(makeModels(sc_)),
      plan_(planOf(sc_, models_, opt_)),
      run_id_(newRunId()),
      record_(sc_, plan_, log_),
      participants_(sc_, plan_, run_id_, log_, stop_),
      scheme_(makeCouplingScheme(sc_, plan_,
                                 opt_.scheme.empty() ? sc_.coupling.scheme : opt_.scheme,
                                 opt_.replay_terms, opt_.resume.empty())),
      monitor_(sc_) {}

Coupler::~Coupler() { participants_.shutdown(false); }

RunResult Coupler::run() {
  RunResult result;
  wall0_ = Clock::now();
  time_ = sc_.coupling.start_time;
  clock_ = {sc_.coupling.start_time, sc_.coupling.dt};
  nsteps_ = sc_.coupling.steps();
  result.folder =
      opt_.resume.empty() ? record_.open(opt_.output, opt_.overwrite) : record_.reopen(opt_.resume);
  checkpoints_.emplace(record_.folder());
  next_checkpoint_ = sc_.coupling.start_time + sc_.checkpoint.interval;
  std::optional<Progress> progress;
  std::string status = "completed";
  std::uint64_t done = 0;  // steps of the run before this invocation (a resume's)
  try {
    if (opt_.resume.empty()) {
      record_.startRecorders(run_id_);
      if (recordsZonePasses()) {
        passes_.emplace().start(record_.folder());
      } else {
        std::error_code ec;  // a run folder reused with --overwrite keeps no stale passes
        std::filesystem::remove(record_.folder() / analysis::kZonePassesFile, ec);
      }
      // Status "running" until the end; its space is what the last summary takes if the disk
      // is full by then.
      record_.summary(summarize(result, "running"));
      participants_.start(record_.folder());
      participants_.handshake();
      reportInitialState();
    } else {
      done = resumeFromCheckpoint();
    }
    progress.emplace(time_, sc_.coupling.end_time, opt_.quiet, Progress::WallClock{}, stdout,
                     sc_.coupling.start_time);
    progress_ = &*progress;  // the Courant warning ends the open progress line first
    result.steps = done;
    bool interrupted = false;
    for (std::uint64_t k = done; k < nsteps_ && !interrupted; ++k) {
      if (opt_.untimed_steps && k == done + *opt_.untimed_steps) resetTimings();
      beginStep(k);
      const models::CouplingTerms terms = termsOfStep();             // gas at parcels, models
      const AdvanceReplies replies = advanceBoth(terms);             // both solvers over dt
      if (replies.particles) takeParticleState(*replies.particles);  // the particles' new state
      if (replies.fluid) takeFluidResults(*replies.fluid);           // what the gas did
      creditAndRecord(replies, k + 1 == nsteps_);                    // coating, rows, snapshots
      progress->update(time_, k + 1, state_.size());
      result.steps = k + 1;
      interrupted = stop_.requested() && k + 1 < nsteps_;
      if (interrupted || checkpointDue(k + 1 == nsteps_)) {
        writeCheckpoint();
        // Ctrl-C while that checkpoint was written: it holds this state, stop with it
        interrupted = stop_.requested() && k + 1 < nsteps_;
      }
    }
    if (interrupted) {
      status = "interrupted";
      result.exit_code = exit_code::interrupted;
      const std::string by = stop_.signal() != 0
                                 ? "interrupted by signal " + std::to_string(stop_.signal())
                                 : std::string("stopped on request");
      result.message = "cosim: " + by + " at t = " + analysis::formatShortest(time_) + " s (step " +
                       std::to_string(step_) +
                       "); a checkpoint holds this state. Continue with:\n  cosim resume " +
                       record_.folder().string();
      progress->abort();
      closePeerPasses();
    } else {
      finishRun();
      closePeerPasses();
      progress->finish(time_, result.steps);
    }
    participants_.shutdown(true);
  } catch (const RunFailure& f) {
    status = stop_.requested() ? "interrupted" : "failed";
    result.message = describe(f);
    result.exit_code = stop_.requested() ? exit_code::interrupted : exitCodeOf(f.kind());
    if (progress) progress->abort();
    participants_.shutdown(false);
  } catch (const std::exception& e) {
    status = "failed";
    result.message = std::string("cosim: ") + e.what();
    result.exit_code = exitCodeOf(kindOf(e, ErrorKind::solver));
    if (progress) progress->abort();
    participants_.shutdown(false);
  }
  if (status != "completed") recordStoppedState();
  result.message = util::cutLongQuotes(result.message);  // a peer's or a user's long input
  closeZonePasses(result.steps);
  result.wall_seconds = wall_before_ + std::chrono::duration<double>(Clock::now() - wall0_).count();
  result.final_state = state_;
  result.time = time_;
  result.unstable_step = courant_stop_ && status == "failed";
  result.totals = totals_;
  result.phase_seconds = phases_.seconds;
  result.compute_seconds = participants_.computeSeconds();
  for (const auto& [n, w] : participants_.advanceWireSeconds())
    result.compute_seconds["advance_" + n] = w;
  const std::uint64_t untimed = opt_.untimed_steps ? done + *opt_.untimed_steps : 0;
  result.timed_steps = result.steps > untimed ? result.steps - untimed : 0;
  if (status == "completed") {
    try {
      result.observables = record_.observables(state_, totals_);
    } catch (const std::exception& e) {
      result.exit_code = exitCodeOf(kindOf(e, ErrorKind::solver));
      result.message = std::string("cosim: ") + e.what();
      status = "failed";
    }
  }
  // A resume refused before it began leaves the run folder (and its summary) as it was.
  if (opt_.resume.empty() || resume_accepted_) record_.summary(summarize(result, status));
  if (!result.message.empty()) {
    log_.file(result.message);
    result.message += "\n  everything recorded so far is in " + record_.folder().string();
    result.message += howToContinue(status, result.steps);
  }
  return result;
}

// The end of the message of a failed run: how to continue it (from which checkpoint), or "".
std::string Coupler::howToContinue(const std::string& status, std::uint64_t steps_done) const {
  std::string message;
  // A run stopped before its end by a failure continues from its newest checkpoint
  const bool at_restore = !opt_.resume.empty() &&
                          (unreadable_checkpoint_ || (resume_accepted_ && step_ <= resumed_step_));
  if (status == "failed" && at_restore) {
    // The resume failed before it completed a step: perhaps the checkpoint itself cannot be read
    // back; the others are another way on.
    std::string others, next;
    for (const auto& c : checkpoints_->all()) {
      if (c == resumed_from_) continue;
      others += (others.empty() ? "" : ", ") + c.filename().string() + " s";
      next = c.filename().string();  // the newest of the others
    }
    message +=
        resumed_from_.empty()
            ? std::string()
            : "; the resume from the checkpoint at t = " + resumed_from_.filename().string() +
                  " s failed before it completed a step";
    if (!others.empty())
      message += "; the run's other complete checkpoints: " + others +
                 ". If that checkpoint is damaged, continue from another, e.g.\n  "
                 "cosim resume " +
                 record_.folder().string() + " --from " + next;
  } else if (status == "failed" && steps_done < nsteps_ &&
             (opt_.resume.empty() || resume_accepted_)) {
    if (const auto newest = checkpoints_->newest()) {
      message += "; its newest checkpoint is t = " + newest->filename().string() +
                 " s: once the cause is fixed, continue with\n  cosim resume " +
                 record_.folder().string();
    }
  }
  return message;
}

// A scene the saved state cannot honour, a DEM step that would change, a wake history missing.
void Coupler::refuseWhatItCannotHonour(const CoupledState& saved,
                                       const std::filesystem::path& checkpoint) const {
  const auto differences = sceneDifferences(YAML::Load(saved.scene), sc_.resolved);
  if (!differences.empty()) {
    std::string msg = "cannot resume from " + checkpoint.string() +
                      ": the scene differs from the one the checkpoint was written with, in "
                      "what the saved state cannot honour:";
    for (const auto& d : differences) msg += "\n  - " + d;
    msg +=
        "\n  (only coupling.end_time, coupling.dt with coupling.dem_steps, coupling.scheme, "
        "coupling.cpus, output, checkpoint, transport, checks, observables, timeouts and "
        "solver_log_every may change; start a new run for anything else)";
    throw RunFailure("", msg, ErrorKind::input);
  }
  if (const auto why = refusedStepChange(YAML::Load(saved.scene), sc_.resolved); !why.empty())
    throw RunFailure("", "cannot resume from " + checkpoint.string() + ": " + why,
                     ErrorKind::input);
  if (models_.wake && !plan_.peer && !saved.wake) {
    throw RunFailure("",
                     "cannot resume from " + checkpoint.string() +
                         ": it holds no wake history, which models.drag.undisturbed_velocity "
                         "'self_disturbance_transient' needs (each parcel's force history); "
                         "start a new run",
                     ErrorKind::input);
  }
}

std::uint64_t Coupler::resumeFromCheckpoint() {
  const auto checkpoint =
      opt_.resume_from ? checkpoints_->at(*opt_.resume_from) : checkpoints_->newest();
  if (!checkpoint && opt_.resume_from) {
    throw RunFailure(
        "",
        "cosim resume --from " + analysis::formatShortest(*opt_.resume_from) + ": " +
            record_.folder().string() +
            " holds no complete checkpoint at that time; it holds: " + checkpoints_->listTimes(),
        ErrorKind::input);
  }
  if (!checkpoint) {
    throw RunFailure("",
                     "nothing to resume in " + record_.folder().string() +
                         ": it holds no complete checkpoint (checkpoints/<time>/ with "
                         "orchestrator.json); runs write them when checkpoint.interval is "
                         "set, and when they are interrupted",
                     ErrorKind::input);
  }
  resumed_from_ = *checkpoint;
  CoupledState saved;
  try {
    saved = readCoupledState(*checkpoint);
  } catch (const std::exception& e) {
    unreadable_checkpoint_ = true;
    throw RunFailure("", e.what(), ErrorKind::input);
  }
  refuseWhatItCannotHonour(saved, *checkpoint);
  const StepClock was = clockOf(saved);
  const bool new_step = sc_.coupling.dt != was.dt;
  // A new coupling step: the steps done keep their numbers and times, the next ones are dt long
  clock_ = new_step ? StepClock{saved.time - static_cast<double>(saved.step) * sc_.coupling.dt,
                                sc_.coupling.dt}
                    : was;
  nsteps_ = clock_.stepsTo(sc_.coupling.end_time);
  if (saved.step >= nsteps_) {
    throw RunFailure("",
                     "the run in " + record_.folder().string() +
                         " already reached t = " + analysis::formatShortest(saved.time) +
                         " s, the scene's coupling.end_time; make it longer with --set "
                         "coupling.end_time=...",
                     ErrorKind::input);
  }
  resume_accepted_ = true;  // from here on the run folder changes
  resumed_step_ = saved.step;
  // Checkpoints newer than the one resumed from (--from) belong to the history it leaves
  for (const auto& moved : checkpoints_->setAsideAfter(*checkpoint))
    log_.show("set aside the newer checkpoint " + moved.filename().string() + " in " +
              moved.parent_path().string() +
              " (this resume continues from t = " + checkpoint->filename().string() + " s)");
  record_.writeResolvedScene();
  record_.resumeRecorders(saved.series_rows, saved.time, saved.next_output, run_id_);
  if (recordsZonePasses() && saved.zone_passes) {
    passes_.emplace().resume(record_.folder(), *saved.zone_passes);
  } else if (recordsZonePasses()) {
    log_.warn("the checkpoint holds no zone passes (written by an older cosim): " +
              std::string(analysis::kZonePassesFile) + " is not continued for this run");
  }
  participants_.resumeFrom(*checkpoint);
  participants_.setClockStart(clock_.start);
  participants_.start(record_.folder());
  participants_.handshake();

  step_ = saved.step;
  time_ = saved.time;
  participants_.setClock(step_, time_);
  reportParticleState({});
  // The particles must continue from exactly the state the checkpoint was written with
  if (const auto diff = digestDifferences(saved.particle_digest, particleDigest(state_));
      !diff.empty()) {
    std::string fields;
    for (const auto& f : diff) fields += (fields.empty() ? "" : ", ") + f;
    throw RunFailure("particles", "cannot resume from " + checkpoint->string() +
                                      ": the particle state read back from the checkpoint is not "
                                      "the one written, in: " +
                                      fields +
                                      " (bit for bit): its restart data do not hold the whole "
                                      "state, and the run would not continue as it was; see "
                                      "docs/restarts.md");
  }
  ledger_.restore(saved.balance, saved.pending);
  if (models_.wake && saved.wake) models_.wake->restore(*saved.wake);
  // The gas sampled ahead is where the parcels would be after the old step: with a new one the
  // first interval samples them where they are
  if (saved.sample_ahead && !new_step) scheme_->resumeSamplingAt(std::move(*saved.sample_ahead));
  totals_ = saved.totals;
  monitor_.restore(saved.monitor);
  initial_count_ = saved.initial_count;
  initial_row_written_ = saved.initial_row_written;
  phases_.seconds = saved.phases;
  for (const auto& [name, seconds] : saved.compute) participants_.addComputeSeconds(name, seconds);
  wall_before_ = saved.wall_seconds;
  next_checkpoint_ = saved.time + sc_.checkpoint.interval;
  log_.show("resumed from " + checkpoint->string() + " (t = " +
            analysis::formatShortest(saved.time) + " s, step " + std::to_string(saved.step) + ")");
  if (new_step) {
    log_.show("the coupling step changes from " + analysis::formatShortest(was.dt) + " to " +
              analysis::formatShortest(clock_.dt) + " s (" +
              std::to_string(sc_.coupling.dem_steps) +
              " DEM steps each) from t = " + analysis::formatShortest(saved.time) +
              " s: " + std::to_string(nsteps_ - saved.step) + " steps to coupling.end_time");
    // What the new step means for the bed as it is now (the Courant and relaxation checks)
    refuseOrWarn(checkBeforeRun(sc_, models_, plan_, state_, reported_dt_over_rayleigh_));
    if (const auto w = offTheStepGrid(sc_.coupling.start_time, saved.time, clock_.dt))
      log_.warn(*w);
  }
  if (const auto free_now = freeBytes()) disk_ = {time_, *free_now};
  return saved.step;
}

bool Coupler::checkpointDue(bool last) const {
  if (sc_.checkpoint.interval <= 0.0) return false;
  return last || time_ + 1e-9 * sc_.coupling.dt >= next_checkpoint_;
}

void Coupler::writeCheckpoint() {
  wholeState();  // its digest is of the whole state
  const auto partial = checkpoints_->begin(time_, participants_.names());
  participants_.checkpoint(partial);
  CoupledState s;
  s.step = step_;
  s.time = time_;
  s.clock = clock_;
  s.balance = ledger_.balance();
  s.pending = ledger_.pending();
  s.totals = totals_;
  s.monitor = monitor_.state();
  s.initial_count = initial_count_;
  s.initial_row_written = initial_row_written_;
  s.series_rows = record_.rows();
  s.next_output = record_.nextOutput();
  s.wall_seconds = wall_before_ + std::chrono::duration<double>(Clock::now() - wall0_).count();
  s.phases = phases_.seconds;
  s.compute = participants_.computeSeconds();
  YAML::Emitter em;
  em << sc_.resolved;
  s.scene = em.c_str();
  s.particle_digest = particleDigest(state_);
  if (passes_) s.zone_passes = passes_->state();
  if (models_.wake && !plan_.peer) s.wake = models_.wake->state();  // peer: the particles'

  s.sample_ahead = scheme_->samplingAhead();
  const auto dir = checkpoints_->commit(partial, s, sc_.checkpoint.keep);
  next_checkpoint_ = time_ + sc_.checkpoint.interval;
  log_.file("checkpoint at t = " + analysis::formatShortest(time_) + " s: " + dir.string());
  // the disk's filling, measured over the run so far (said once)
  if (const auto free_now = freeBytes(); free_now && disk_ && !disk_warned_) {
    const auto [t0, free0] = *disk_;
    const auto w = checkDiskFilling(t0, free0, time_, *free_now, sc_.coupling.end_time,
                                    [&] { return largestEntries(record_.folder(), 3); });
    if (w) {
      if (progress_) progress_->abort();  // the warning on a line of its own
      log_.warn(w->substr(std::string("warning: ").size()));
      disk_warned_ = true;
    }
  }
  phases_.lap("checkpoint");
}

std::optional<double> Coupler::freeBytes() const {
  std::error_code ec;
  const auto space = std::filesystem::space(record_.folder(), ec);
  if (ec) return std::nullopt;
  return static_cast<double>(space.available);
}

void Coupler::reportInitialState() {
  step_ = 0;
  participants_.setClock(step_, time_);
  reportParticleState({});
  if (plan_.coating) ledger_.start(state_);
  initial_count_ = state_.size();
  record_.snapshot(time_, state_, true);
  if (auto wrong = checkParticleCount(sc_, state_)) throw RunFailure("particles", *wrong);
  StabilityReport report = checkBeforeRun(sc_, models_, plan_, state_, reported_dt_over_rayleigh_);
  if (const auto free_now = freeBytes()) {
    if (auto w = checkDiskSpace(sc_, plan_, state_, time_, *free_now)) report.lines.push_back(*w);
    disk_ = {time_, *free_now};
  }
  refuseOrWarn(report);
}

void Coupler::beginStep(std::uint64_t k) {
  step_ = k + 1;
  time_ = clock_.time(k);
  participants_.setClock(step_, time_);
  phases_.start();
}

void Coupler::resetTimings() {
  phases_.seconds.clear();
  participants_.resetComputeSeconds();
}

// Steps 2 and 3, unless the scheme replays earlier terms (cosim bench's solver-alone runs). On
// the peer data path the particles do both themselves, and pay the coating owed from their own
// part of the ledger: no per-parcel term is sent.
models::CouplingTerms Coupler::termsOfStep() {
  if (plan_.peer) {
    phases_.lap("models");
    return {};
  }
  if (auto replayed = scheme_->replay(state_)) {
    phases_.lap("models");
    return std::move(*replayed);
  }
  std::vector<char> lost;
  const link::ParticleData samples = sampleFluid(lost);         // the gas at the parcels
  models::CouplingTerms terms = evaluateModels(samples, lost);  // forcing, exchange terms
  if (opt_.record_terms) {
    opt_.record_terms->push_back(terms);
    phases_.skip();
  }
  return terms;
}

// Step 2: the gas velocity, voidage, ... at every parcel; parcels outside the mesh are `lost`.
// Under the overlapped scheme the fluid has already sampled them during the last interval.
link::ParticleData Coupler::sampleFluid(std::vector<char>& lost) {
  lost.assign(state_.size(), 0);
  if (!plan_.fluid) return {};
  if (auto ahead = scheme_->samplesAhead(participants_, state_)) return samplesOf(*ahead, lost);
  wire::Envelope e;
  cosim::link::toWire(state_, *e.mutable_sample()->mutable_particles(), plan_.sample_state);
  const auto r = participants_.request("fluid", std::move(e), wire::Envelope::kSamples);
  participants_.addComputeSeconds("fluid_sample", r.samples().wall_seconds());
  return samplesOf(r.samples(), lost);
}

link::ParticleData Coupler::samplesOf(const wire::Samples& sm, std::vector<char>& lost) {
  link::ParticleData samples = cosim::link::fromWire(sm.at_particles());
  if (samples.ids != state_.ids) {
    throw RunFailure("fluid", "returned samples for other particles than it was sent (ids differ)",
                     ErrorKind::peer);
  }
  if (sm.lost_ids_size() > 0) {
    const auto idx = state_.index();
    for (auto id : sm.lost_ids()) {
      if (auto it = idx.find(id); it != idx.end()) lost[it->second] = 1;
    }
  }
  check(samples, "fluid");
  phases_.lap("fluid_sample");
  return samples;
}

// Step 3: the models over all parcels; the coating owed since the last step joins the forcing.
models::CouplingTerms Coupler::evaluateModels(const link::ParticleData& samples,
                                              const std::vector<char>& lost) {
  models::CouplingTerms terms = models::evaluateTerms(models_, plan_.coating, sc_.constants, state_,
                                                      samples, lost, sc_.coupling.dt, lawThreads());
  check(terms.forcing, "models (forcing)");
  if (step_ == 1) refuseOrWarn(checkFirstStep(sc_, state_, samples, terms.forcing));
  if (plan_.coating) ledger_.pay(terms.forcing);
  if (passes_) passes_->update(time_, state_.ids, terms.in_zone);  // time_: the step's start
  phases_.lap("models");
  return terms;
}

// Step 4: as the coupling scheme says (today both at the same time).
AdvanceReplies Coupler::advanceBoth(const models::CouplingTerms& terms) {
  AdvanceReplies replies = scheme_->advance(participants_, state_, terms);
  phases_.lap("advance");
  time_ = clock_.time(step_);
  participants_.setClock(step_, time_);
  return replies;
}

// Step 1 of the next interval: the particle state, with every particle that appeared or left
// accounted for.
void Coupler::takeParticleState(const wire::Advanced& pa) {
  participants_.addComputeSeconds("particles", pa.wall_seconds());
  if (pa.has_peer()) takePeerAccount(pa.peer());  // about the parcels at the interval's start
  if (pa.has_peer() && pa.state().ids_size() == 0 && pa.state().fields_size() == 0) {
    takeParticleChanges(pa);  // who came and went; the state comes when it is recorded
    ledger_.delivered();
    return;
  }
  const std::vector<std::int64_t> before = state_.ids;
  state_ = cosim::link::fromWire(pa.state());
  // An older participant's peer reply: the parcels' ids only (Advance.state_ids_only)
  state_partial_ = pa.has_peer() && state_.names().empty() && !state_.ids.empty();
  if (state_partial_) std::sort(state_.ids.begin(), state_.ids.end());
  ledger_.delivered();  // the coating paid with this step is on the parcels
  try {
    monitor_.checkParticleLedger(before, state_.ids,
                                 {pa.inserted_ids().begin(), pa.inserted_ids().end()},
                                 {pa.deleted_ids().begin(), pa.deleted_ids().end()}, step_, time_);
  } catch (const std::exception& e) {
    throw RunFailure("particles", e.what());
  }
  check(state_, "particles");
}

// The peer path between records (Advance.state_changes_only): the particles send their count and
// the ids that came and went, not their parcels, so that nothing here grows with the bed on a
// step where none came or left. state_ keeps the ids, sorted; wholeState checks them against the
// particles' own when it records the state.
void Coupler::takeParticleChanges(const wire::Advanced& pa) {
  if (!state_partial_) {  // the last reply was the whole state, in the particles' order
    link::ParticleData ids;
    ids.ids = std::move(state_.ids);
    std::sort(ids.ids.begin(), ids.ids.end());
    state_ = std::move(ids);
    state_partial_ = true;
  }
  if (auto wrong = applyParticleChanges(
          state_.ids, {pa.inserted_ids().begin(), pa.inserted_ids().end()},
          {pa.deleted_ids().begin(), pa.deleted_ids().end()}, pa.particles().particle_count()))
    throw RunFailure("particles",
                     "reported at step " + std::to_string(step_) +
                         " (t = " + analysis::formatShortest(time_) + " s) that it " + *wrong,
                     ErrorKind::peer);
}

// The peer path's account of the interval: the first step's checks (central: evaluateModels),
// the time the particles spent sampling and in the laws, their part of the coating ledger.
void Coupler::takePeerAccount(const wire::PeerInterval& p) {
  participants_.addComputeSeconds("particles_sample", p.sample_seconds());
  participants_.addComputeSeconds("particles_models", p.models_seconds());
  if (step_ == 1 && p.has_samples()) {
    const link::ParticleData samples = cosim::link::fromWire(p.samples());
    const link::ParticleData forcing = cosim::link::fromWire(p.forcing());
    check(samples, "fluid");
    check(forcing, "models (forcing)");
    refuseOrWarn(checkFirstStep(sc_, state_, samples, forcing));
  }
  if (p.has_ledger()) takePeerLedger(p.ledger());
}

// The peer path: the particles' part of the coating ledger (running totals) and the zone passes
// they closed, which zone_passes.csv takes as they come.
void Coupler::takePeerLedger(const wire::PeerLedger& l) {
  if (!plan_.coating) return;
  for (const double v : {l.removed(), l.credited(), l.credited_including_owed(), l.left_domain()})
    if (!std::isfinite(v))
      throw RunFailure("particles",
                       "reported a coating ledger total of " + analysis::formatShortest(v) +
                           " at step " + std::to_string(step_) + " (PeerLedger)",
                       ErrorKind::peer);
  ledger_.takeParticleTotals(link::fromWire(l), l.credited_including_owed());
  peer_coating_outside_ = l.coating_outside();
  if (!passes_ || l.passes_size() == 0) return;
  std::vector<analysis::ZonePass> rows;
  rows.reserve(static_cast<std::size_t>(l.passes_size()));
  for (const auto& r : l.passes()) {
    if (!std::isfinite(r.entry_time()) || !std::isfinite(r.exit_time()) ||
        r.exit_time() < r.entry_time() || !std::isfinite(r.coating()) || r.coating() < 0)
      throw RunFailure("particles",
                       "reported a zone pass of parcel " + std::to_string(r.parcel_id()) +
                           " from t = " + analysis::formatShortest(r.entry_time()) + " to " +
                           analysis::formatShortest(r.exit_time()) + " s with coating " +
                           analysis::formatShortest(r.coating()) +
                           " kg: expected finite times in order and a coating of at least 0",
                       ErrorKind::peer);
    rows.push_back(link::fromWire(r));
  }
  passes_->write(rows);
}

// The fluid's results of the interval: precursor each parcel removed (now owed as coating), the
// precursor balance, the Courant number. On the peer path the particles booked the removal
// themselves (takePeerLedger).
void Coupler::takeFluidResults(const wire::Advanced& fa) {
  participants_.addComputeSeconds("fluid", fa.wall_seconds());
  if (plan_.coating) {
    if (!plan_.peer) {
      const auto fr = cosim::link::fromWire(fa.state());
      check(fr, "fluid");
      ledger_.owe(fr);
      if (passes_) passes_->credit(fr);
    }
    const auto& species = fa.fluid().species();
    ledger_.addFlows(species.precursor_in(), species.precursor_out());
    ledger_.setHeld(species.precursor_held());
    if (step_ == 1 && species.has_precursor_held_start()) {
      ledger_.setHeldAtStart(species.precursor_held_start());
      monitor_.setHeldAtStart(species.precursor_held_start());
    }
    const auto& b = ledger_.balance();
    try {
      monitor_.checkMassBalance(b.in, b.out, b.held, b.removed, step_, time_);
    } catch (const std::exception& e) {
      throw RunFailure("fluid", e.what());
    }
    if (auto w = monitor_.checkPrecursorBounds(species.precursor_min(), species.precursor_max(),
                                               step_, time_)) {
      if (progress_) progress_->abort();
      log_.show(*w);
    }
  }
  if (fa.fluid().has_max_courant()) {
    try {
      if (auto w = monitor_.checkCourant(fa.fluid().max_courant(), step_, time_)) {
        if (progress_) progress_->abort();
        log_.show(*w);
      }
    } catch (const std::exception& e) {
      courant_stop_ = true;
      throw RunFailure("fluid", e.what());
    }
  }
}

// Step 5: deleted parcels take their credit along; the time-series row and the snapshot at
// time_ hold what the parcels have at time_ (coating still owed included, as the ledger will pay
// it with the next Advance or the final flush).
void Coupler::creditAndRecord(const AdvanceReplies& replies, bool last) {
  if (replies.particles) {
    const auto& pa = *replies.particles;
    if (plan_.peer) {  // the particles' ledger and passes saw them leave
      ledger_.addDeletedCoating(pa.particles().deleted_coating_mass());
    } else {
      ledger_.leave({pa.deleted_ids().begin(), pa.deleted_ids().end()},
                    pa.particles().deleted_coating_mass());
      if (passes_ && !pa.deleted_ids().empty())
        passes_->leave({pa.deleted_ids().begin(), pa.deleted_ids().end()}, time_);
    }
    if (!pa.inserted_ids().empty()) totals_["particles_inserted"] += pa.inserted_ids_size();
    if (!pa.deleted_ids().empty()) totals_["particles_deleted"] += pa.deleted_ids_size();
  }
  // (Only particles that advance are paid: not so when the fluid runs alone in cosim bench.)
  if (plan_.coating && last && replies.particles) flushCredit();

  namespace col = analysis::column;
  const auto& b = ledger_.balance();
  if (plan_.coating && !initial_row_written_) {
    // The state at the start for the mass balance, written once the fluid has said what it
    // holds at the start. Quantities that only exist over a step (pressure drop) are NaN.
    record_.row(sc_.coupling.start_time,
                {{col::particle_count, static_cast<double>(initial_count_)},
                 {col::precursor_held, b.held_start},
                 {col::pressure_drop, std::numeric_limits<double>::quiet_NaN()}});
    initial_row_written_ = true;
  }
  Row row{{col::particle_count, static_cast<double>(state_.size())},
          {col::wall_seconds,
           wall_before_ + std::chrono::duration<double>(Clock::now() - wall0_).count()}};
  if (plan_.coating) {
    row[col::precursor_in] = b.in;
    row[col::precursor_out] = b.out;
    row[col::precursor_held] = b.held;
    row[col::precursor_removed] = b.removed;
    row[col::coated_mass] = ledger_.creditedIncludingOwed();
  }
  if (replies.fluid) row[col::pressure_drop] = replies.fluid->fluid().pressure_drop();
  record_.row(time_, row);
  // The parcels with their coating owed, only when recorded or watched: a copy of every parcel
  if (on_step || record_.snapshotDue(time_, last)) {
    wholeState();
    const link::ParticleData held = ledger_.held(state_);
    record_.snapshot(time_, held, last);
    if (on_step) on_step(time_, held);
  }
  phases_.lap("bookkeeping");
}

// The fluid reports removal after a step and the particles receive it with the next step's
// terms, so the last step's removal needs an Advance of zero length of its own.
void Coupler::flushCredit() {
  if (plan_.peer) {  // the particles pay from their own part of the ledger
    reportParticleState({}, ZeroLength::pay_owed);
    return;
  }
  link::ParticleData flush;
  flush.ids = state_.ids;
  ledger_.pay(flush);
  reportParticleState(flush);
  ledger_.delivered();
}

// The peer path: the particles' whole state, for a snapshot or a checkpoint, when their last reply
// held their ids only.
void Coupler::wholeState() {
  if (!state_partial_) return;
  const std::vector<std::int64_t> known = std::move(state_.ids);  // sorted
  reportParticleState({});
  // the changes the particles reported step by step must add up to the parcels they hold
  if (auto wrong = compareWithChanges(known, state_.ids))
    throw RunFailure(
        "particles",
        "sent its state at t = " + analysis::formatShortest(time_) + " s, which " + *wrong,
        ErrorKind::peer);
  phases_.lap("bookkeeping");
}

void Coupler::reportParticleState(const link::ParticleData& terms, ZeroLength what) {
  wire::Envelope e;
  auto* a = e.mutable_advance();
  a->set_dt(0.0);
  a->set_pay_owed(what == ZeroLength::pay_owed);
  a->set_close_passes(what == ZeroLength::close_passes);
  if (!terms.ids.empty()) cosim::link::toWire(terms, *a->mutable_terms());
  if (!participants_.peerAddress().empty()) a->set_peer_connect(participants_.peerAddress());
  const auto r = participants_.request("particles", std::move(e), wire::Envelope::kAdvanced);
  state_ = cosim::link::fromWire(r.advanced().state());
  state_partial_ = false;
  if (r.advanced().has_particles())
    reported_dt_over_rayleigh_ = r.advanced().particles().dt_over_rayleigh_time();
  check(state_, "particles");
  if (r.advanced().has_peer() && r.advanced().peer().has_ledger())
    takePeerLedger(r.advanced().peer().ledger());
}

// The peer path, a run that ends with its particles still there (completed, or stopped on
// request): the passes still open close at the end, as on the central path (closeZonePasses).
void Coupler::closePeerPasses() {
  if (!plan_.peer || !passes_) return;
  reportParticleState({}, ZeroLength::close_passes);
  passes_closed_ = true;
}

void Coupler::finishRun() {
  totals_["particles_inserted"] += 0.0;
  totals_["particles_deleted"] += 0.0;
  if (plan_.coating) ledger_.totals(state_, totals_);
}

bool Coupler::recordsZonePasses() const {
  return plan_.coating && models_.zone && scheme_->evaluatesEveryStep();
}

// A run stopped before its end (failed, interrupted): the particles as they were after the last
// step done, as the final snapshot, so that particles.h5 ends where zone_passes.csv is closed and
// the time series ends (the coating on the parcels equals the coating in their passes). Without
// it the file would end at the last output time, passes later.
void Coupler::recordStoppedState() {
  if (!record_.recording() || step_ == 0 || state_.ids.empty()) return;  // nothing ran
  if (state_partial_) {  // the peer path, stopped between two records: the last one stands
    log_.file(
        "the particles' state at the stop was not sent (coupling.data_path: peer): "
        "particles.h5 ends at its last snapshot");
    return;
  }
  ledger_.undelivered();  // a step cut short: what it paid is still owed to the parcels
  try {
    record_.snapshot(time_, ledger_.held(state_), true);
  } catch (const std::exception& e) {
    log_.warn(std::string("could not write the particles at the stop: ") + e.what());
  }
}

void Coupler::closeZonePasses(std::uint64_t steps_done) {
  if (!passes_) return;
  if (plan_.peer && !passes_closed_)
    log_.file("the zone passes still open when the run stopped are not in " +
              std::string(analysis::kZonePassesFile) +
              " (coupling.data_path: peer: the particles keep them, and the run did not end "
              "with them)");
  try {
    passes_->close(clock_.time(steps_done));
    const double outside = plan_.peer ? peer_coating_outside_ : passes_->coatingOutsidePasses();
    if (outside != 0.0) {
      log_.warn("zone passes: " + analysis::formatShortest(outside) +
                " kg of coating went to parcels outside the coating zone (expected 0)");
    }
  } catch (const std::exception& e) {
    log_.warn(std::string("could not finish ") + analysis::kZonePassesFile + ": " + e.what());
  }
  passes_.reset();
}

void Coupler::check(const link::ParticleData& s, const std::string& where) const {
  if (auto problem = checkParticleState(s, where, sc_.checks.max_particle_speed, step_, time_))
    throw RunFailure(where, *problem);
}

void Coupler::refuseOrWarn(const StabilityReport& rep) {
  for (const auto& line : rep.lines) log_.show("check: " + line);
  if (!rep.refusals.empty() && sc_.checks.stability == "refuse") {
    std::string msg = "unstable settings refused:";
    for (const auto& r : rep.refusals) msg += "\n  - " + r;
    msg += "\n  (set checks.stability: warn to run anyway)";
    throw RunFailure("", msg, ErrorKind::input);
  }
}

std::string Coupler::describe(const RunFailure& f) const {
  std::string s =
      (f.participant.empty() ? std::string("cosim") : "participant '" + f.participant + "'") +
      ": " + f.what();
  if (const auto log = participants_.logOf(f.participant); !log.empty())
    s += "\n  last lines of " + log.string() + ":\n" + tailOfFile(log, 15);
  return s;
}

analysis::Summary Coupler::summarize(const RunResult& r, const std::string& status) const {
  analysis::Summary s;
  s.scenario = sc_.name;
  // The run's id is the one particles.h5 was created with, kept across resumes; the id on the
  // wire (run_id_) is new for every process, so that no participant of an earlier piece can
  // answer this one.
  s.run_id = record_.runId().empty() ? run_id_ : record_.runId();
  s.status = status;
  s.message = r.message;
  s.start_time = sc_.coupling.start_time;
  s.end_time = time_;
  s.steps = static_cast<std::int64_t>(r.steps);
  for (const auto& [k, v] : totals_) s.headline.emplace_back(k, v);
  s.headline.emplace_back("particle_count", static_cast<double>(state_.size()));
  s.timings.emplace_back("total", r.wall_seconds);
  for (const auto& [n, w] : participants_.computeSeconds())
    s.timings.emplace_back(n + "_compute", w);
  for (const auto& [n, w] : participants_.advanceWireSeconds())
    s.timings.emplace_back("advance_" + n, w);
  for (const auto& [n, w] : phases_.seconds) s.timings.emplace_back("step_" + n, w);
  s.parameters.assign(sc_.parameters.begin(), sc_.parameters.end());
  s.coupling_dt = sc_.coupling.dt;
  s.dem_steps = static_cast<std::int64_t>(sc_.coupling.dem_steps);
  s.cg = sc_.constants.cg;
  s.coating = plan_.coating;
  s.observables = r.observables;
  return s;
}

}  // namespace cosim::orchestrator

// Stability checks and run-time monitors.
//
// Before the run / at the first coupling step each check prints its ratio; an unstable setting
// is refused (checks.stability: refuse, the default) with the value that would work, a doubtful
// one is a warning. While running, the monitors stop the run cleanly on NaN/Inf, voidage out of
// bounds, runaway particle speed, particles that vanish without being reported, a Courant number
// beyond the limit, or a drifting precursor mass balance; the message says what, where and when.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "cosim/link/particle_data.h"
#include "cosim/util/rayleigh_time.h"
#include "plan.h"
#include "scenario.h"

namespace cosim::orchestrator {

struct StabilityReport {
  std::vector<std::string> lines;     // every check with its ratio ("ok", "warning: ...")
  std::vector<std::string> refusals;  // unstable: what is wrong and what would work
};

// Rayleigh time of a Hertzian sphere (docs/physics.md section 7), the one implementation the
// LIGGGHTS adapter's time-step check uses too, with the same limits.
using util::rayleighTime;
// Particle relaxation time under a drag coefficient K [kg/s]: tau = m / K.
double relaxationTime(double mass, double drag_coefficient);

// Checks that need only the scenario and the initial particle state. The DEM step against the
// Rayleigh time uses one source of material data: the particle participant's own, when it reports
// DEM dt / Rayleigh time (`reported_dt_over_rayleigh` > 0, ParticleReport; LIGGGHTS does, from
// its script's youngsModulus and poissonsRatio); only a participant that reports none is judged
// from constants.youngs_modulus and poisson_ratio. Constants that disagree with the participant's
// own data by more than 1 % are named in a warning.
StabilityReport checkBeforeRun(const Scenario& sc, const models::SceneModels& models,
                               const Plan& plan, const link::ParticleData& initial_state,
                               double reported_dt_over_rayleigh = 0.0);

// Checks that need the first fluid samples and drag coefficients: relaxation time against the
// coupling interval and DEM step, cell size against parcel size.
StabilityReport checkFirstStep(const Scenario& sc, const link::ParticleData& state,
                               const link::ParticleData& samples,
                               const link::ParticleData& forcing);

// A state that no physics allows: a non-finite value, a particle faster than
// checks.max_particle_speed, a voidage outside (0, 1]. Returns what is wrong, where and when.
std::optional<std::string> checkParticleState(const link::ParticleData& state,
                                              const std::string& where, double max_speed,
                                              std::uint64_t step, double time);

// The peer path between records (Advance.state_changes_only): `ids`, the parcels held before the
// step (sorted), become those after it, from the ids the particles reported inserted and deleted;
// `count` is the number they report holding. Returns what does not add up (a deleted parcel not
// held, an inserted one held already or twice, another count), leaving `ids` as they were.
std::optional<std::string> applyParticleChanges(std::vector<std::int64_t>& ids,
                                                std::vector<std::int64_t> inserted,
                                                std::vector<std::int64_t> deleted,
                                                std::uint64_t count);

// The parcels of a whole state (`sent`, in any order) against the ids kept from the reported
// changes (`known`, sorted): which parcel one holds and the other does not, if any.
std::optional<std::string> compareWithChanges(const std::vector<std::int64_t>& known,
                                              std::vector<std::int64_t> sent);

// The particles held when coupling starts against checks.particle_count (when the scene sets
// it): another count says what was inserted, the mass it stands for (with
// constants.particle_density) against the mass asked for, and what to do. nullopt if it agrees
// or is not checked.
std::optional<std::string> checkParticleCount(const Scenario& sc,
                                              const link::ParticleData& initial_state);

// What particles.h5 grows by from t = `from` to the run's end [bytes]: one snapshot per
// output.interval (every coupling step when it is shorter), each the ids and the recorded fields
// (plan.particles_send) of `state`'s particles as doubles, plus a few kB of groups and attributes.
double particleOutputBytes(const Scenario& sc, const Plan& plan, const link::ParticleData& state,
                           double from);
// A warning when that growth exceeds 80 % of `available` bytes on the run folder's disk (the run
// would stop with the disk full, keeping what it wrote), with an output.interval that would fit;
// nullopt when it fits.
std::optional<std::string> checkDiskSpace(const Scenario& sc, const Plan& plan,
                                          const link::ParticleData& state, double from,
                                          double available);

// "52.3 MB", "1.0 kB"
std::string byteText(std::uintmax_t bytes);
// The size of a file, or of everything below a folder (links not followed) [bytes]
std::uintmax_t bytesOnDisk(const std::filesystem::path& p);

// The disk filling while the run goes (checked at every checkpoint): the run folder's disk had
// `free0` bytes free at simulated time `t0` and has `free_now` at `t`. When at that rate
// (everything the disk lost since t0: logs, time folders, dumps, snapshots, other programs) it is
// full before `end`, a warning with the rate, the time it is full and `largest` (what takes the
// most room in the run folder, "fluid.log 530.0 MB, ...", asked for only then); nullopt otherwise.
std::optional<std::string> checkDiskFilling(double t0, double free0, double t, double free_now,
                                            double end,
                                            const std::function<std::string()>& largest);

// The `n` largest entries of a run folder with their sizes: "fluid.log 530 MB, particles/ 90 MB".
std::string largestEntries(const std::filesystem::path& folder, std::size_t n);

// Per-step monitors that need memory across steps.
class StepMonitor {
 public:
  explicit StepMonitor(const Scenario& sc) : sc_(sc) {}
  // Ids that vanished without being reported deleted; throws std::runtime_error with the ids.
  void checkParticleLedger(const std::vector<std::int64_t>& before,
                           const std::vector<std::int64_t>& after,
                           const std::vector<std::int64_t>& inserted,
                           const std::vector<std::int64_t>& deleted, std::uint64_t step,
                           double time);
  // Courant number reported by the fluid: warning once above 1, stop above checks.max_courant.
  // Returns a warning to show (once) or nullopt.
  std::optional<std::string> checkCourant(double courant, std::uint64_t step, double time);
  // The precursor's smallest mass fraction in the gas: a warning (once a run piece) when it is
  // negative beyond round-off (below -1e-6 of the largest), with where it comes from and what the
  // parcels make of it; nullopt otherwise.
  std::optional<std::string> checkPrecursorBounds(double smallest, double largest,
                                                  std::uint64_t step, double time);
  // Precursor balance in - out - (held - held0) - removed, relative to what came in: stop when
  // it drifts above checks.mass_balance_tolerance.
  // Precursor the gas held at the start (the fluid's precursor_held_start): the balance then
  // counts from the start instead of from the end of the first step.
  void setHeldAtStart(double held);
  void checkMassBalance(double in, double out, double held, double removed, std::uint64_t step,
                        double time);

  // What the monitors remember across steps (saved with a checkpoint).
  struct State {
    bool courant_warned = false;
    std::optional<std::array<double, 4>> baseline;  // in, out, held, removed at the start
  };
  State state() const { return {courant_warned_, baseline_}; }
  void restore(const State& s) {
    courant_warned_ = s.courant_warned;
    baseline_ = s.baseline;
  }

 private:
  const Scenario& sc_;
  bool courant_warned_ = false;
  bool undershoot_warned_ = false;
  bool ledger_checked_ = false;  // the full id check ran once (later steps may take the fast path)
  std::optional<std::array<double, 4>> baseline_;
};

}  // namespace cosim::orchestrator

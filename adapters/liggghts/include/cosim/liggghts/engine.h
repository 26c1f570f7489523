// Engine: one embedded LIGGGHTS instance plus the coupling this adapter adds to the user's
// script (per-atom forcing properties, the coating-mass property, the cosim/drag fix).
//
// Every method is collective: all MPI ranks of the communicator call it with the same
// arguments. Results that are gathered (state()) are complete on rank 0 only.
// Any LIGGGHTS error becomes a LiggghtsError carrying LIGGGHTS' own message.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "cosim/liggghts/timestep_check.h"

namespace LAMMPS_NS {
class LAMMPS;
}

namespace cosim::liggghts {

// Name of the per-atom property holding the coating mass [kg]. A script may define it itself
// (to dump it): fix coatingMass all property/atom coatingMass scalar yes no no 0
inline constexpr const char* kCoatingMassProperty = "coatingMass";

// Forcing for one coupling interval, by particle id. Empty vectors = term not sent.
struct Terms {
  std::vector<std::int64_t> ids;
  std::vector<double> drag_coefficient;   // K [kg/s], one per id
  std::vector<double> fluid_velocity;     // u_f [m/s], 3 per id
  std::vector<double> explicit_force;     // [N], 3 per id
  std::vector<double> coating_increment;  // [kg], one per id
};

// Particle state sorted by id (rank 0).
struct State {
  std::vector<std::int64_t> ids;
  std::vector<int> rank;         // the rank that holds each parcel (several ranks only)
  std::vector<double> position;  // 3 per id
  std::vector<double> velocity;  // 3 per id
  std::vector<double> radius;
  std::vector<double> mass;
  std::vector<double> coating_mass;
  std::vector<double> type;
};

// Written beside a restart file whose fix property/atom data hold the last step's forces other
// than the fluid's (checkpoints written before that lack it and resume as before).
inline constexpr const char* kOtherForcesMarker = "liggghts.other-forces";

class Engine {
 public:
  // workdir: where LIGGGHTS writes its screen (liggghts.screen) and log (liggghts.log) files.
  // Relative paths in the script are resolved against the process' current directory.
  Engine(MPI_Comm comm, const std::filesystem::path& workdir);
  ~Engine();
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  std::filesystem::path screenFile() const { return workdir_ / "liggghts.screen"; }

  // Runs the user's script (which sets up box, materials, walls, insertion, integration).
  void runScript(const std::filesystem::path& script);
  // Resume: runs the scene's script with the commands that build and fill the box replaced by
  // `read_restart restart` (create_box, read_data -> read_restart; create_atoms, one-off
  // insertions `insert_every once` and their `unfix`, run, reset_timestep and write_restart left
  // out), so the particles, their coating, their contact history and the step counter continue
  // from the restart file. Other fixes, walls, continuous insertions and dumps are defined again
  // as written and pick up their restart data. The rewritten script is written beside the
  // script as SCRIPT.resume and run as a file, so its flow control (label, jump SELF, if) works.
  void resumeScript(const std::filesystem::path& script, const std::filesystem::path& restart);
  // One LIGGGHTS command.
  void command(const std::string& line);
  // Adds the coupling (per-atom properties and the cosim/drag fix). Call once, after the script.
  void installCoupling();

  double timestep() const;
  // LIGGGHTS' step counter (update->ntimestep).
  std::int64_t step() const;
  // Number of dumps the script defines.
  int dumpCount() const;
  // Writes every dump of the script at the current step, unless it already did at this step
  // (a run's final state: LIGGGHTS writes dumps only at multiples of their interval).
  void writeDumpsNow();
  std::int64_t particleCount() const;
  // Rayleigh and Hertz times over all current particles, from the script's fix property/global
  // youngsModulus and poissonsRatio. Throws std::runtime_error if they are not defined.
  TimestepReport timestepReport(double impact_speed) const;
  // The smallest radius over the particles timestepReport() looks at (a few instructions per
  // particle: the full report is only needed when it shrinks); max() without particles.
  double minRadius() const;

  // Sets the forcing of the next advance(): particles not listed get no fluid force; coating
  // increments are added to the listed particles' coating mass. Throws std::runtime_error naming
  // the particle for unknown or duplicate ids and non-finite or negative K.
  void applyTerms(const Terms& terms);
  // The checks of applyTerms alone (no LIGGGHTS needed): rank 0 makes them over every parcel
  // before it sends each rank its part.
  static void checkTerms(const Terms& terms);
  // The forcing of this rank's own parcels, checked already (checkTerms on rank 0): every id
  // must be a parcel this rank holds, else PeerError on every rank.
  void applyOwnTerms(const Terms& terms);
  // Runs `steps` DEM steps.
  void advance(int steps);
  // Gathers the state to rank 0 (sorted by id); other ranks get an empty State.
  State state() const;
  // Writes a LIGGGHTS restart file (includes the coating mass and the forces of the last step
  // other than the fluid's, and beside it kOtherForcesMarker) without changing the run; returns
  // its path.
  std::filesystem::path writeRestart(const std::filesystem::path& file);

  // true once a LIGGGHTS error left the instance unusable.
  bool broken() const { return broken_; }

 private:
  // own: the terms are this rank's parcels' (applyOwnTerms), else every rank's (applyTerms)
  void applyCheckedTerms(const Terms& terms, bool own);
  template <class F>
  void guarded(const std::string& what, F&& f);
  [[noreturn]] void failWithLiggghtsMessage(const std::string& what, bool aborted);

  MPI_Comm comm_;
  int rank_ = 0;
  int size_ = 1;
  std::filesystem::path workdir_;
  std::filesystem::path script_;
  LAMMPS_NS::LAMMPS* lmp_ = nullptr;
  class DragRelaxationFix* drag_fix_ = nullptr;  // owned by LIGGGHTS' fix list
  bool coupled_ = false;
  bool keep_restored_forces_ = false;  // resumed from a restart that holds the other forces
  bool need_setup_ = true;  // next run must do a full setup (new fixes since the last run)
  bool broken_ = false;
};

}  // namespace cosim::liggghts

// LIGGGHTS fix "cosim/drag": applies the fluid forcing of the orchestrator at EVERY DEM step,
//   F = K (u_f - v) + F_explicit,
// with the particle's current velocity, integrated exactly (exponential relaxation, see
// exponential_drag.h) so that relaxation times m/K far shorter than the coupling interval or the
// DEM step stay stable. K, u_f and F_explicit are per-atom properties (fix property/atom) that
// migrate with the atoms between MPI ranks; particles without terms have K = 0, F_explicit = 0
// and feel no fluid force.
//
// The fix must be the last post_force fix so that it sees every other force (pair contacts,
// walls, gravity); Coupling::install() appends it after the user's script has run.
#pragma once

#include <vector>

#include "fix.h"

namespace cosim::liggghts {

// Names of the per-atom properties the fix reads (fix property/atom variable names).
inline constexpr const char* kDragCoefficientProperty = "cosimDragK";    // scalar [kg/s]
inline constexpr const char* kFluidVelocityProperty = "cosimFluidVel";   // vector [m/s]
inline constexpr const char* kExplicitForceProperty = "cosimExplicitF";  // vector [N]
// Written by the fix: every force on the atom except the fluid forcing, at the last step [N].
inline constexpr const char* kOtherForceProperty = "cosimOtherF";  // vector [N]
// Written by the fix: the torque on the atom at the last step, kept for the same reason [N m].
inline constexpr const char* kLastTorqueProperty = "cosimLastTorque";  // vector [N m]

class DragRelaxationFix : public LAMMPS_NS::Fix {
 public:
  DragRelaxationFix(LAMMPS_NS::LAMMPS* instance, int narg, char** arg);
  int setmask() override;
  void init() override;
  void setup(int vflag) override;
  void post_force(int vflag) override;
  // Recomputes the total force of the local atoms with the current forcing properties. Called
  // when new terms arrive between two runs: LIGGGHTS starts a `run ... pre no` with the forces
  // of the previous step, which still hold the previous interval's forcing.
  void refreshForces();

  // The next setup (a `run ... pre yes`) keeps the stored other forces instead of taking them
  // from the forces LIGGGHTS recomputes there. Those would differ from the ones the step saw:
  // the contacts' damping is evaluated with the full-step velocity at a setup, with the
  // half-step one inside a step. Used after writing a checkpoint and after resuming from one, so
  // that neither changes the run.
  void keepOtherForcesAtNextSetup() { keep_other_ = true; }

 private:
  LAMMPS_NS::Fix* drag_coefficient_ = nullptr;
  LAMMPS_NS::Fix* fluid_velocity_ = nullptr;
  LAMMPS_NS::Fix* explicit_force_ = nullptr;
  LAMMPS_NS::Fix* other_force_ = nullptr;
  LAMMPS_NS::Fix* last_torque_ = nullptr;
  bool keep_other_ = false;
  // phi(K dt / m) of the atom at each local index, with the K, m and dt it was computed from:
  // K and m change only between coupling intervals, so the expm1 runs once per atom and
  // interval, not once per DEM step (an atom moved to another index simply misses the cache)
  std::vector<double> cache_K_, cache_m_, cache_phi_;
  double cache_dt_ = 0.0;
  // Where apply() takes the other forces from: those LIGGGHTS has just computed (kept for
  // later at the last step of a run, computed_kept), or the kept ones.
  enum class Source { computed, computed_kept, kept };
  void lookup();
  void apply(Source from);
};

}  // namespace cosim::liggghts

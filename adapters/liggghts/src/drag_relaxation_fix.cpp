#include "cosim/liggghts/drag_relaxation_fix.h"

#include "atom.h"
#include "cosim/liggghts/exponential_drag.h"
#include "error.h"
#include "modify.h"
#include "update.h"

namespace cosim::liggghts {

using namespace LAMMPS_NS;

DragRelaxationFix::DragRelaxationFix(LAMMPS* instance, int narg, char** arg)
    : Fix(instance, narg, arg) {}

int DragRelaxationFix::setmask() { return FixConst::POST_FORCE; }

void DragRelaxationFix::lookup() {
  drag_coefficient_ =
      modify->find_fix_property(kDragCoefficientProperty, "property/atom", "scalar", 0, 0, style);
  fluid_velocity_ =
      modify->find_fix_property(kFluidVelocityProperty, "property/atom", "vector", 0, 0, style);
  explicit_force_ =
      modify->find_fix_property(kExplicitForceProperty, "property/atom", "vector", 0, 0, style);
  other_force_ =
      modify->find_fix_property(kOtherForceProperty, "property/atom", "vector", 0, 0, style);
  last_torque_ =
      modify->find_fix_property(kLastTorqueProperty, "property/atom", "vector", 0, 0, style);
}

void DragRelaxationFix::init() {
  lookup();
  if (!atom->rmass_flag || !atom->radius_flag)
    error->all(FLERR,
               "cosim/drag needs spheres with per-atom mass (atom_style sphere or granular)");
}

void DragRelaxationFix::setup(int) {
  apply(!keep_other_);
  keep_other_ = false;
}

void DragRelaxationFix::post_force(int) { apply(true); }

void DragRelaxationFix::refreshForces() {
  lookup();
  apply(false);
}

void DragRelaxationFix::apply(bool store_other_force) {
  const double dt = update->dt;
  const double* K = drag_coefficient_->vector_atom;
  double** uf = fluid_velocity_->array_atom;
  double** fex = explicit_force_->array_atom;
  double** other = other_force_->array_atom;
  double** torque_kept = last_torque_->array_atom;
  double** torque = atom->torque;
  double** v = atom->v;
  double** f = atom->f;
  const double* mass = atom->rmass;
  const int* amask = atom->mask;
  const int nlocal = atom->nlocal;
  const auto n = static_cast<std::size_t>(nlocal);
  if (cache_K_.size() < n || cache_dt_ != dt) {
    cache_K_.assign(n, -1.0);  // no K is negative: every entry misses
    cache_m_.assign(n, 0.0);
    cache_phi_.assign(n, 1.0);
    cache_dt_ = dt;
  }
  for (int i = 0; i < nlocal; ++i) {
    if (!(amask[i] & groupbit)) continue;
    if (store_other_force) {
      for (int d = 0; d < 3; ++d) other[i][d] = f[i][d];
      if (torque)
        for (int d = 0; d < 3; ++d) torque_kept[i][d] = torque[i][d];
    } else if (torque && keep_other_) {
      for (int d = 0; d < 3; ++d) torque[i][d] = torque_kept[i][d];
    }
    if (K[i] <= 0.0) {
      // no drag: the explicit force (if any) is simply added
      for (int d = 0; d < 3; ++d) f[i][d] = other[i][d] + fex[i][d];
      continue;
    }
    // phi(K dt / m) is the same for the three components and for every DEM step of the
    // interval: one expm1 per particle and interval
    if (cache_K_[i] != K[i] || cache_m_[i] != mass[i]) {
      cache_K_[i] = K[i];
      cache_m_[i] = mass[i];
      cache_phi_[i] = exponentialDragFactor(K[i] * dt / mass[i]);
    }
    const double phi = cache_phi_[i];
    for (int d = 0; d < 3; ++d)
      f[i][d] = phi * (K[i] * (uf[i][d] - v[i][d]) + (other[i][d] + fex[i][d]));
  }
}

}  // namespace cosim::liggghts

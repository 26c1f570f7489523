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
  apply(keep_other_ ? Source::kept : Source::computed_kept);
  keep_other_ = false;
}

// The other forces are kept only at the last step of a run: what reads them (the next
// interval's refreshForces, a restart file, the setup after one) comes after a run.
void DragRelaxationFix::post_force(int) {
  apply(update->ntimestep == update->laststep ? Source::computed_kept : Source::computed);
}

void DragRelaxationFix::refreshForces() {
  lookup();
  apply(Source::kept);
}

namespace {

// The per-atom arrays of one apply(): distinct LIGGGHTS arrays, never overlapping.
struct DragArrays {
  const double* __restrict K;
  const double* __restrict uf;
  const double* __restrict fex;
  double* __restrict other;
  double* __restrict torque_kept;
  double* __restrict torque;
  const double* __restrict v;
  double* __restrict f;
  const double* __restrict mass;
  const int* __restrict mask;
  double* __restrict cache_K;
  double* __restrict cache_m;
  double* __restrict cache_phi;
};

// Where the other forces of one apply() come from.
enum class Other {
  computed,       // LIGGGHTS has just computed them (a DEM step)
  computed_kept,  // the same, at the last step of a run: kept (with the torque) for what follows
  kept,           // the kept ones (new forcing between two runs, or the setup after a restart)
};

// F = phi(K dt / m) (K (u_f - v) + F_other + F_explicit) for every atom of the group. kTorque
// with Other::kept: the kept torque is put back as well.
template <Other kFrom, bool kTorque>
void relax(const DragArrays& a, int nlocal, int groupbit, double dt) {
  for (int i = 0; i < nlocal; ++i) {
    if (!(a.mask[i] & groupbit)) continue;
    const int j = 3 * i;
    double o[3];
    for (int d = 0; d < 3; ++d) {
      if constexpr (kFrom == Other::kept) {
        o[d] = a.other[j + d];
        if constexpr (kTorque) a.torque[j + d] = a.torque_kept[j + d];
      } else {
        o[d] = a.f[j + d];
        if constexpr (kFrom == Other::computed_kept) {
          a.other[j + d] = o[d];
          if constexpr (kTorque) a.torque_kept[j + d] = a.torque[j + d];
        }
      }
    }
    const double k = a.K[i];
    if (k <= 0.0) {
      // no drag: the explicit force (if any) is simply added
      for (int d = 0; d < 3; ++d) a.f[j + d] = o[d] + a.fex[j + d];
      continue;
    }
    // phi(K dt / m) is the same for the three components and for every DEM step of the
    // interval: one expm1 per particle and interval
    if (a.cache_K[i] != k || a.cache_m[i] != a.mass[i]) {
      a.cache_K[i] = k;
      a.cache_m[i] = a.mass[i];
      a.cache_phi[i] = exponentialDragFactor(k * dt / a.mass[i]);
    }
    const double phi = a.cache_phi[i];
    for (int d = 0; d < 3; ++d)
      a.f[j + d] = phi * (k * (a.uf[j + d] - a.v[j + d]) + (o[d] + a.fex[j + d]));
  }
}

}  // namespace

void DragRelaxationFix::apply(Source from) {
  const double dt = update->dt;
  const int nlocal = atom->nlocal;
  const auto n = static_cast<std::size_t>(nlocal);
  if (cache_K_.size() < n || cache_dt_ != dt) {
    cache_K_.assign(n, -1.0);  // no K is negative: every entry misses
    cache_m_.assign(n, 0.0);
    cache_phi_.assign(n, 1.0);
    cache_dt_ = dt;
  }
  if (nlocal == 0) return;
  // LIGGGHTS allocates every per-atom array as one block (Memory::create/grow): the 3 values of
  // atom i are at [3 i, 3 i + 3) of the first row. Flat pointers spare a load per array and atom
  // on this path, which runs at every DEM step.
  const bool torque = atom->torque != nullptr;
  const DragArrays a{drag_coefficient_->vector_atom,
                     fluid_velocity_->array_atom[0],
                     explicit_force_->array_atom[0],
                     other_force_->array_atom[0],
                     last_torque_->array_atom[0],
                     torque ? atom->torque[0] : nullptr,
                     atom->v[0],
                     atom->f[0],
                     atom->rmass,
                     atom->mask,
                     cache_K_.data(),
                     cache_m_.data(),
                     cache_phi_.data()};
  if (from == Source::computed) {
    relax<Other::computed, false>(a, nlocal, groupbit, dt);
  } else if (from == Source::computed_kept) {
    if (torque)
      relax<Other::computed_kept, true>(a, nlocal, groupbit, dt);
    else
      relax<Other::computed_kept, false>(a, nlocal, groupbit, dt);
  } else if (torque && keep_other_) {
    relax<Other::kept, true>(a, nlocal, groupbit, dt);
  } else {
    relax<Other::kept, false>(a, nlocal, groupbit, dt);
  }
}

}  // namespace cosim::liggghts

// Build-up in time of a parcel's own disturbance of its cell's gas, for
// `models.drag.undisturbed_velocity: self_disturbance_transient` (docs/models.md, "Build-up in
// time"). The steady estimate (undisturbed_velocity.h) assumes the gas of the parcel's cell has
// answered the whole force; the real gas answers a force switched on at t = 0 with
//
//   u_self(t) = -G S(t) F,   S(tau) = C(tau) / C(inf),  C(tau) = int_0^tau [e^-2s I0(2s)]^3 ds,
//
// tau = nu t / Delta^2 (the on-site heat kernel of the 7-point Laplacian; the projection onto
// divergence-free fields keeps 2/3 of it at every time, by the cubic symmetry). 1 - S falls as
// 0.178 / sqrt(tau) (3-D diffusion). For any force history u_self = -G H with H the "built-up
// force" (Duhamel): H = sum over past force increments dF_k of S(t - t_k) dF_k.
//
// S is held as a sum of exponentials, 1 - S(tau) = sum_i w_i exp(-lambda_i tau) (21 modes,
// lambda_i in the lattice's spectrum [0, 12], w_i >= 0, sum w_i = 1, sum w_i lambda_i =
// 1/C(inf); fitted by scenarios/verify-wake/kernel.py, error < 1.1e-3 in S over all tau, < 1.2e-4
// for tau >= 1), so H = sum_i y_i with one 3-vector y_i per mode and parcel:
//
//   dy_i/dt = r_i (w~_i F - y_i),   r_i = (lambda_i + c) nu_f / Delta^2,
//   w~_i = w_i q_i / sum_j w_j q_j,  q_i = lambda_i / (lambda_i + c),   c = (sqrt(1 + Re) - 1)^2
//
// nu_f = eps_f mu / (eps rho) (the viscous flux through the faces, as in the steady G), Re =
// |u_f| Delta / nu_f the cell Reynolds number. c is the flow carrying the disturbance away: the
// late decay rate (in nu / Delta^2) of the on-site kernel of the lattice walk with an upwind
// drift, exp(-(a + b) t) I0(2 sqrt(a b) t) along the flow (a = nu/Delta^2, b = a + |u|/Delta):
// Re^2 / 4, i.e. |u|^2 / (4 nu), at low Re (the Oseen cut-off of the diffusion tail) and
// -> |u| / Delta at high Re (the upwind outflow, whose own build-up is 1 - e^-(|u| t / Delta)).
// It shortens every mode and moves the weight to the fast ones: exact in the two limits (no
// flow: S; no viscosity: the upwind outflow) and for the tail at low Re, an approximation between.
// Steady: H = F, the steady estimate. The gas solver's step is implicit Euler, one CFD step per
// coupling interval, so the modes are advanced the same way:
//
//   y_i <- (y_i + r_i dt w~_i F) / (1 + r_i dt)
//
// which is the lattice's implicit-Euler response mode by mode (checked against the exact one in
// kernel.py: within 3e-4 after one step). F is the force the gas got over the interval: the gas
// solver takes the drag implicitly, K (U_new - v) with its own new velocity U_new and the
// parcel's velocity v at the start of the interval (adapters/openfoam/gas/UEqn.H), which is
// less than K (u_f - v) at the start while the wake builds up (by 1 / (1 + K G S_1), 40 % in
// cells of 2 diameters). So each interval's K and v are kept, and the modes are advanced at the
// start of the next interval, when the gas's new velocity at the parcel has been sampled:
// F = K (u_f,new - v). (The sample is the cell's velocity when the parcel lies in one cell.)
//
// Cell identity: the parcel's cell is not known to the coupler (cell_size is its size only), so
// each parcel keeps an anchor, the position where its history started, moved by whole cells of
// the current Delta: when the parcel is more than half a cell from it along an axis it is taken
// to be in the next cell along that axis (n_j = round((x_j - anchor_j) / Delta) cells), the
// anchor moves by n_j Delta and every mode keeps the share the old cell's disturbance has in the
// new one: (1 - lambda_i / 6)^(|n_x| + |n_y| + |n_z|). One cell over, 1 - lambda / 6 is exact
// per lattice mode (the mean of cos k over the six neighbours; the steady share is
// 1 - 1 / (6 C(inf)) = 0.3405); more than one cell over it is the product of single steps, an
// approximation. Exact for a parcel that starts centred in its cell on a uniform mesh; a parcel
// that starts off centre changes cell up to half a cell early or late.
//
// Parcels are held by id: a new id starts with no history (its gas is undisturbed), an id no
// longer present is dropped, a lost parcel (in no cell) loses its history.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <vector>

#include "cosim/models/parcels.h"

namespace cosim::models {

struct WakeKernel {
  static constexpr std::size_t kModes = 21;
  struct Mode {
    double lambda;  // decay rate in units of nu / Delta^2
    double weight;  // w_i
  };
  static const std::array<Mode, kModes>& modes();
  // S(tau) of the modes: 1 - sum w_i exp(-lambda_i tau)
  static double buildup(double tau);
  // The modes after m implicit-Euler steps of tau_s each: 1 - sum w_i (1 + lambda_i tau_s)^-m
  static double buildupImplicit(int m, double tau_s);
  // The share of mode i kept when the parcel moves one cell over: 1 - lambda_i / 6
  static double neighbourShare(std::size_t i) { return 1.0 - modes()[i].lambda / 6.0; }
};

class WakeBuildup {
 public:
  struct Parcel {
    std::array<double, 3> anchor{};                  // [m] where its cell is taken to be
    std::array<double, 3 * WakeKernel::kModes> y{};  // [N] y_i, mode by mode, x y z
    // The interval not yet in y (dt = 0: none): its drag coefficient and parcel velocity
    double K = 0.0;             // [kg/s]
    std::array<double, 3> v{};  // [m/s]
    double dt = 0.0;            // [s]
  };
  using State = std::map<std::int64_t, Parcel>;

  // The built-up force H of every parcel (3n, [N]) at the start of this interval, for
  // ParcelBatch::built_up_force. First advances each parcel's modes over the last interval
  // with the force its gas got, K (u_f - v) from the recorded K and v and the sampled u_f (the
  // rates from this sample), then moves the history to the parcel's cell. Keeps exactly the
  // parcels `ids` (n of them, the batch's order): new ids start empty, absent ids are dropped,
  // lost parcels are dropped and get 0; a parcel that changed cell keeps the old cell's share.
  // Reads position, cell_size, fluid_velocity, voidage, fluid_density, fluid_viscosity.
  std::vector<double> startInterval(const std::vector<std::int64_t>& ids, const ParcelBatch& p,
                                    const SceneConstants& c);
  // Records the interval dt [s] that starts now: the drag coefficients K sent to the solvers
  // and the parcels' velocities. Call after startInterval, same batch, once per interval.
  void recordInterval(const std::vector<std::int64_t>& ids, const ParcelBatch& p, const double* K,
                      double dt);

  // The per-parcel history, for checkpoints (restored bit for bit).
  const State& state() const { return parcels_; }
  void restore(State s) { parcels_ = std::move(s); }

 private:
  State parcels_;
};

}  // namespace cosim::models

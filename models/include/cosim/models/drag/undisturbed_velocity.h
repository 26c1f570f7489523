// Undisturbed gas velocity at a parcel: removes the parcel's own disturbance ("self-induced
// velocity", its wake in its own cell) from the sampled gas velocity before drag is evaluated.
// Selected with `models.drag.undisturbed_velocity: self_disturbance` on any drag law (default
// `none`); docs/models.md has the derivation, the choice and the limits.
//
// The gas the parcel samples is the average over the cells its volume was deposited to, and
// that gas already carries the reaction -F of the parcel's own drag. For a force F spread over
// one cubic cell of side Delta the steady response of the discretised gas momentum in that cell
// is u_self = -G F with
//
//   G = 1 / ( eps_f mu Delta / c_v  +  eps rho |u_f| Delta^2 / c_a ),   eps_f = (1 + eps) / 2
//
//   c_v = (2/3) W_sc = 0.168487   viscous: W_sc = 0.2527310 is the Green's function of the
//                                 7-point Laplacian at the source (Watson's integral / 6);
//                                 the projection onto divergence-free fields keeps exactly 2/3
//                                 of it on the cubic lattice (trace of I - kk/k^2 = 2, split
//                                 equally over 3 directions).
//   c_a = 1                       advective: at high cell Reynolds number the momentum put
//                                 into the cell leaves through its downstream face with the
//                                 superficial mass flux eps rho |u_f| Delta^2 (upwind balance).
//
// The two are parallel momentum sinks (conductances add). With F = K (u_und - v) and
// u_s = u_und - G F (a lone parcel),
//
//   u_und - v = (u_s - v) / (1 - a),  a = K G,    so    K_eff = K(u_und) / (1 - a)
//
// and the force is F = K_eff (u_s - v): the correction is a factor on K, applied the same way
// by both solvers (the fluid keeps K_eff implicit), so momentum stays conserved. K is
// re-evaluated at the undisturbed slip (fixed point until K changes by < 1e-13, at most 50
// passes; it contracts with the factor (dln K / dln |u - v|) a / (1 - a), 0.1-0.3 in practice).
// a is bounded by kMaxSelfCoupling = 0.9 (K_eff at most 10 K): beyond it the estimate is
// capped and the drag is under-corrected, never unstable or negative.
//
// Dense suspensions: voidage-dependent laws are defined on the cell-average gas velocity that
// already contains the disturbance of every particle in the cell, and the other particles of
// the cell resist the disturbance a parcel makes (their drag is a momentum sink in parallel with
// the free gas). With w the parcel's share of its cell's solid volume,
//
//   w     = min(1, V_parcel / ((1 - eps) Delta^3))     (1 when the cell holds no other solid)
//   K_o   = K (1 - w) / w                               (the others, as much drag per volume)
//   G_eff = 1 / (1/G + K_o),   self-coupling  a = w K G_eff   (instead of K G)
//
// A lone parcel gets the full correction (a = K G); in a packed cell (K G >> 1) a -> w^2/(1-w).
//
// `self_disturbance` is steady: it assumes the disturbance has built up (viscous time
// rho Delta^2 / mu with a t^-1/2 tail, advective Delta / |u_f|); until then it over-corrects
// (measured in docs/verification.md, section 4). It keeps no per-parcel memory.
//
// `self_disturbance_transient` uses the disturbance built up so far instead: the coupler keeps
// each parcel's force history (WakeBuildup, wake_buildup.h) and passes H, the part of its force
// the cell's gas has answered (ParcelBatch::built_up_force; H = F once built up). Then
//
//   u_und = u_s + w G_eff H                      (explicit: H holds past forces only)
//   K     = K(u_und)                             (fixed point only through G_eff's K)
//   K_eff = K (1 + x),  x = (u_und - u_s) . (u_s - v) / |u_s - v|^2,  x in [-0.9, 9]
//
// K_eff (u_s - v) is K (u_und - v) along the sampled slip (exact when H is parallel to it, as
// for a settling or dragged parcel; the part of H across the slip is not applied). Still a pure
// factor on K, applied by both solvers: momentum stays conserved and the drag stays implicit.
// Bounds: K_eff in [0.1 K, 10 K], as the steady cap (a <= 0.9); x < 0 when the parcel's old
// wake runs against its slip (a reversal). Built up (H = F) it is the steady estimate.
//
// Calibrated for the gas solver (`self_disturbance_gain` gamma, `self_disturbance_offset` beta,
// defaults 1 and 0: the lattice above). The gas solver's own discrete operator, with its
// solver settings and time step, answers a lone parcel as
//
//   u_s - v = (1 + beta f) (u_und - v) - gamma w G_eff F,     f = w G_eff / G  (1 when lone)
//
// gamma: its response per unit force against the lattice's G; beta: the parcel's own cell
// running ahead of the undisturbed gas with no force at all (its velocity reconstructed from face
// fluxes over a voidage below 1). Both are measured with a held parcel in the scene's own mesh and
// solver settings (docs/verification.md, section 4, "Calibrating"); f fades beta in dense cells as
// a is faded. Then
//
//   steady:     K_eff = K(u_und) / (1 + beta f - gamma a)    (gamma a capped at 0.9, as a)
//   transient:  u_und - v = (u_s - v + gamma w G_eff H) / (1 + beta f), K_eff as above
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cosim/models/model.h"

namespace cosim::models {

struct SelfDisturbance {
  static constexpr double kViscous = 2.0 / 3.0 * 0.2527310;  // c_v = 0.168487
  static constexpr double kAdvective = 1.0;                  // c_a
  static constexpr double kMaxSelfCoupling = 0.9;            // bound on a
  static constexpr int kMaxPasses = 50;                      // fixed-point passes for K(u_und) ...
  static constexpr double kTolerance = 1e-13;                // ... until K changes less than this

  // G [s/kg]: cell-average gas velocity per unit force spread over a cubic cell of side Delta.
  // eps: the cell's voidage. The viscous flux leaves through the faces with the face voidage,
  // interpolated between the cell and its neighbours; the neighbours are taken free of solids
  // ((1 + eps) / 2: the lone parcel, the only case where the correction is not faded away).
  // The advective flux is the superficial mass flux eps rho |u_f| Delta^2 (u_f interstitial).
  static double response(double eps, double mu, double rho, double speed, double Delta) {
    const double eps_face = 0.5 * (1.0 + eps);
    return 1.0 /
           (eps_face * mu * Delta / kViscous + eps * rho * speed * Delta * Delta / kAdvective);
  }
  // a = w K G_eff, G_eff = 1 / (1/G + K (1 - w) / w) (unbounded; the caller caps it).
  static double coupling(double K, double G, double w);
  // w: the parcel's share of its cell's solid volume (1 for a lone parcel).
  static double share(double parcel_radius, double voidage, double Delta);
};

// Wraps a drag law: K_eff = K(u_und) / (1 - a) (see above).
class UndisturbedVelocityDrag final : public DragLaw {
 public:
  enum class Estimate { steady, transient };
  // gamma, beta: the calibration of the gas solver's operator (above; 1 and 0: the lattice)
  explicit UndisturbedVelocityDrag(std::unique_ptr<DragLaw> inner,
                                   Estimate estimate = Estimate::steady, double gamma = 1.0,
                                   double beta = 0.0);
  std::string name() const override { return inner_->name(); }
  bool carriesAcrossParcels() const override { return inner_->carriesAcrossParcels(); }
  std::vector<std::string> requiredFields() const override;
  void coefficients(const ParcelBatch& p, const SceneConstants& c, double* K) const override;
  const DragLaw& inner() const { return *inner_; }
  // Transient: the caller keeps a WakeBuildup and fills ParcelBatch::built_up_force.
  bool transient() const { return estimate_ == Estimate::transient; }

 private:
  void steadyCoefficients(const ParcelBatch& p, const SceneConstants& c, const double* G,
                          const double* w, double* K) const;
  void transientCoefficients(const std::string& owner, const ParcelBatch& p,
                             const SceneConstants& c, const double* G, const double* w,
                             double* K) const;

  std::unique_ptr<DragLaw> inner_;
  Estimate estimate_;
  double gamma_;
  double beta_;
};

// Bounds on the calibration (models.drag.self_disturbance_gain / _offset).
struct CalibrationBounds {
  static constexpr double kMinGain = 0.5, kMaxGain = 2.0;
  static constexpr double kMinOffset = -0.3, kMaxOffset = 0.3;
  static constexpr double kMinDenominator = 0.1;  // 1 + beta f - gamma a: K_eff <= 10 K
};

// The cap on x of the transient estimate: K_eff / K in [1 + kMinGain, 1 + kMaxGain].
struct TransientBounds {
  static constexpr double kMinGain = -0.9;
  static constexpr double kMaxGain = 9.0;
};

// Names accepted by models.drag.undisturbed_velocity.
std::vector<std::string> undisturbedVelocityNames();

}  // namespace cosim::models

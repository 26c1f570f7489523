// Interfaces of the coupling models. One law per file in models/src/<kind>/; each is selected by
// name from the scenario and declares the per-particle fields it needs (names from
// cosim/link/fields.h), which the orchestrator uses to decide what packets carry.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cosim/models/parameters.h"
#include "cosim/models/parcels.h"

namespace cosim::models {

class Model {
 public:
  virtual ~Model() = default;
  virtual std::string name() const = 0;
  // Per-particle fields this model reads (e.g. "voidage", "fluid_velocity").
  virtual std::vector<std::string> requiredFields() const = 0;
  // True for a law whose numbers for a parcel may depend on the parcels before it in the batch
  // (work carried from one parcel to the next, as the filtered Beetstra's Newton start): its
  // batch is then never split into parts evaluated at once (evaluateTerms' threads).
  virtual bool carriesAcrossParcels() const { return false; }
};

// Drag: K per parcel [kg/s] so that the force on the parcel is F = K (u_f - v).
// Evaluated for one real particle (diameter 2 r / cg) and multiplied by cg^3.
class DragLaw : public Model {
 public:
  virtual void coefficients(const ParcelBatch& p, const SceneConstants& c, double* K) const = 0;
};

// Other fluid forces, explicit over a coupling interval: adds to force (3n) [N].
class ForceModel : public Model {
 public:
  virtual void addForces(const ParcelBatch& p, const SceneConstants& c, double* force) const = 0;
};

// Mass transfer: per parcel transfer coefficient k [kg/s per unit precursor mass fraction],
// so that dm/dt = k * Y (paper Eq. 7 times cg^3: k = cg^3 K_m rho_f a_p).
class MassTransferLaw : public Model {
 public:
  virtual void transferCoefficients(const ParcelBatch& p, const SceneConstants& c,
                                    double* k) const = 0;
};

// Where coating can happen. contains() for one point; mask() for a batch (1 inside, 0 outside).
class CoatingZone : public Model {
 public:
  virtual bool contains(const double* x) const = 0;
  void mask(const ParcelBatch& p, double* inside) const {
    for (std::size_t i = 0; i < p.n; ++i) inside[i] = contains(p.position + 3 * i) ? 1.0 : 0.0;
  }
  std::vector<std::string> requiredFields() const override { return {"position"}; }
};

}  // namespace cosim::models

// Example model plugin: the drag law of Tenneti, Garg & Subramaniam (2011), Int. J. Multiphase
// Flow 37:1072-1092, fitted to particle-resolved simulations (0.01 <= Re <= 300, phi <= 0.5):
//   F = (1 + 0.15 Re^0.687) / eps^3 + 5.81 phi / eps^3 + 0.48 phi^(1/3) / eps^4
//       + phi^3 Re (0.95 + 0.61 phi^3 / eps^2)
//   per real particle K = 3 pi mu d eps F  (f = eps F; F(1, 0) = 1: Stokes)
// Registered as drag law "tenneti". Build: see CMakeLists.txt next to this file; load it from a
// scenario with   models: { plugins: [path/to/cosim_example_drag.so], drag: { law: tenneti } }
#include <cmath>

#include "cosim/models/drag/dimensionless_drag.h"
#include "cosim/models/registry.h"

namespace {

using namespace cosim::models;

class TennetiDrag final : public DragLaw {
 public:
  explicit TennetiDrag(const Parameters& p) { p.rejectUnknown({}); }
  std::string name() const override { return "tenneti"; }
  std::vector<std::string> requiredFields() const override { return denseDragFields(); }
  void coefficients(const ParcelBatch& p, const SceneConstants& c, double* K) const override {
    evaluateDrag(*this, p, c, K, [](double eps, double Re) {
      const double phi = 1.0 - eps;
      const double eps3 = eps * eps * eps;
      const double phi3 = phi * phi * phi;
      const double F = (1.0 + 0.15 * std::pow(Re, 0.687)) / eps3 + 5.81 * phi / eps3 +
                       0.48 * std::cbrt(phi) / (eps3 * eps) +
                       phi3 * Re * (0.95 + 0.61 * phi3 / (eps * eps));
      return eps * F;
    });
  }
};

}  // namespace

extern "C" __attribute__((visibility("default"))) void cosim_register_models(
    cosim::models::Registry& registry) {
  registry.addDrag("tenneti", [](const cosim::models::Parameters& p) {
    return std::unique_ptr<cosim::models::DragLaw>(new TennetiDrag(p));
  });
}

// Koch & Hill (2001) drag, in the form of Hill, Koch & Ladd (2001, J. Fluid Mech. 448) as fitted
// by Benyahia, Syamlal & O'Brien (2006, Powder Technol. 162:166-174), valid for all phi, Re.
// phi = 1 - eps, Re_h = Re / 2 (Reynolds number on the particle radius), F = F(phi, Re_h):
//   w      = exp(-10 (0.4 - phi) / phi)
//   F0     = (1-w)(1 + 3 sqrt(phi/2) + 135/64 phi ln phi + 17.14 phi)
//            / (1 + 0.681 phi - 8.48 phi^2 + 8.16 phi^3) + w 10 phi / eps^3        (phi < 0.4)
//          = 10 phi / eps^3                                                        (phi >= 0.4)
//   F1     = sqrt(2/phi) / 40 (0.01 < phi <= 0.1);  0.11 + 5.1e-4 exp(11.6 phi) (phi > 0.1)
//   F2     = (1-w)(1 + 3 sqrt(phi/2) + 135/64 phi ln phi + 17.89 phi)
//            / (1 + 0.681 phi - 11.03 phi^2 + 15.41 phi^3) + w 10 phi / eps^3      (phi < 0.4)
//          = 10 phi / eps^3                                                        (phi >= 0.4)
//   F3     = 0.9351 phi + 0.03667 (phi < 0.0953);  0.0673 + 0.212 phi + 0.0232 / eps^5
//   Re_t1  = (F2 - 1) / (3/8 - F3),  Re_t2 = (F3 + sqrt(F3^2 - 4 F1 (F0 - F2))) / (2 F1)
//   F      = 1 + 3/8 Re_h        (phi <= 0.01, Re_h <= Re_t1)
//          = F0 + F1 Re_h^2      (phi >  0.01, Re_h <= Re_t2)
//          = F2 + F3 Re_h        otherwise
// Per particle K = 3 pi mu d eps^2 F (F is normalised with the superficial velocity and includes
// the mean pressure-gradient share, hence eps^2 against Beetstra's eps), i.e. f = eps^2 F.
#pragma once

#include "cosim/models/model.h"

namespace cosim::models {

double kochHillF(double phi, double Re_h);  // F above

class KochHillDrag final : public DragLaw {
 public:
  explicit KochHillDrag(const Parameters& p) { p.rejectUnknown({}); }
  std::string name() const override { return "koch_hill"; }
  std::vector<std::string> requiredFields() const override;
  void coefficients(const ParcelBatch& p, const SceneConstants& c, double* K) const override;
};

}  // namespace cosim::models

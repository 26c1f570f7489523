// D'Agostino-Pearson K^2 omnibus normality test (D'Agostino, Belanger & D'Agostino 1990):
// the sample skewness and kurtosis are each turned into an approximately standard normal
// score (Z_s by D'Agostino's 1970 transform, Z_k by Anscombe & Glynn 1983), K^2 = Z_s^2 + Z_k^2
// is chi-squared with 2 degrees of freedom, p = exp(-K^2/2). Needs n >= 20 (the kurtosis
// transform is poor below); formulas in docs/analysis.md.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace cosim::analysis {

struct NormalityTest {
  bool valid = false;
  std::string problem;  // why not valid
  std::size_t n = 0;
  double skewness = 0;  // g1 (biased)
  double kurtosis = 0;  // b2 = m4/m2^2 (normal: 3)
  double z_skewness = 0;
  double z_kurtosis = 0;
  double k2 = 0;
  double p_value = 0;
};

NormalityTest dagostinoPearson(const std::vector<double>& values);

}  // namespace cosim::analysis

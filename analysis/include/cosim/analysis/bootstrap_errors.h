// Standard errors of a1 and a2 by resampling parcels (bootstrap over particles).
//
// The snapshots of a run follow the same parcels, so the residuals of the Eqs. 9-10 fit are
// correlated in time and the regression standard errors (origin_fit.h) understate how much a1
// and a2 would change for another sample of parcels. Here whole parcel histories are drawn with
// replacement (N of N), the snapshot means and variances are recomputed from the drawn parcels,
// the fit is repeated, and the standard deviation of a1 and a2 over the resamples is the
// standard error. Parcels absent from a snapshot (not yet inserted / already deleted) are NaN
// there and skipped.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace cosim::analysis {

struct ParcelHistories {
  std::vector<double> time;               // snapshot times [s]
  std::vector<std::vector<double>> mass;  // mass[snapshot][parcel] [kg]; NaN = parcel absent
};

struct BootstrapErrors {
  bool ok = false;
  std::string problem;
  std::size_t resamples = 0;
  std::size_t parcels = 0;
  std::size_t snapshots = 0;
  double a1_se = 0, a2_se = 0;
};

BootstrapErrors bootstrapGrowthErrors(const ParcelHistories& histories, double coating_start,
                                      std::size_t resamples = 200, std::uint64_t seed = 1);

}  // namespace cosim::analysis

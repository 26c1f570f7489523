// One branch-free pass over an array: are all its values finite? For the checks that run over
// every parcel at every coupling step (the message, with the first bad value, is looked for only
// when this fails).
#pragma once

#include <cstddef>
#include <vector>

namespace cosim::util {

// x * 0 is 0 for a finite x and NaN for an infinite or NaN one; four partial sums keep the
// additions independent of each other.
inline bool allFinite(const std::vector<double>& v) {
  double a[4] = {0.0, 0.0, 0.0, 0.0};
  std::size_t i = 0;
  for (; i + 4 <= v.size(); i += 4)
    for (std::size_t d = 0; d < 4; ++d) a[d] += v[i + d] * 0.0;
  for (; i < v.size(); ++i) a[0] += v[i] * 0.0;
  return (a[0] + a[1]) + (a[2] + a[3]) == 0.0;
}

}  // namespace cosim::util

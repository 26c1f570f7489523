#include "cosim/liggghts/order_by_id.h"

#include <algorithm>
#include <numeric>

namespace cosim::liggghts {

std::vector<std::size_t> orderById(const std::vector<double>& records, std::size_t per) {
  const std::size_t n = records.size() / per;
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  if (n == 0) return order;
  double lo = records[0], hi = records[0];
  for (std::size_t j = 1; j < n; ++j) {
    lo = std::min(lo, records[j * per]);
    hi = std::max(hi, records[j * per]);
  }
  const double span = hi - lo + 1;
  if (span <= 2.0 * static_cast<double>(n) + 16) {
    constexpr std::size_t kEmpty = static_cast<std::size_t>(-1);
    std::vector<std::size_t> slot(static_cast<std::size_t>(span), kEmpty);
    bool unique = true;
    for (std::size_t j = 0; j < n && unique; ++j) {
      std::size_t& at = slot[static_cast<std::size_t>(records[j * per] - lo)];
      unique = at == kEmpty;
      at = j;
    }
    if (unique) {
      std::size_t k = 0;
      for (std::size_t j : slot)
        if (j != kEmpty) order[k++] = j;
      return order;
    }
  }
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return records[a * per] < records[b * per]; });
  return order;
}

}  // namespace cosim::liggghts

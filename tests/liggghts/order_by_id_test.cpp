// The state's id order: every record once, ids ascending, whatever the ids' spread.
#include "cosim/liggghts/order_by_id.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace cosim::liggghts {
namespace {

// Records of stride 2 (id, payload = the record's own position), in a shuffled order.
std::vector<double> shuffledRecords(std::vector<double> ids, unsigned seed) {
  std::shuffle(ids.begin(), ids.end(), std::mt19937(seed));
  std::vector<double> r;
  for (std::size_t j = 0; j < ids.size(); ++j) {
    r.push_back(ids[j]);
    r.push_back(static_cast<double>(j));
  }
  return r;
}

void expectAscendingAndComplete(const std::vector<double>& r, const std::vector<std::size_t>& o) {
  ASSERT_EQ(o.size(), r.size() / 2);
  std::vector<std::size_t> seen(o);
  std::sort(seen.begin(), seen.end());
  for (std::size_t k = 0; k < seen.size(); ++k) ASSERT_EQ(seen[k], k) << "every record once";
  for (std::size_t k = 1; k < o.size(); ++k) ASSERT_LE(r[2 * o[k - 1]], r[2 * o[k]]);
}

TEST(OrderById, DenseGappedSparseAndRepeatedIds) {
  std::vector<double> dense, gapped, sparse;
  for (int id = 1; id <= 1000; ++id) dense.push_back(id);
  for (int id = 1; id <= 3000; ++id)
    if (id % 3 != 0) gapped.push_back(id);  // a third of the parcels left the domain
  for (int k = 0; k < 500; ++k) sparse.push_back(1.0 + 7919.0 * k);  // ids 16 times their count
  for (const auto& ids : {dense, gapped, sparse}) {
    const auto r = shuffledRecords(ids, 42);
    const auto o = orderById(r, 2);
    expectAscendingAndComplete(r, o);
    for (std::size_t k = 0; k < o.size(); ++k) EXPECT_EQ(r[2 * o[k]], *std::next(ids.begin(), k));
  }
  std::vector<double> repeated = dense;
  repeated[500] = 3;  // id 3 twice, 501 missing: the slot pass gives way to the sort
  const auto r = shuffledRecords(repeated, 7);
  expectAscendingAndComplete(r, orderById(r, 2));
  EXPECT_TRUE(orderById({}, 11).empty());
}

}  // namespace
}  // namespace cosim::liggghts

#include "cosim/analysis/histogram.h"

#include <gtest/gtest.h>

#include <numeric>

using namespace cosim::analysis;

TEST(Histogram, FreedmanDiaconisOnOneToHundred) {
  // 1..100: quartiles (type 7) 25.75 and 75.25, IQR 49.5, width 2*49.5/100^(1/3) = 21.33,
  // range 99 -> ceil(4.64) = 5 equal bins of 19.8 holding 20 values each.
  std::vector<double> v(100);
  std::iota(v.begin(), v.end(), 1.0);
  EXPECT_DOUBLE_EQ(quantileSorted(v, 0.25), 25.75);
  EXPECT_DOUBLE_EQ(quantileSorted(v, 0.75), 75.25);
  const auto h = histogram(v);
  EXPECT_EQ(h.rule, "freedman-diaconis");
  ASSERT_EQ(h.counts.size(), 5u);
  for (auto c : h.counts) EXPECT_EQ(c, 20u);
  EXPECT_DOUBLE_EQ(h.edges.front(), 1.0);
  EXPECT_DOUBLE_EQ(h.edges.back(), 100.0);
  EXPECT_NEAR(h.edges[1], 20.8, 1e-12);
}

TEST(Histogram, SturgesWhenTheIqrIsZeroAndSingleValue) {
  // 16 values, 13 of them zero: IQR 0 -> Sturges ceil(log2 16) + 1 = 5 bins over [0, 4].
  std::vector<double> v(13, 0.0);
  v.insert(v.end(), {1.0, 2.0, 4.0});
  const auto h = histogram(v);
  EXPECT_EQ(h.rule, "sturges");
  ASSERT_EQ(h.counts.size(), 5u);
  // Bins of width 0.8: [0,0.8) thirteen zeros, [0.8,1.6) 1, [1.6,2.4) 2, [2.4,3.2) none,
  // [3.2,4] 4 (the last bin is closed).
  EXPECT_EQ(h.counts, (std::vector<std::size_t>{13, 1, 1, 0, 1}));
  const auto one = histogram({2.0, 2.0});
  EXPECT_EQ(one.rule, "single-value");
  EXPECT_EQ(one.counts, std::vector<std::size_t>{2});
}

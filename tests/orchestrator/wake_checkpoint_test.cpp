// The wake history of models.drag.undisturbed_velocity: self_disturbance_transient in a
// checkpoint (orchestrator.json): written and read back bit for bit, so that a resumed run
// continues every parcel's force history as it was. (The real-solver resume is
// Wake.TransientResumesFromACheckpoint in tests/verification/wake_test.cpp.)
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include "checkpoints.h"

using namespace cosim;
using namespace cosim::orchestrator;
namespace fs = std::filesystem;

namespace {

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(Checkpoint, WakeHistoryIsReadBackBitForBit) {
  const fs::path dir = fs::temp_directory_path() / ("cosim-wake-ckpt-" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  CheckpointStore store(dir);
  CoupledState s;
  s.step = 12;
  s.time = 2.4e-3;
  models::WakeBuildup::State wake;
  // values whose shortest decimal forms need all 17 digits, a denormal, a negative zero
  for (std::int64_t id : {std::int64_t{3}, std::int64_t{-7}, std::int64_t{1234567890123}}) {
    auto& p = wake[id];
    p.anchor = {0.1 + 0.2, -1.0 / 3.0, 4.9406564584124654e-324};
    for (std::size_t k = 0; k < p.y.size(); ++k)
      p.y[k] = std::pow(0.7, static_cast<double>(k) + id % 5) * 1.2345678901234567e-11;
    p.K = 3.3929200658769765e-09;
    p.v = {-0.0, std::nextafter(1e-3, 1.0), -2.0 / 7.0};
    p.dt = 2.0e-4;
  }
  s.wake = wake;
  const auto final_dir = store.commit(store.begin(s.time, {}), s, 2);
  const CoupledState back = readCoupledState(final_dir);
  ASSERT_TRUE(back.wake);
  ASSERT_EQ(back.wake->size(), wake.size());
  for (const auto& [id, p] : wake) {
    const auto& q = back.wake->at(id);
    for (int j = 0; j < 3; ++j) {
      EXPECT_TRUE(sameBits(p.anchor[j], q.anchor[j])) << id;
      EXPECT_TRUE(sameBits(p.v[j], q.v[j])) << id;
    }
    for (std::size_t k = 0; k < p.y.size(); ++k) EXPECT_TRUE(sameBits(p.y[k], q.y[k])) << id;
    EXPECT_TRUE(sameBits(p.K, q.K));
    EXPECT_TRUE(sameBits(p.dt, q.dt));
  }
  // a checkpoint of a scene without the option holds none
  CoupledState plain;
  plain.time = 5e-3;
  EXPECT_FALSE(readCoupledState(store.commit(store.begin(plain.time, {}), plain, 2)).wake);
  fs::remove_all(dir);
}

}  // namespace

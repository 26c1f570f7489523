// `cosim report` on a run without coating: the bed over the second half of its record, from a
// run folder made here whose statistics are computed by hand.
#include "cosim/analysis/bed_report.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cosim/analysis/particle_recorder.h"
#include "cosim/analysis/report.h"
#include "cosim/link/fields.h"
#include "cosim/util/errors.h"
#include "report_fixture.h"

using namespace cosim::analysis;
namespace fs = std::filesystem;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// Five parcels at heights z0 + {0, 1, 2, 3, 4} mm, snapshots at t = 0, 1, 2, 3 with z0 = 10, 20,
// 30, 40 mm; parcel i moves at (3, 4, 0) * i mm/s (speed 5 i mm/s). The pressure drop is 100 +
// t Pa at t = 0, 0.5, ..., 3.
fs::path makeBedRun(const std::string& name, bool coating) {
  const fs::path dir = test::scratchFolder("cosim-bed-report", name);
  {
    std::vector<std::string> fields = {cosim::field::position, cosim::field::velocity};
    if (coating) fields.emplace_back(cosim::field::coating_mass);
    ParticleRecorder rec(dir, fields, RunIdentity{"bed-report-test", 1.0});
    for (int s = 0; s < 4; ++s) {
      cosim::link::ParticleData p;
      p.ids = {1, 2, 3, 4, 5};
      std::vector<double> x, u;
      for (int i = 0; i < 5; ++i) {
        x.insert(x.end(), {0.0, 0.0, 0.010 * (s + 1) + 0.001 * i});
        u.insert(u.end(), {0.003 * i, 0.004 * i, 0.0});
      }
      p.field(cosim::field::position) = x;
      p.field(cosim::field::velocity) = u;
      if (coating) p.field(cosim::field::coating_mass) = {1e-12, 2e-12, 3e-12, 4e-12, 5e-12};
      rec.write(static_cast<double>(s), p);
    }
  }
  std::ofstream ts(dir / "timeseries.csv");
  ts << "time,particle_count,wall_seconds,pressure_drop\n";
  for (int r = 0; r <= 6; ++r) ts << 0.5 * r << ",5," << r << "," << 100 + 0.5 * r << "\n";
  return dir;
}

}  // namespace

TEST(BedReport, SecondHalfOfTheRecordByHand) {
  const fs::path run = makeBedRun("bed", false);
  const BedAnalysis a = analyseBed(run, kNaN, kNaN);
  EXPECT_DOUBLE_EQ(a.from, 1.5);
  EXPECT_DOUBLE_EQ(a.to, 3.0);
  // rows at 1.5, 2, 2.5, 3: 101.5 .. 103, mean 102.25, sample sd sqrt(5/12) * 1
  ASSERT_EQ(a.pressure_drop.n, 4u);
  EXPECT_NEAR(a.pressure_drop.mean, 102.25, 1e-12);
  EXPECT_NEAR(a.pressure_drop.sd, std::sqrt((2 * 0.75 * 0.75 + 2 * 0.25 * 0.25) / 3), 1e-12);
  EXPECT_DOUBLE_EQ(a.pressure_drop.min, 101.5);
  EXPECT_DOUBLE_EQ(a.pressure_drop.max, 103.0);
  EXPECT_DOUBLE_EQ(a.particle_count.mean, 5.0);
  // snapshots at 2 and 3: medians 32 and 42 mm; 90th percentiles 33.6 and 43.6 mm
  EXPECT_EQ(a.snapshots, 2u);
  EXPECT_NEAR(a.height_median.mean, 0.037, 1e-12);
  EXPECT_NEAR(a.height_median.min, 0.032, 1e-12);
  EXPECT_NEAR(a.height_p90.mean, 0.0386, 1e-12);
  // speeds 0, 5, 10, 15, 20 mm/s: median 10 mm/s in both
  EXPECT_NEAR(a.speed_median.mean, 0.010, 1e-12);
  EXPECT_NEAR(a.speed_median.sd, 0.0, 1e-15);
}

TEST(BedReport, WindowGivenAndRefusedWhenEmpty) {
  const fs::path run = makeBedRun("window", false);
  const BedAnalysis a = analyseBed(run, 0.0, 1.0);
  EXPECT_EQ(a.pressure_drop.n, 3u);
  EXPECT_NEAR(a.pressure_drop.mean, 100.5, 1e-12);
  EXPECT_EQ(a.snapshots, 2u);
  try {
    (void)analyseBed(run, 2.0, 1.0);
    FAIL() << "an empty window was accepted";
  } catch (const cosim::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--fit-start"), std::string::npos) << e.what();
  }
}

TEST(BedReport, CosimReportWritesItForARunWithoutCoating) {
  const fs::path run = makeBedRun("report", false);
  test::QuietReport report({run});
  ASSERT_EQ(report.run(), 0) << report.log.str();
  const auto j = nlohmann::json::parse(std::ifstream(run / "report" / "report.json"));
  EXPECT_EQ(j.at("kind"), "bed");
  EXPECT_NEAR(j.at("pressure_drop_pa").at("mean").get<double>(), 102.25, 1e-12);
  EXPECT_TRUE(fs::exists(run / "report" / "report.md"));
  EXPECT_NE(report.log.str().find("pressure drop 102.2"), std::string::npos) << report.log.str();
  // again: its own earlier report is replaced
  ASSERT_EQ(report.run(), 0) << report.log.str();
}

TEST(BedReport, AComparisonWithARunWithoutCoatingIsRefusedNamingIt) {
  const fs::path bed = makeBedRun("cmp-bed", false);
  const fs::path coated = makeBedRun("cmp-coated", true);
  test::QuietReport report({coated, bed});
  testing::internal::CaptureStderr();
  EXPECT_EQ(report.run(), 1);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find(bed.string() + " has no coating"), std::string::npos) << err;
}

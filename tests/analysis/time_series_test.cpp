#include "cosim/analysis/time_series.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using namespace cosim::analysis;

TEST(TimeSeries, RowsAreOnDiskRightAfterWriteAndReadBack) {
  const auto path = fs::temp_directory_path() / ("cosim_ts_" + std::to_string(::getpid()) + ".csv");
  TimeSeriesRecorder rec(path, {"precursor_in", "particle_count"});
  rec.write(0.0, {0.0, 10});
  rec.write(1e-4, {1.2345678901234567e-9, 10});
  // Read while the recorder is still open: every row must already be there.
  TimeSeries ts = readTimeSeries(path);
  ASSERT_EQ(ts.rows(), 2u);
  EXPECT_EQ(ts.columns, (std::vector<std::string>{"time", "precursor_in", "particle_count"}));
  EXPECT_EQ(ts.at("precursor_in")[1], 1.2345678901234567e-9);
  EXPECT_EQ(ts.at("time")[1], 1e-4);
  EXPECT_THROW(rec.write(2e-4, {1.0}), std::runtime_error);
  fs::remove(path);
  try {
    ts.at("precursor_out");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("precursor_out"), std::string::npos);
  }
}

TEST(TimeSeries, LastLineCutByACrashIsIgnored) {
  const auto path =
      fs::temp_directory_path() / ("cosim_ts_cut_" + std::to_string(::getpid()) + ".csv");
  {
    std::ofstream f(path);
    f << "time,a,b\n0,1,2\n0.1,3,4\n0.2,5";
  }
  TimeSeries ts = readTimeSeries(path);
  EXPECT_EQ(ts.rows(), 2u);
  {
    std::ofstream f(path);
    f << "time,a,b\n0,1,2\n0.1,x,4\n0.2,5,6\n";
  }
  try {
    readTimeSeries(path);
    FAIL() << "a bad number inside the file must be reported";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(":3:"), std::string::npos) << e.what();
  }
  fs::remove(path);
}

// The progress line's rate and ETA against a synthetic clock: the ETA is that of the recent
// steps, not of the average since the start (a slow first step must not make an 8-minute run
// announce hours).
#include "progress.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "recent_rate.h"

using namespace cosim::orchestrator;

namespace {
// The 8-minute run of the issue, by hand: 10,000 steps of 1e-4 s to t = 1 s; the first step
// takes 20 s (solver set-up), every later one 46 ms, so the run takes 20 + 9999 * 0.046 =
// 479.95 s and, after step k >= 1, 0.046 (10000 - k) s remain.
constexpr double kDt = 1e-4;
constexpr double kFirst = 20.0;
constexpr double kStep = 0.046;
double wallAfter(int k) { return kFirst + kStep * (k - 1); }
}  // namespace

TEST(RecentRate, EtaOfAnEightMinuteRunIsTheRemainingStepsAtTheRecentPace) {
  RecentRate r(30.0);
  EXPECT_TRUE(std::isnan(r.eta(1.0))) << "no rate before two samples";
  r.add(wallAfter(1), kDt);
  EXPECT_TRUE(std::isnan(r.eta(1.0)));
  for (int k = 2; k <= 100; ++k) {
    r.add(wallAfter(k), k * kDt);
    const double expected = kStep * (10000 - k);
    EXPECT_NEAR(r.eta(1.0), expected, 1e-6 * expected) << "after step " << k;
  }
  // The average since the start would have said 24.55 s * 0.99 / 0.01 = 40 min here.
  EXPECT_NEAR(r.eta(1.0), 455.4, 1e-3);
  EXPECT_NEAR(r.rate(), kDt / kStep, 1e-9);
}

TEST(RecentRate, FollowsAChangeOfPaceWithinItsWindow) {
  // 1000 steps at 46 ms, then the steps take 92 ms (e.g. the bed starts bubbling). Once the
  // 30 s window holds only slow steps, the ETA is that of the slow pace exactly; halfway it
  // is between the two.
  RecentRate r(30.0);
  double wall = 0.0;
  int k = 0;
  for (; k < 1000; ++k) r.add(wall += kStep, k * kDt);
  for (int j = 0; j < 200; ++j, ++k) r.add(wall += 2 * kStep, k * kDt);  // 18.4 s of slow steps
  const double fast = kStep * (10000 - (k - 1)), slow = 2 * fast;
  EXPECT_GT(r.eta(1.0), fast * 1.2);
  EXPECT_LT(r.eta(1.0), slow * 0.95);
  for (int j = 0; j < 400; ++j, ++k) r.add(wall += 2 * kStep, k * kDt);  // 36.8 s more
  EXPECT_NEAR(r.eta(1.0), 2 * kStep * (10000 - (k - 1)), 1e-6 * slow);
}

TEST(RecentRate, AStalledRunHasNoEta) {
  RecentRate r(30.0);
  r.add(1.0, 0.5);
  r.add(2.0, 0.5);
  EXPECT_TRUE(std::isnan(r.eta(1.0)));
  RecentRate same_time;
  same_time.add(1.0, 0.1);
  same_time.add(1.0, 0.2);
  EXPECT_TRUE(std::isnan(same_time.rate()));
}

TEST(Progress, LogLineOfAnEightMinuteRunAnnouncesMinutesNotHours) {
  double now = 100.0;  // wall clock at construction; the first step ends kFirst later
  char* buffer = nullptr;
  std::size_t size = 0;
  std::FILE* out = open_memstream(&buffer, &size);
  ASSERT_NE(out, nullptr);
  {
    Progress p(
        0.0, 1.0, false, [&] { return now; }, out);
    for (int k = 1; k <= 10000; ++k) {
      now = 100.0 + wallAfter(k);
      p.update(k * kDt, static_cast<std::uint64_t>(k), 1500);
    }
    p.finish(1.0, 10000);
  }
  std::fclose(out);
  const std::string text(buffer, size);
  std::free(buffer);
  // Not a terminal: a line at the first step, then every 10 % or 30 s.
  std::regex line(
      R"re(t = ([0-9.e-]+) / 1 s .*step (\d+) .* ([0-9.?]+) steps/s  ETA ([^\n]+)\n)re");
  std::vector<std::pair<int, std::string>> etas;
  std::vector<std::string> rates;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), line); it != std::sregex_iterator();
       ++it) {
    etas.emplace_back(std::stoi((*it)[2]), (*it)[4]);
    rates.push_back((*it)[3]);
  }
  ASSERT_GE(etas.size(), 10u) << text;
  EXPECT_EQ(etas[0].first, 1);
  EXPECT_EQ(etas[0].second, "?") << "one step gives no rate yet";
  // Every later line: the remaining steps at 46 ms, to the second.
  for (std::size_t i = 1; i < etas.size(); ++i) {
    const int k = etas[i].first;
    const double expected = kStep * (10000 - k);
    std::smatch m;
    const std::string& eta = etas[i].second;
    double seconds = NAN;
    if (std::regex_match(eta, m, std::regex(R"((\d+) min (\d+) s)")))
      seconds = 60.0 * std::stoi(m[1]) + std::stoi(m[2]);
    else if (std::regex_match(eta, m, std::regex(R"((\d+) s)")))
      seconds = std::stoi(m[1]);
    EXPECT_NEAR(seconds, expected, 1.0) << "line at step " << k << ": ETA " << eta;
    EXPECT_EQ(rates[i], "21.7") << "1 / 0.046 s steps per second";
  }
  EXPECT_NE(text.find("reached t = 1 s in 10000 coupling steps, wall 7 min 59 s"),
            std::string::npos)
      << text;
}

// A run resumed at 20 s of its 40 s: the line says how far the run is (50 %), not how far this
// piece of it is (0 %); the ETA is that of what remains.
TEST(Progress, AResumedRunShowsItsShareOfTheWholeRun) {
  auto firstLine = [](std::optional<double> origin) {
    double now = 0.0;
    char* buffer = nullptr;
    std::size_t size = 0;
    std::FILE* out = open_memstream(&buffer, &size);
    if (out == nullptr) {
      ADD_FAILURE() << "open_memstream failed";
      return std::string();
    }
    {
      Progress p(
          20.0, 40.0, false, [&] { return now; }, out, origin);
      for (int k = 1; k <= 3; ++k) {
        now = 0.5 * k;
        p.update(20.0 + 0.01 * k, static_cast<std::uint64_t>(200000 + k), 8000);
      }
    }
    std::fclose(out);
    const std::string text(buffer, size);
    std::free(buffer);
    return text;
  };
  const std::string whole = firstLine(0.0);
  EXPECT_NE(whole.find("t = 20.01 / 40 s ( 50.0%)  step 200001"), std::string::npos) << whole;
  // without an origin the share is of the piece itself: 0.01 of its 20 s
  const std::string piece = firstLine(std::nullopt);
  EXPECT_NE(piece.find("t = 20.01 / 40 s (  0.1%)  step 200001"), std::string::npos) << piece;
}

// Numbers on the command line: each refusal says what was expected in words, never CLI11's
// largest-double bound, and a negative count is not taken as a huge unsigned one.
#include "cli_checks.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "batch_command.h"

namespace cli = cosim::orchestrator::cli;

namespace {

// The message CLI11 gives for `args` after the subcommand, or "" when they parse.
std::string parseError(const std::vector<std::string>& args) {
  CLI::App app{"cosim"};
  cosim::orchestrator::BatchOptions options;
  cosim::orchestrator::addBatchCommand(app, options);
  std::vector<std::string> argv = {"batch", COSIM_SOURCE_DIR};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<std::string> reversed(argv.rbegin(), argv.rend());  // CLI11 pops from the back
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    return e.what();
  }
  return "";
}

std::string check(const CLI::Validator& v, std::string in) { return v(in); }

}  // namespace

TEST(CommandLineNumbers, SecondsOfAtLeastZero) {
  const auto v = cli::atLeast(0.0, "seconds");
  EXPECT_EQ(check(v, "0"), "");
  EXPECT_EQ(check(v, "2.5"), "");
  EXPECT_EQ(check(v, "1e3"), "");
  EXPECT_EQ(check(v, "-1"), "expected a number of seconds of at least 0, got '-1'");
  for (const char* bad : {"abc", "nan", "inf", "1e400", "", "5s", "0x"})
    EXPECT_NE(check(v, bad), "") << bad;
}

TEST(CommandLineNumbers, AboveABoundWithAnUpperLimit) {
  const auto v = cli::above(0.0, "seconds", 1.0e7);
  EXPECT_EQ(check(v, "3600"), "");
  EXPECT_EQ(check(v, "1e7"), "");
  EXPECT_EQ(check(v, "0"), "expected a number of seconds above 0 and at most 10000000, got '0'");
  EXPECT_NE(check(v, "2e7"), "");
  EXPECT_EQ(check(cli::above(0.0, "metres"), "-0.004"),
            "expected a number of metres above 0, got '-0.004'");
}

TEST(CommandLineNumbers, WholeNumbersRefuseSignsFractionsAndOverflow) {
  const auto v = cli::wholeNumber(0, 1000000000);
  EXPECT_EQ(check(v, "0"), "");
  EXPECT_EQ(check(v, "5"), "");
  EXPECT_EQ(check(v, "-3"), "expected a whole number from 0 to 1000000000, got '-3'");
  for (const char* bad : {"3.5", "+3", "1e3", "2000000000", "99999999999999999999", "", " 3"})
    EXPECT_NE(check(v, bad), "") << bad;
}

TEST(CommandLineNumbers, BatchNamesTheOptionAndWhatItExpected) {
  EXPECT_EQ(parseError({"--from", "0.6", "--until", "3600", "--times", "20,1200"}), "");
  const std::string from = parseError({"--from", "-1"});
  EXPECT_NE(from.find("--from"), std::string::npos) << from;
  EXPECT_NE(from.find("expected a number of seconds of at least 0, got '-1'"), std::string::npos)
      << from;
  EXPECT_EQ(from.find("1797693"), std::string::npos) << from;  // no largest double
  const std::string times = parseError({"--times", "20,abc"});
  EXPECT_NE(times.find("got 'abc'"), std::string::npos) << times;
  const std::string rings = parseError({"--rings", "-2"});
  EXPECT_NE(rings.find("expected a whole number from 1 to 100, got '-2'"), std::string::npos)
      << rings;
  EXPECT_NE(parseError({"--step", "0"}), "");
  EXPECT_NE(parseError({"--until", "0"}), "");
}

// cosim_util: programs run from argument vectors (no shell), the tail of a log, the Rayleigh time.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include "cosim/util/child_process.h"
#include "cosim/util/cpu_binding.h"
#include "cosim/util/errors.h"
#include "cosim/util/format.h"
#include "cosim/util/long_quotes.h"
#include "cosim/util/rayleigh_time.h"
#include "cosim/util/text_file.h"

namespace fs = std::filesystem;
using namespace cosim::util;

namespace {
fs::path scratch(const std::string& tag) {
  const fs::path p = fs::temp_directory_path() / ("cosim-util-" + tag + std::to_string(getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}
std::string slurp(const fs::path& f) {
  std::ifstream in(f);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
}  // namespace

TEST(RunProgram, ArgumentsReachTheProgramVerbatimAndNoShellRunsThem) {
  const fs::path dir = scratch("argv-");
  const std::string hostile = "a b'$(touch X1)'\"$(touch X2)\"`touch X3`;touch X4|touch X5 > X6";
  const int rc = runProgram({"printf", "%s|%s", hostile, "$HOME"}, dir / "out.log", {}, dir);
  EXPECT_EQ(rc, 0);
  EXPECT_EQ(slurp(dir / "out.log"), hostile + "|$HOME");
  for (const char* f : {"X1", "X2", "X3", "X4", "X5", "X6"}) EXPECT_FALSE(fs::exists(dir / f)) << f;
  fs::remove_all(dir);
}

TEST(RunProgram, ExitCodeEnvironmentAndMissingProgram) {
  const fs::path dir = scratch("exit-");
  EXPECT_EQ(runProgram({"sh", "-c", "exit 7"}, "/dev/null"), 7);
  EXPECT_EQ(runProgram({"sh", "-c", "kill -9 $$"}, "/dev/null"), 128 + 9);
  EXPECT_EQ(runProgram({"sh", "-c", "printf %s \"$COSIM_UTIL_TEST\""}, dir / "env.log",
                       {{"COSIM_UTIL_TEST", "x y"}}),
            0);
  EXPECT_EQ(slurp(dir / "env.log"), "x y");
  EXPECT_THROW(runProgram({"/nonexistent/cosim-no-such-program"}, "/dev/null"), std::runtime_error);
  fs::remove_all(dir);
}

TEST(CpuBinding, ListTextAsTasksetWritesIt) {
  EXPECT_EQ(cpuListText({0}), "0");
  EXPECT_EQ(cpuListText({1, 2, 3}), "1-3");
  EXPECT_EQ(cpuListText({0, 2, 3, 5}), "0,2-3,5");
  EXPECT_EQ(cpuListText({}), "");
}

TEST(CpuBinding, AChildAndItsThreadsRunOnTheCpusGiven) {
  const std::vector<int> allowed = allowedCpus();
  ASSERT_FALSE(allowed.empty());
  const fs::path dir = scratch("cpus-");
  // the kernel's own account of the child's mask, read by the child itself
  ChildProcess child({"sh", "-c", "grep Cpus_allowed_list /proc/self/status"}, dir, dir / "out.log",
                     {}, {allowed.back()});
  EXPECT_EQ(child.wait(), 0);
  EXPECT_EQ(slurp(dir / "out.log"), "Cpus_allowed_list:\t" + std::to_string(allowed.back()) + "\n");
  ChildProcess free({"sh", "-c", "grep Cpus_allowed_list /proc/self/status"}, dir, dir / "free.log",
                    {});
  EXPECT_EQ(free.wait(), 0);
  EXPECT_EQ(slurp(dir / "free.log"), "Cpus_allowed_list:\t" + cpuListText(allowed) + "\n");
  fs::remove_all(dir);
}

TEST(DisplayCommand, QuotesWhatAShellWouldReadOtherwise) {
  EXPECT_EQ(displayCommand({"blockMesh"}), "blockMesh");
  EXPECT_EQ(displayCommand({"decomposePar", "-force"}), "decomposePar -force");
  EXPECT_EQ(displayCommand({"ls", "a b", "it's"}), "ls 'a b' 'it'\\''s'");
  EXPECT_EQ(displayCommand({"echo", ""}), "echo ''");
}

TEST(TailOfFile, LastLinesOldestFirst) {
  const fs::path dir = scratch("tail-");
  std::ofstream(dir / "log") << "one\ntwo\nthree\nfour";
  EXPECT_EQ(tailOfFile(dir / "log", 2), "three\nfour\n");
  EXPECT_EQ(tailOfFile(dir / "log", 10), "one\ntwo\nthree\nfour\n");
  EXPECT_EQ(*lastLines(dir / "log", 1), std::vector<std::string>{"four"});
  EXPECT_FALSE(lastLines(dir / "missing", 3));
  EXPECT_EQ(tailOfFile(dir / "missing", 3), "");
  fs::remove_all(dir);
}

TEST(RayleighTime, HandValueAndScaling) {
  // r = 0.75 mm, rho = 1750, E = 5 MPa, nu = 0.3: G = 5e6 / 2.6 = 1.923e6 Pa,
  // t_R = pi 0.75e-3 sqrt(1750 / 1.923e6) / (0.1631 0.3 + 0.8766) = 7.680e-5 s
  EXPECT_NEAR(rayleighTime(0.75e-3, 1750, 5e6, 0.3), 7.680e-5, 0.002e-5);
  const double t = rayleighTime(1e-3, 2500, 1e7, 0.25);
  EXPECT_NEAR(rayleighTime(2e-3, 2500, 1e7, 0.25), 2 * t, 1e-15);    // ~ r
  EXPECT_NEAR(rayleighTime(1e-3, 2500, 4e7, 0.25), 0.5 * t, 1e-15);  // ~ 1/sqrt(E)
}

// A quoted input is shown up to 200 characters, with how long it was; short ones are untouched.
TEST(LongQuotes, AQuotedInputIsCutToAReadableLengthAndSaysHowLongItWas) {
  EXPECT_EQ(cosim::util::cutInput("abc"), "abc");
  const std::string value(10000, 'x');
  EXPECT_EQ(cosim::util::cutInput(value), std::string(200, 'x') + "... (10000 characters in all)");
  const std::string msg =
      "parameters.u: expected a number, got '" + value + "' (see the scene's doc)";
  const std::string cut = cosim::util::cutLongQuotes(msg);
  EXPECT_EQ(cut, "parameters.u: expected a number, got '" + std::string(200, 'x') +
                     "... (10000 characters in all)' (see the scene's doc)");
  // an unquoted run without spaces (a --set echoed as given) likewise; prose is kept whole
  const std::string set = "command line --set u=" + value + ": not a number";
  EXPECT_EQ(cosim::util::cutLongQuotes(set),
            "command line --set " + ("u=" + value).substr(0, 200) +
                "... (10003 characters in all) not a number");  // the colon was part of the run
  const std::string prose = "a message in words, 'a name', the scene's doc: nothing to cut";
  EXPECT_EQ(cosim::util::cutLongQuotes(prose), prose);
}

// The exact form reads back as the same double, for every double (here: hard ones); the others
// are the printf forms people read.
TEST(NumberFormats, ExactReadsBackAndTheOthersAreAsPrintfWritesThem) {
  for (double v : {0.1, 1.0 / 3.0, 0.1 + 0.2, 1e-5, 6.02214076e23, -2.5e-308, 4.9e-324,
                   1.7976931348623157e308, 123456789.0}) {
    EXPECT_EQ(std::strtod(cosim::util::exact(v).c_str(), nullptr), v) << cosim::util::exact(v);
  }
  EXPECT_EQ(cosim::util::exact(0.1), "0.1");
  EXPECT_EQ(cosim::util::exact(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(cosim::util::significant(0.0123456, 3), "0.0123");
  EXPECT_EQ(cosim::util::significant(123456.0, 3), "1.23e+05");
  EXPECT_EQ(cosim::util::fixed(12.3456, 2), "12.35");
  EXPECT_EQ(cosim::util::clockDuration(42.4), "42 s");
  EXPECT_EQ(cosim::util::clockDuration(185.0), "3 min 05 s");
  EXPECT_EQ(cosim::util::clockDuration(7625.0), "2 h 07 min");
  EXPECT_EQ(cosim::util::clockDuration(-1.0), "?");
}

// One exit code per kind of error, the same in every process (cosim/util/errors.h), and back.
TEST(Errors, EachKindHasItsOwnExitCodeAndAProcessesExitCodeGivesItsKindBack) {
  using cosim::ErrorKind;
  const std::vector<std::pair<ErrorKind, int>> table = {{ErrorKind::input, 1},
                                                        {ErrorKind::solver, 2},
                                                        {ErrorKind::peer, 3},
                                                        {ErrorKind::resource, 4}};
  for (const auto& [kind, code] : table) {
    EXPECT_EQ(cosim::exitCodeOf(kind), code) << cosim::nameOf(kind);
    EXPECT_EQ(cosim::kindOfExitCode(code), kind) << code;
  }
  EXPECT_EQ(cosim::kindOfExitCode(128 + 9), ErrorKind::resource);  // SIGKILL: out of memory
  EXPECT_EQ(cosim::kindOfExitCode(128 + 11), ErrorKind::solver);   // SIGSEGV: a crash
  EXPECT_EQ(cosim::kindOfExitCode(7), ErrorKind::solver);
}

TEST(Errors, AnExceptionsKindIsItsOwnOrWhatTheCallerWasDoing) {
  using cosim::ErrorKind;
  EXPECT_EQ(cosim::kindOf(cosim::PeerError("gone"), ErrorKind::input), ErrorKind::peer);
  EXPECT_EQ(cosim::kindOf(cosim::ResourceError("full"), ErrorKind::input), ErrorKind::resource);
  EXPECT_EQ(cosim::kindOf(std::bad_alloc(), ErrorKind::input), ErrorKind::resource);
  EXPECT_EQ(cosim::kindOf(std::runtime_error("?"), ErrorKind::input), ErrorKind::input);
  EXPECT_EQ(cosim::kindOf(std::runtime_error("?"), ErrorKind::solver), ErrorKind::solver);
  // A file that cannot be written: the disk is the machine's, the path the user's
  EXPECT_EQ(cosim::kindOfErrno(ENOSPC), ErrorKind::resource);
  EXPECT_EQ(cosim::kindOfErrno(EDQUOT), ErrorKind::resource);
  EXPECT_EQ(cosim::kindOfErrno(EIO), ErrorKind::resource);
  EXPECT_EQ(cosim::kindOfErrno(EACCES), ErrorKind::input);
  EXPECT_EQ(cosim::kindOfErrno(ENOENT), ErrorKind::input);
}

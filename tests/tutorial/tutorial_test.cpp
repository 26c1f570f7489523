// docs/tutorial.md, run as a reader would type it: every command of the tutorial, in order, in one
// shell session in a fresh work folder, with the real solvers; then the files and the numbers the
// tutorial says its runs give.
//
// What is run (the convention docs/tutorial.md follows; it says so in its last section):
//   - A fenced block opened with ```sh is shell: its lines go verbatim, in order, into one bash
//     script (so `cd`, variables and here-documents work as in a terminal).
//   - A fenced block opened with ```diff is a unified diff with paths relative to the work folder
//     (`--- my-bed/scenario.yaml`): it is applied with `patch -p0`, as the tutorial tells the
//     reader to do (or to make the same edits by hand).
//   - Every other block (```yaml, ```cpp, ```text, ...) is shown, not run.
//   - An HTML comment on the last non-blank line before a block's opening fence (invisible on the
//     rendered page) changes what is run:
//       <!-- tutorial-test: skip -->          the block is not run (git clone, the set-up that
//                                              installs packages and builds, opening ParaView);
//       <!-- tutorial-test: append ARGS -->   ARGS is added to each `cosim run` / `cosim resume`
//                                              line of the block, before its trailing `# comment`
//                                              (a production run made short: a later --set of
//                                              the same key wins).
//   The skipped set-up defines COSIM (the clone) and COSIM_BUILD (its build folder) and puts
//   $COSIM_BUILD/bin first on PATH; the test does the same for the tree it was built from.
//
// The script runs under `set -e -o pipefail`: the first command that fails stops it, and the
// failure is reported with its line in docs/tutorial.md. The tests below then check what the
// tutorial says the runs leave (the run folders' names are the tutorial's: rename one there,
// rename it here). The work folder is removed when everything passed and kept otherwise.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cosim/util/child_process.h"

namespace fs = std::filesystem;

namespace {

const fs::path kTutorial = fs::path(COSIM_SOURCE_DIR) / "docs" / "tutorial.md";
constexpr double kTimeLimitS = 540;  // the whole tutorial takes about 2.5 min here

std::string readText(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string l; std::getline(ss, l);) out.push_back(l);
  return out;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// `args` inserted before a trailing shell comment (a '#' after a blank, outside quotes).
std::string insertBeforeComment(const std::string& line, const std::string& args) {
  char quote = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '\'' || c == '"') {
      quote = c;
    } else if (c == '#' && i > 0 && (line[i - 1] == ' ' || line[i - 1] == '\t')) {
      std::size_t end = i;
      while (end > 0 && (line[end - 1] == ' ' || line[end - 1] == '\t')) --end;
      return line.substr(0, end) + " " + args + line.substr(end);
    }
  }
  return line + " " + args;
}

struct Script {
  std::string text;
  std::vector<int> md_line;  // per script line (1-based index - 1): its line in tutorial.md
  int sh_blocks = 0, diff_blocks = 0, skipped_blocks = 0, appended_lines = 0;
  std::vector<std::string> commands;  // the shell lines run (for the checks of what is covered)
};

Script extract(const std::string& markdown) {
  Script s;
  auto add = [&](const std::string& l, int md) {
    s.text += l + "\n";
    s.md_line.push_back(md);
  };
  add("set -e -o pipefail", 0);
  add("trap 'echo \"@@ FAILED at script line $LINENO (exit $?): $BASH_COMMAND\"' ERR", 0);
  add("set -x", 0);
  const auto md = lines(markdown);
  std::string directive;  // the HTML comment on the last non-blank line before a fence
  for (std::size_t i = 0; i < md.size(); ++i) {
    const std::string t = trim(md[i]);
    if (t.rfind("```", 0) != 0) {
      if (!t.empty()) directive = t;
      continue;
    }
    const std::string info = trim(t.substr(3));
    const int open = static_cast<int>(i) + 1;
    std::vector<std::pair<std::string, int>> body;
    for (++i; i < md.size() && trim(md[i]) != "```"; ++i)
      body.emplace_back(md[i], static_cast<int>(i) + 1);
    static const std::regex kDirective(R"(<!--\s*tutorial-test:\s*(\w+)\s*(.*?)\s*-->)");
    std::smatch m;
    std::string what, args;
    if (std::regex_match(directive, m, kDirective)) {
      what = m[1];
      args = m[2];
    }
    directive.clear();
    if (info != "sh" && info != "diff") continue;
    if (what == "skip") {
      ++s.skipped_blocks;
      continue;
    }
    add(": '@@ docs/tutorial.md line " + std::to_string(open) + "'", open);
    if (info == "diff") {
      ++s.diff_blocks;
      add("patch -p0 --forward --no-backup-if-mismatch <<'COSIM_TUTORIAL_DIFF'", open);
      for (const auto& [l, n] : body) add(l, n);
      add("COSIM_TUTORIAL_DIFF", open);
      continue;
    }
    ++s.sh_blocks;
    for (auto [l, n] : body) {
      const std::string c = trim(l);
      if (what == "append" && (c.rfind("cosim run ", 0) == 0 || c.rfind("cosim resume ", 0) == 0)) {
        l = insertBeforeComment(l, args);
        ++s.appended_lines;
      }
      s.commands.push_back(trim(l));
      add(l, n);
    }
  }
  return s;
}

struct Outcome {
  bool ran = false;
  int exit_code = -1;
  std::string failure;  // where and what, for the messages
  std::string log_tail;
  double seconds = 0;
};

class Tutorial : public ::testing::Test {
 protected:
  static inline Script script;
  static inline Outcome outcome;
  static inline fs::path work;

  static void SetUpTestSuite() {
    script = extract(readText(kTutorial));
    work = fs::temp_directory_path() / ("cosim-tutorial-" + std::to_string(getpid()));
    fs::remove_all(work);
    fs::create_directories(work);
    const fs::path script_file = work / ".tutorial.sh";
    std::ofstream(script_file) << script.text;
    const fs::path bin = fs::path(COSIM_BINARY_DIR);
    const char* path = std::getenv("PATH");
    const std::map<std::string, std::string> env = {
        {"COSIM", COSIM_SOURCE_DIR},
        {"COSIM_BUILD", bin.parent_path().string()},
        {"PATH", bin.string() + ":" + (path ? path : "/usr/bin:/bin")}};
    const fs::path log = work / ".tutorial.log";
    const auto t0 = std::chrono::steady_clock::now();
    cosim::util::ChildProcess child({"bash", script_file.string()}, work, log, env);
    bool timed_out = false;
    while (child.running()) {
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() >
          kTimeLimitS) {
        child.stop(5.0);
        timed_out = true;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    outcome.ran = true;
    outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    outcome.exit_code = child.exitCode();
    const auto log_lines = lines(readText(log));
    for (std::size_t i = log_lines.size() > 60 ? log_lines.size() - 60 : 0; i < log_lines.size();
         ++i)
      outcome.log_tail += log_lines[i] + "\n";
    static const std::regex kFailed(R"(@@ FAILED at script line (\d+) \(exit (\d+)\): (.*))");
    for (const auto& l : log_lines) {
      std::smatch m;
      if (!std::regex_search(l, m, kFailed)) continue;
      const std::size_t at = std::stoul(m[1].str());
      const int md = at >= 1 && at <= script.md_line.size() ? script.md_line[at - 1] : 0;
      outcome.failure = "docs/tutorial.md line " + std::to_string(md) + ": `" + m[3].str() +
                        "` exited with " + m[2].str();
    }
    if (timed_out)
      outcome.failure = "stopped after " + std::to_string(kTimeLimitS) + " s: " + outcome.failure;
    std::cout << "tutorial: ran " << script.sh_blocks << " sh blocks and " << script.diff_blocks
              << " diffs in " << work << " in " << outcome.seconds << " s, exit "
              << outcome.exit_code << "\n";
  }

  static void TearDownTestSuite() {
    if (!::testing::UnitTest::GetInstance()->Failed()) {
      fs::remove_all(work);
    } else {
      std::cout << "tutorial: work folder kept: " << work << "\n";
    }
  }

  static nlohmann::json summary(const std::string& run) {
    const fs::path p = work / "runs" / run / "summary.json";
    if (!fs::exists(p)) return nlohmann::json::object();
    return nlohmann::json::parse(readText(p));
  }

  static double observableError(const std::string& run, const std::string& name) {
    const auto j = summary(run);
    if (!j.contains("extra") || !j["extra"].contains("observables") ||
        !j["extra"]["observables"].contains(name))
      return NAN;
    return j["extra"]["observables"][name].value("relative_error", NAN);
  }
};

TEST_F(Tutorial, EveryCommandSucceeds) {
  ASSERT_TRUE(outcome.ran);
  EXPECT_EQ(outcome.exit_code, 0) << outcome.failure << "\nlast lines of " << work
                                  << "/.tutorial.log:\n"
                                  << outcome.log_tail;
  EXPECT_LT(outcome.seconds, 300) << "the tutorial's commands should stay quick";
}

// The test cannot pass on a page whose blocks it no longer recognizes.
TEST_F(Tutorial, RunsWhatItTeaches) {
  EXPECT_GE(script.sh_blocks, 8);
  EXPECT_GE(script.diff_blocks, 3);
  EXPECT_GE(script.skipped_blocks, 1);  // the set-up
  EXPECT_GE(script.appended_lines, 1);  // the long run made short
  for (const std::string what :
       {"cosim validate ", "cosim run ", "cosim resume ", "cosim report ", "--set ", "g++ "}) {
    bool found = false;
    for (const auto& c : script.commands) found = found || c.find(what) != std::string::npos;
    EXPECT_TRUE(found) << "no command with '" << what << "' is run";
  }
}

TEST_F(Tutorial, AFirstRunLeavesTheFilesItNames) {
  for (const char* f : {"summary.json", "timeseries.csv", "particles.h5", "particles.xmf",
                        "scenario.resolved.yaml", "cosim.log"})
    EXPECT_TRUE(fs::exists(work / "runs/sphere" / f)) << f;
  EXPECT_EQ(summary("sphere").value("status", ""), "completed");
}

// "v_terminal ... relative error below 1e-6": the Stokes sphere against its analytic solution.
TEST_F(Tutorial, TheSettlingSphereReachesStokesVelocity) {
  EXPECT_LT(std::abs(observableError("sphere", "v_terminal")), 1e-6);
}

// The coating bed: zone_passes.csv, the report, and a precursor balance that closes.
TEST_F(Tutorial, TheCoatingRunBalancesItsPrecursorAndHasAReport) {
  EXPECT_TRUE(fs::exists(work / "runs/coating/zone_passes.csv"));
  EXPECT_TRUE(fs::exists(work / "runs/coating/report/report.html"));
  const auto h = summary("coating").value("headline", nlohmann::json::object());
  ASSERT_TRUE(h.contains("precursor_in_kg")) << "no headline in runs/coating/summary.json";
  const double in = h["precursor_in_kg"];
  const double rest = h.value("precursor_held_kg", 0.0) + h.value("precursor_out_kg", 0.0) +
                      h.value("precursor_removed_kg", 0.0);
  EXPECT_GT(in, 0);
  EXPECT_NEAR(rest / in, 1.0, 1e-9);
  EXPECT_NEAR(h.value("coating_on_particles_kg", 0.0) / h.value("coating_credited_kg", 1.0), 1.0,
              1e-9);
}

// The user's bed: every parcel inserted, the bed carried by the gas (pressure drop = weight less
// buoyancy over the area plus the gas column, within the 2 % the tutorial states), checkpoints,
// and the resumed run longer than the first.
TEST_F(Tutorial, TheOwnBedRunsIsCarriedAndResumes) {
  for (const char* run : {"my-bed-try", "my-bed", "my-bed-wen-yu"}) {
    const auto j = summary(run);
    EXPECT_EQ(j.value("status", ""), "completed") << run;
    EXPECT_EQ(j.value("headline", nlohmann::json::object()).value("particle_count", 0.0), 1200.0)
        << run;
  }
  EXPECT_LT(std::abs(observableError("my-bed", "bed_pressure_drop")), 0.02);
  EXPECT_TRUE(fs::exists(work / "my-bed/dem/baffles.stl"));
  // the newest three (checkpoint.keep): 0.2, 0.3 (the first run's end), 0.32 (the resumed run's)
  for (const char* t : {"0.2", "0.3", "0.32"})
    EXPECT_TRUE(fs::exists(work / "runs/my-bed/checkpoints" / t)) << t;
  EXPECT_TRUE(fs::exists(work / "runs/my-bed/particles.xmf"));
  const auto resumed = summary("my-bed");
  EXPECT_GT(resumed.value("end_time_s", 0.0), 0.3);  // resumed past the first run's 0.3 s
}

// "v_terminal 3.0 % slower than Stokes'": the Wen & Yu plugin at Re = 0.1 in clear liquid.
TEST_F(Tutorial, ThePluginLawGivesTheSlowerSphereItPredicts) {
  EXPECT_TRUE(fs::exists(work / "wen_yu.so"));
  const double e = observableError("sphere-wen-yu", "v_terminal");
  EXPECT_GT(e, 0.025) << "relative error " << e;
  EXPECT_LT(e, 0.035) << "relative error " << e;
  EXPECT_NE(readText(work / "runs/my-bed-wen-yu/scenario.resolved.yaml").find("wen_yu"),
            std::string::npos);
}

}  // namespace

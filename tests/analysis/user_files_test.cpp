// A user's files: a measured CSV as a spreadsheet or an instrument's software saves it (what is
// read, what is refused and how the refusal reads: user_csv.h, through the two readers of
// measured data), and where a command writes what a user's -o names (a file or folder the command
// did not write is never replaced or emptied: files.h claimOutputFiles / claimOutputFolder, and
// the commands that call them).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>

#include "cosim/analysis/files.h"
#include "cosim/analysis/ft4_calibration.h"
#include "cosim/analysis/piv_command.h"
#include "cosim/analysis/piv_compare.h"
#include "cosim/analysis/user_csv.h"

namespace fs = std::filesystem;
using namespace cosim::analysis;

namespace {

class UserFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("cosim-user-files-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path file(const std::string& name, const std::string& text) {
    fs::create_directories((dir_ / name).parent_path());
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }
  static std::string text(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  fs::path dir_;
};

template <class Call>
std::string refusal(Call call) {
  try {
    call();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  ADD_FAILURE() << "nothing was refused";
  return "";
}

}  // namespace

TEST(UserCsvCells, CommasInsideQuotesAreTextAndDoubledQuotesAreOne) {
  const auto c = userCsvCells(" a ,\"b,c\", \"d\"\"e\" ,\r", "f:1");
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c[0], "a");
  EXPECT_EQ(c[1], "b,c");
  EXPECT_EQ(c[2], "d\"e");
  EXPECT_EQ(c[3], "");
  EXPECT_EQ(userCsvCells("", "f:1").size(), 1u);
  const auto open = refusal([] { (void)userCsvCells("1,\"2", "f.csv:7"); });
  EXPECT_NE(open.find("f.csv:7: a double quote is left open"), std::string::npos) << open;
  const auto after = refusal([] { (void)userCsvCells("\"1\"x,2", "f.csv:3"); });
  EXPECT_NE(after.find("f.csv:3: text 'x' after a quoted cell"), std::string::npos) << after;
}

// What a spreadsheet adds is read as the plain file would be: the same numbers.
TEST_F(UserFiles, ASpreadsheetsByteOrderMarkQuotesLineEndsAndCommentsAreRead) {
  const auto totals = readMeasuredEnergy(file(
      "totals.csv", "\xef\xbb\xbf\"energy_mJ\"\r\n# FT4, batch 3\r\n\r\n\"80.5\"\r\n 79.5 \r\n"));
  ASSERT_EQ(totals.replicates_J.size(), 2u);
  EXPECT_DOUBLE_EQ(totals.replicates_J[0], 0.0805);
  EXPECT_DOUBLE_EQ(totals.replicates_J[1], 0.0795);
  const auto profile = readProfileCsv(file(
      "piv.csv", "\xef\xbb\xbfheight_m,\"x_m\",vz_m_s\r\n0.13,-0.01,\"0.25\"\r\n0.13,0.01,\r\n"));
  ASSERT_EQ(profile.size(), 2u);
  EXPECT_DOUBLE_EQ(profile[0].height, 0.13);
  EXPECT_DOUBLE_EQ(profile[0].x, -0.01);
  EXPECT_DOUBLE_EQ(profile[0].vz, 0.25);
  EXPECT_TRUE(std::isnan(profile[1].vz));  // an empty cell: no data at that point
}

// A spreadsheet in a locale with a decimal comma separates cells by ';' (or tabs) and writes
// 80,5: refused with the line and the cause, never read as other numbers.
TEST_F(UserFiles, DecimalCommaExportsAreRefusedWithTheirCause) {
  const auto semicolon =
      refusal([&] { (void)readMeasuredEnergy(file("semi.csv", "height_mm;energy_mJ\n50;0\n")); });
  EXPECT_NE(semicolon.find("semi.csv:1: the header's cells are separated by ';'"),
            std::string::npos)
      << semicolon;
  EXPECT_NE(semicolon.find("'.' in numbers"), std::string::npos) << semicolon;
  const auto tabs = refusal(
      [&] { (void)readProfileCsv(file("tabs.csv", "height_m\tx_m\tvz_m_s\n0.13\t0\t1\n")); });
  EXPECT_NE(tabs.find("tabs.csv:1: the header's cells are separated by tabs"), std::string::npos)
      << tabs;
  // 80,5 mJ is two cells under one header: the count and the likely cause
  const auto comma =
      refusal([&] { (void)readMeasuredEnergy(file("comma.csv", "energy_mJ\n80,5\n")); });
  EXPECT_NE(comma.find("comma.csv:2: 2 cells, the header has 1 (numbers with a decimal comma?"),
            std::string::npos)
      << comma;
  // before, a PIV row "0,13,0,-0,2" read as height 0, x 13, vz 0 from its first three cells
  const auto piv = refusal(
      [&] { (void)readProfileCsv(file("pivcomma.csv", "height_m,x_m,vz_m_s\n0,13,0,-0,2\n")); });
  EXPECT_NE(piv.find("pivcomma.csv:2: 5 cells, the header has 3"), std::string::npos) << piv;
  // fewer cells than the header: named, without the decimal-comma guess
  const auto fewer =
      refusal([&] { (void)readProfileCsv(file("fewer.csv", "height_m,x_m,vz_m_s\n0.13,0\n")); });
  EXPECT_NE(fewer.find("fewer.csv:2: 2 cells, the header has 3"), std::string::npos) << fewer;
  EXPECT_EQ(fewer.find("decimal comma"), std::string::npos) << fewer;
}

TEST_F(UserFiles, AFileOfOnlyCommentsIsEmpty) {
  const auto empty =
      refusal([&] { (void)readMeasuredEnergy(file("c.csv", "# exported 2026-12-04\n\n")); });
  EXPECT_NE(empty.find("c.csv: empty; expected a measured FT4 energy CSV"), std::string::npos)
      << empty;
  const auto piv = refusal([&] { (void)readProfileCsv(file("e.csv", "")); });
  EXPECT_NE(piv.find("e.csv: empty; expected a profile CSV"), std::string::npos) << piv;
}

TEST_F(UserFiles, OutputFilesOnlyWhenAbsentOrTheCommandsOwn) {
  const auto csv = dir_ / "profile.csv", png = dir_ / "profile.png";
  EXPECT_NO_THROW(claimOutputFiles({csv, png}, "height_m,force_N", "-o"));  // none exists
  file("profile.csv", "height_m,force_N,torque_Nm\n0.05,1,2\n");
  file("profile.png", "\x89PNG");
  EXPECT_NO_THROW(claimOutputFiles({csv, png}, "height_m,force_N", "-o"));  // an earlier one's
  // someone's notes under the name: refused, named, untouched
  file("profile.csv", "my notes\n");
  const auto notes = refusal([&] { claimOutputFiles({csv, png}, "height_m,force_N", "-o"); });
  EXPECT_NE(notes.find("-o: " + csv.string() +
                       " already exists and is not an earlier output of this command"),
            std::string::npos)
      << notes;
  EXPECT_EQ(text(csv), "my notes\n");
  // the first file absent, but a picture of the user's where the plot would go
  fs::remove(csv);
  const auto picture = refusal([&] { claimOutputFiles({csv, png}, "height_m,force_N", "-o"); });
  EXPECT_NE(picture.find(png.string() + " already exists"), std::string::npos) << picture;
  // a dangling symbolic link is a file there too
  fs::remove(png);
  fs::create_symlink(dir_ / "nowhere", png);
  EXPECT_THROW(claimOutputFiles({csv, png}, "height_m,force_N", "-o"), std::runtime_error);
}

TEST_F(UserFiles, OutputFolderOnlyWhenNewEmptyOrTheCommandsOwn) {
  EXPECT_NO_THROW(claimOutputFolder(dir_ / "new", "report.json", "\"cosim-report\"", "-o"));
  fs::create_directories(dir_ / "empty");
  EXPECT_NO_THROW(claimOutputFolder(dir_ / "empty", "report.json", "\"cosim-report\"", "-o"));
  file("old/report.json", "{\n \"format\": \"cosim-report\",\n \"version\": 1\n}\n");
  EXPECT_NO_THROW(claimOutputFolder(dir_ / "old", "report.json", "\"cosim-report\"", "-o"));
  file("pictures/holiday.png", "\x89PNG");
  const auto why = refusal(
      [&] { claimOutputFolder(dir_ / "pictures", "report.json", "\"cosim-report\"", "-o"); });
  EXPECT_NE(why.find("holds other files and no report.json"), std::string::npos) << why;
  file("pictures/report.json", "{\"format\": \"someone else's\"}\n");
  EXPECT_THROW(claimOutputFolder(dir_ / "pictures", "report.json", "\"cosim-report\"", "-o"),
               std::runtime_error);
  const auto plain = file("plain", "x");
  EXPECT_THROW(claimOutputFolder(plain, "report.json", "\"cosim-report\"", "-o"),
               std::runtime_error);
}

// cosim piv-compare -o onto a file of the user's: refused before anything is written; onto its
// own earlier comparison: replaced. A name ending .png would put the CSV and its plot in one file.
TEST_F(UserFiles, PivCompareOutputNeverWritesOverAFileItDidNotWrite) {
  file("sim.csv",
       "height_m,x_m,vz_m_s,samples,vz_stderr_m_s\n0.13,-0.01,1,5,0.1\n0.13,0.01,2,5,0.1\n");
  file("measured.csv", "height_m,x_m,vz_m_s\n0.13,0,1\n");
  PivCompareCommandOptions c;
  c.simulated = dir_ / "sim.csv";
  c.measured = dir_ / "measured.csv";
  c.plots = false;
  c.output = file("thesis.csv", "chapter 3\n");
  std::ostringstream out;
  const auto why = refusal([&] { runPivCompareCommand(c, out); });
  EXPECT_NE(why.find("cosim piv-compare -o: " + c.output.string() + " already exists"),
            std::string::npos)
      << why;
  EXPECT_EQ(text(c.output), "chapter 3\n");
  c.output = dir_ / "cmp.csv";
  ASSERT_EQ(runPivCompareCommand(c, out), 0);
  ASSERT_EQ(runPivCompareCommand(c, out), 0);  // its own: replaced
  EXPECT_EQ(text(c.output).rfind("height_m,region,points", 0), 0u);
  c.output = dir_ / "cmp.png";
  EXPECT_THROW(runPivCompareCommand(c, out), std::runtime_error);
  EXPECT_FALSE(fs::exists(c.output));
}

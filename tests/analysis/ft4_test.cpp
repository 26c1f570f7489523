// The FT4 analyses on synthetic data of known answer: the flow energy of Eq. 11 against hand
// calculations, the blade file of a resumed run, the measured CSV forms, and the calibration's
// line fit, inversion and uncertainty against closed-form least squares; end to end through
// run folders made here (no solvers).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <tuple>

#include "cosim/analysis/ft4_calibration.h"
#include "cosim/analysis/ft4_energy.h"
#include "cosim/analysis/report.h"

using namespace cosim::analysis;
namespace fs = std::filesystem;

namespace {

fs::path tempDir(const std::string& name) {
  const auto d = fs::temp_directory_path() / ("cosim-ft4-" + name + "-" + std::to_string(getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void write(const fs::path& f, const std::string& text) {
  fs::create_directories(f.parent_path());
  std::ofstream(f) << text;
}

// The message of the Error that call() throws ("" and a test failure when it throws none).
template <class Error, class Call>
std::string thrown(Call call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "nothing was thrown";
  return "";
}

// A run folder of the FT4 scene as far as the analyses read it: the resolved parameters, a
// completed summary and the blade rows F = force, M = torque while the blade falls from 0.04 m
// to 0.01 m in steps of 1 mm (after three rows at rest at 0.04 m).
fs::path syntheticRun(const fs::path& dir, double mu, double force, double torque) {
  write(dir / "scenario.resolved.yaml",
        "# x as run\nname: ft4\nparameters:\n  mu_fric: " + std::to_string(mu) +
            "\n  blade_radius: 0.024\n  helix_deg: 5\n");
  write(dir / "summary.json", "{\"status\": \"completed\"}\n");
  std::string csv = "time_s,height_m,force_N,torque_Nm\n";
  for (int i = 1; i <= 3; ++i) csv += std::to_string(0.01 * i) + ",0.04,0,-0\n";
  for (int k = 1; k <= 30; ++k)
    csv += std::to_string(0.03 + 0.1 * k) + "," + std::to_string(0.04 - 0.001 * k) + "," +
           std::to_string(force) + "," + std::to_string(torque) + "\n";
  write(dir / "particles" / "ft4_blade.csv", csv);
  return dir;
}

const double kLever = 0.024 * std::tan(5 * std::numbers::pi / 180);  // R tan(alpha)

}  // namespace

TEST(Ft4Energy, ConstantForceAndTorqueGiveTheirWorkExactly) {
  // F = 2 N, M = 0.01 N m over 30 mm: W = (M / (R tan a) + F) x 0.03 m
  std::vector<BladeRow> rows{{0.0, 0.04, 0, 0}, {0.1, 0.04, 0, 0}};
  for (int k = 0; k <= 30; ++k) rows.push_back({0.2 + 0.1 * k, 0.04 - 0.001 * k, 2.0, 0.01});
  const auto p = flowEnergy(rows, 0.024, 5);
  // the first step into the powder is a trapezoid from 0 to the full gradient over 0 mm: the
  // rows at 0.04 m with F = 0 and F = 2 share the height, so they add nothing
  const double g = 0.01 / kLever + 2.0;
  EXPECT_NEAR(p.total_J(), g * 0.03, 1e-12 * g);
  EXPECT_NEAR(p.torque_J(), 0.01 / kLever * 0.03, 1e-12 * g);  // and 2 N x 0.03 m from F
  EXPECT_NEAR(p.points.back().gradient_J_per_m, g, 1e-12 * g);
  EXPECT_NEAR(p.between(0.015, 0.035), g * 0.02, 1e-12 * g);
  EXPECT_DOUBLE_EQ(p.highest_m(), 0.04);
  EXPECT_NEAR(p.lowest_m(), 0.01, 1e-15);
  EXPECT_THROW((void)p.between(0.005, 0.035), std::invalid_argument);
}

TEST(Ft4Energy, LinearGradientIsIntegratedExactlyByTheTrapezoids) {
  // F rising linearly with depth d = 0.04 - H: F = 100 d, M = 0 -> W = 50 d^2
  std::vector<BladeRow> rows;
  for (int k = 0; k <= 40; ++k) {
    const double d = 0.00075 * k;
    rows.push_back({0.1 * k, 0.04 - d, 100 * d, 0.0});
  }
  const auto p = flowEnergy(rows, 0.024, 5);
  EXPECT_NEAR(p.total_J(), 50 * 0.03 * 0.03, 1e-13);
}

TEST(Ft4Energy, RefusesARisingBladeAndBadParameters) {
  std::vector<BladeRow> rows{{0.1, 0.02, 1, 0}, {0.2, 0.021, 1, 0}};
  EXPECT_THROW((void)flowEnergy(rows, 0.024, 5), std::invalid_argument);
  EXPECT_THROW((void)flowEnergy({}, 0.0, 5), std::invalid_argument);
  EXPECT_THROW((void)flowEnergy({}, 0.024, 90), std::invalid_argument);
}

TEST(Ft4Energy, ResumedRunRowsReplaceTheStoppedRunsFromTheCheckpoint) {
  const auto d = tempDir("resume");
  // the stopped run wrote up to t = 0.4; the resumed one restarts at its checkpoint t = 0.2
  write(d / "ft4_blade.csv",
        "time_s,height_m,force_N,torque_Nm\n0.1,0.04,0,0\n0.2,0.039,1,0\n0.3,0.038,9,0\n"
        "0.4,0.037,9,0\ntime_s,height_m,force_N,torque_Nm\n0.3,0.038,2,0\n0.4,0.037,3,0\n");
  const auto rows = readBladeRows(d / "ft4_blade.csv");
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_DOUBLE_EQ(rows[2].force_N, 2);
  EXPECT_DOUBLE_EQ(rows[3].force_N, 3);
  write(d / "bad.csv", "time_s,height_m,force_N,torque_Nm\n0.1,0.04,x,0\n");
  const auto bad = thrown<std::runtime_error>([&] { (void)readBladeRows(d / "bad.csv"); });
  EXPECT_NE(bad.find("bad.csv:2: column force_N"), std::string::npos) << bad;
  fs::remove_all(d);
}

// The scene's file since the `averaged` column: the interval in which a resumed run started has
// no mean (LIGGGHTS' ave/time writes 0 for it) and is left out; the profile joins its
// neighbours by the trapezoid rule. Files with four columns still read; there a resume's zero
// row makes the blade "rise", and the refusal says which line to delete.
TEST(Ft4Energy, ARowWithoutAMeanIsLeftOutAndTheOldFilesZeroRowIsNamed) {
  const auto d = tempDir("cut");
  // stopped after 0.3 (rows 0.1 .. 0.3 kept up to the checkpoint at 0.25: 0.3 replaced),
  // resumed at 0.25: the row at 0.3 has no mean
  write(d / "ft4_blade.csv",
        "time_s,height_m,force_N,torque_Nm,averaged\n0.1,0.040,1,0.001,1\n0.2,0.039,2,0.002,1\n"
        "0.3,0.038,3,0.003,1\ntime_s,height_m,force_N,torque_Nm,averaged\n0.3,0,0,0,0\n"
        "0.4,0.036,5,0.005,1\n");
  std::vector<double> cut;
  const auto rows = readBladeRows(d / "ft4_blade.csv", &cut);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_DOUBLE_EQ(rows[2].time_s, 0.4);
  ASSERT_EQ(cut.size(), 1u);
  EXPECT_DOUBLE_EQ(cut[0], 0.3);
  // R 24 mm, helix 5 deg: lever R tan(5 deg) = 2.0997e-3 m; gradients M/lever + F =
  // 1.476252, 2.952504, 7.381261 N (hand-computed); trapezoids over 1 mm and 3 mm
  const auto p = flowEnergy(rows, 0.024, 5);
  const double lever = 0.024 * std::tan(5 * std::numbers::pi / 180);
  const double g1 = 0.001 / lever + 1, g2 = 0.002 / lever + 2, g4 = 0.005 / lever + 5;
  EXPECT_NEAR(p.total_J(), 0.5 * (g1 + g2) * 0.001 + 0.5 * (g2 + g4) * 0.003, 1e-15);
  EXPECT_NEAR(p.total_J(),
              0.5 * (1.476252 + 2.952504) * 0.001 + 0.5 * (2.952504 + 7.381261) * 0.003, 1e-8);
  // a cut window at the end of the file: kept out, nothing after it
  write(d / "end.csv",
        "time_s,height_m,force_N,torque_Nm,averaged\n0.1,0.040,1,0,1\n0.2,0,0,0,0\n");
  cut.clear();
  EXPECT_EQ(readBladeRows(d / "end.csv", &cut).size(), 1u);
  EXPECT_EQ(cut.size(), 1u);
  // a later resume from before the cut row replaces it (newest rows win): not cut any more
  write(d / "again.csv",
        "time_s,height_m,force_N,torque_Nm,averaged\n0.1,0.040,1,0,1\n0.2,0,0,0,0\n"
        "time_s,height_m,force_N,torque_Nm,averaged\n0.2,0.039,1,0,1\n");
  cut.clear();
  EXPECT_EQ(readBladeRows(d / "again.csv", &cut).size(), 2u);
  EXPECT_TRUE(cut.empty());
  // five columns promised, four given
  write(d / "short.csv", "time_s,height_m,force_N,torque_Nm,averaged\n0.1,0.04,1,0\n");
  const auto short_row = thrown<std::runtime_error>([&] { (void)readBladeRows(d / "short.csv"); });
  EXPECT_NE(short_row.find("short.csv:2: expected 5 columns"), std::string::npos) << short_row;
  // the four-column file of a run resumed before the fix
  const std::vector<BladeRow> old{{0.78, 0.0077, 1, 0.001}, {0.79, 0, 0, 0}, {0.8, 0.0076, 1, 0}};
  const auto rises = thrown<std::invalid_argument>([&] { (void)flowEnergy(old, 0.024, 5); });
  EXPECT_NE(rises.find("the row at t = 0.79 s has height, force and torque 0"), std::string::npos)
      << rises;
  fs::remove_all(d);
}

TEST(Ft4Calibration, LineFitInversionAndUncertaintyAgainstClosedForm) {
  // mu 0.3, 0.5, 0.7 with W 1.0, 2.1, 3.0 J: by hand, b = Sxy/Sxx = 0.4/0.08 = 5,
  // a = 2.0333.. - 2.5, s^2 = SSE/(n-2) = 0.0066667; measured 2.5 J:
  // mu = (2.5 - a)/b = 0.593333.., sigma_study = s sqrt(1/3 + (mu - 0.5)^2/0.08)/5
  std::vector<CalibrationPoint> pts{{"a", 0.3, 1.0}, {"b", 0.5, 2.1}, {"c", 0.7, 3.0}};
  const auto c = calibrate(pts, 2.5, 0.05);
  EXPECT_NEAR(c.slope_J, 5.0, 1e-12);
  EXPECT_NEAR(c.intercept_J, 6.1 / 3 - 2.5, 1e-12);
  const double s2 = (1.0 / 900 + 4.0 / 900 + 1.0 / 900) / 1;  // residuals -1/30, 2/30, -1/30
  EXPECT_NEAR(c.residual_sd_J, std::sqrt(s2), 1e-12);
  const double mu = (2.5 - (6.1 / 3 - 2.5)) / 5;
  EXPECT_NEAR(c.parameter, mu, 1e-12);
  const double study = std::sqrt(s2 * (1.0 / 3 + (mu - 0.5) * (mu - 0.5) / 0.08)) / 5;
  EXPECT_NEAR(c.sigma_study, study, 1e-12);
  EXPECT_NEAR(c.sigma_measurement, 0.05 / 5, 1e-12);
  EXPECT_NEAR(c.sigma, std::hypot(study, 0.01), 1e-12);
  EXPECT_FALSE(c.extrapolated);
  EXPECT_TRUE(calibrate(pts, 3.5, 0).extrapolated);
}

TEST(Ft4Calibration, ExactLineGivesBackTheKnownValueWithTheMeasurementsUncertaintyOnly) {
  std::vector<CalibrationPoint> pts;
  for (double mu : {0.2, 0.35, 0.5, 0.65, 0.8}) pts.push_back({"", mu, 0.004 + 0.012 * mu});
  const auto c = calibrate(pts, 0.004 + 0.012 * 0.52, 0.0003);
  EXPECT_NEAR(c.parameter, 0.52, 1e-12);
  EXPECT_NEAR(c.sigma_study, 0.0, 1e-9);
  EXPECT_NEAR(c.sigma, 0.0003 / 0.012, 1e-9);
}

TEST(Ft4Calibration, RefusesTooFewRunsAndAFlatResponse) {
  EXPECT_THROW((void)calibrate({{"", 0.3, 1}, {"", 0.5, 2}}, 1.5, 0), std::invalid_argument);
  EXPECT_THROW((void)calibrate({{"", 0.5, 1}, {"", 0.5, 2}, {"", 0.5, 3}}, 1.5, 0),
               std::invalid_argument);
  // noise only: no slope
  EXPECT_THROW(
      (void)calibrate({{"", 0.3, 1.0}, {"", 0.5, 1.2}, {"", 0.7, 0.9}, {"", 0.9, 1.1}}, 1.0, 0),
      std::invalid_argument);
}

TEST(Ft4Calibration, MeasuredTotalsAndProfilesInEitherUnit) {
  const auto d = tempDir("measured");
  write(d / "totals.csv", "energy_mJ\n10\n12\n14\n");
  const auto t = readMeasuredEnergy(d / "totals.csv");
  EXPECT_NEAR(t.mean_J(), 0.012, 1e-15);
  EXPECT_NEAR(t.standard_error_J(), 0.002 / std::sqrt(3.0), 1e-15);  // std 2 mJ over sqrt(3)
  EXPECT_FALSE(t.height_low_m);
  // a profile from 40 mm down to 10 mm, two replicates, cumulative from the top
  write(d / "profile.csv", "height_mm,energy_mJ_1,energy_mJ_2\n40,0,0\n30,2,3\n20,5,6\n10,9,11\n");
  const auto p = readMeasuredEnergy(d / "profile.csv");
  ASSERT_EQ(p.replicates_J.size(), 2u);
  EXPECT_NEAR(p.replicates_J[0], 0.009, 1e-15);
  EXPECT_NEAR(p.replicates_J[1], 0.011, 1e-15);
  EXPECT_NEAR(*p.height_low_m, 0.010, 1e-15);
  EXPECT_NEAR(*p.height_high_m, 0.040, 1e-15);
  write(d / "bad.csv", "height_mm,work\n1,2\n");
  const auto unknown = thrown<std::runtime_error>([&] { (void)readMeasuredEnergy(d / "bad.csv"); });
  EXPECT_NE(unknown.find("unknown column 'work'"), std::string::npos) << unknown;
  fs::remove_all(d);
}

TEST(Ft4Calibration, CarelessMeasuredFilesAreRefusedWithTheirCause) {
  const auto d = tempDir("careless");
  auto refusal = [&](const std::string& name, const std::string& text) {
    write(d / name, text);
    return thrown<std::runtime_error>([&] { (void)readMeasuredEnergy(d / name); });
  };
  // A negative total (a sign convention of the export) and a cumulative energy that falls.
  const auto negative = refusal("negative.csv", "energy_mJ\n10\n-12\n");
  EXPECT_NE(negative.find("replicate 2"), std::string::npos) << negative;
  EXPECT_NE(negative.find(">= 0"), std::string::npos) << negative;
  const auto falling = refusal("falling.csv", "height_mm,energy_mJ\n40,9\n10,0\n");
  EXPECT_NE(falling.find("grows as the blade descends"), std::string::npos) << falling;
  // A binary file given by mistake: its bytes are escaped and cut, not printed raw.
  std::string binary = "\x01\x9b[2J";
  binary += std::string(100, '\xff');
  const auto garbled = refusal("binary.csv", binary + "\n1\n");
  EXPECT_NE(garbled.find("'\\x01\\x9b[2J"), std::string::npos) << garbled;
  EXPECT_NE(garbled.find("'..."), std::string::npos) << garbled;
  EXPECT_EQ(garbled.find('\x9b'), std::string::npos);
  // A folder or a missing file is named as such.
  const auto folder = thrown<std::runtime_error>([&] { (void)readMeasuredEnergy(d); });
  EXPECT_NE(folder.find("is a folder"), std::string::npos) << folder;
  const auto missing =
      thrown<std::runtime_error>([&] { (void)readMeasuredEnergy(d / "none.csv"); });
  EXPECT_NE(missing.find("no such file"), std::string::npos) << missing;
  fs::remove_all(d);
}

TEST(Ft4Calibration, AFarExtrapolationIsPrintedInSignificantDigitsAndFlagged) {
  // runs at mu 0.3 and 0.6 with W = 0.1 J x mu (and a third on the line): a measured 1e300 J lies
  // at mu = 1e301, which four decimals would print as three hundred digits
  const std::vector<CalibrationPoint> points = {
      {"a", 0.3, 0.030}, {"b", 0.45, 0.0451}, {"c", 0.6, 0.060}};
  const auto c = calibrate(points, 1e300, 0);
  EXPECT_TRUE(c.extrapolated);
  const auto text = calibrationText(c, "mu_fric");
  const auto line = text.substr(text.find("mu_fric = "));
  EXPECT_LT(line.size(), 200u) << line;
  EXPECT_NE(line.find("e+301"), std::string::npos) << line;
  EXPECT_NE(line.find("extrapolated"), std::string::npos) << line;
}

TEST(Ft4Calibration, AnAnswerOfTheOtherSignThanEveryStudiedValueIsFlagged) {
  // W = 0.1 J x mu exactly: 0.01 J reads mu = 0.1 (extrapolated, same sign), -0.01 J (a sign
  // convention) would read -0.1, and on W = 0.02 J + 0.1 J x mu a measured 0.01 J reads -0.1
  const std::vector<CalibrationPoint> line = {
      {"a", 0.3, 0.03}, {"b", 0.45, 0.045}, {"c", 0.6, 0.06}};
  const auto low = calibrate(line, 0.01, 0);
  EXPECT_NEAR(low.parameter, 0.1, 1e-12);
  EXPECT_TRUE(low.extrapolated);
  EXPECT_FALSE(low.changesSign());
  const std::vector<CalibrationPoint> offset = {
      {"a", 0.3, 0.05}, {"b", 0.45, 0.065}, {"c", 0.6, 0.08}};
  const auto below = calibrate(offset, 0.01, 0);
  EXPECT_NEAR(below.parameter, -0.1, 1e-12);
  EXPECT_TRUE(below.changesSign());
  const auto text = calibrationText(below, "mu_fric");
  EXPECT_NE(text.find("warning: mu_fric = -0.1000 has the other sign than every studied value"),
            std::string::npos)
      << text;
  EXPECT_EQ(calibrationJson(below, "mu_fric").at("changes_sign"), true);
  // studied values of both signs: no sign to keep
  const std::vector<CalibrationPoint> both = {{"a", -0.2, 0.0}, {"b", 0.0, 0.02}, {"c", 0.2, 0.04}};
  EXPECT_FALSE(calibrate(both, -0.01, 0).changesSign());
}

TEST(Ft4Calibration, AnEnergyThatBendsIsReadBetweenTheBracketingRunsAndFlagged) {
  // the paper-size friction study's shape: 54.2, 80.22, 81.05 mJ at 0.30, 0.52, 0.70. 80 mJ lies
  // between the first two runs: 0.30 + (80 - 54.2) / (80.22 - 54.2) x 0.22, by hand 0.518140
  const std::vector<CalibrationPoint> bent = {
      {"a", 0.30, 0.05420}, {"b", 0.52, 0.08022}, {"c", 0.70, 0.08105}};
  const auto c = calibrate(bent, 0.080, 0);
  ASSERT_TRUE(c.bracketed.has_value());
  EXPECT_NEAR(*c.bracketed, 0.30 + (80 - 54.2) / (80.22 - 54.2) * 0.22, 1e-12);
  EXPECT_NEAR(*c.bracketed, 0.518140, 1e-6);
  EXPECT_DOUBLE_EQ(c.bracket_low, 0.30);
  EXPECT_DOUBLE_EQ(c.bracket_high, 0.52);
  EXPECT_TRUE(c.bends()) << c.parameter << " +- " << c.sigma;
  EXPECT_NE(calibrationText(c, "mu_fric").find("(it bends)"), std::string::npos);
  // on a line (with scatter) both answers agree within the uncertainty: no warning
  const std::vector<CalibrationPoint> straight = {
      {"a", 0.3, 0.0301}, {"b", 0.45, 0.0449}, {"c", 0.6, 0.0601}, {"d", 0.75, 0.0749}};
  const auto l = calibrate(straight, 0.052, 0);
  ASSERT_TRUE(l.bracketed.has_value());
  EXPECT_NEAR(*l.bracketed, 0.45 + (0.052 - 0.0449) / (0.0601 - 0.0449) * 0.15, 1e-12);
  EXPECT_FALSE(l.bends()) << *l.bracketed << " against " << l.parameter << " +- " << l.sigma;
  EXPECT_EQ(calibrationText(l, "mu_fric").find("warning"), std::string::npos);
  // a measurement no pair brackets (beyond the runs) has no bracketed answer
  EXPECT_FALSE(calibrate(straight, 0.1, 0).bracketed.has_value());
  // one equal to a run's energy is that run's value (both pairs around it agree)
  const auto at = calibrate(straight, 0.0449, 0);
  ASSERT_TRUE(at.bracketed.has_value());
  EXPECT_NEAR(*at.bracketed, 0.45, 1e-12);
  const auto at_first = calibrate(straight, 0.0301, 0);  // the lowest run: one pair only
  ASSERT_TRUE(at_first.bracketed.has_value());
  EXPECT_NEAR(*at_first.bracketed, 0.3, 1e-12);
  // energies that fall and rise again bracket it twice, at different values: none
  const std::vector<CalibrationPoint> zigzag = {
      {"a", 0.3, 0.030}, {"b", 0.45, 0.050}, {"c", 0.6, 0.040}, {"d", 0.75, 0.070}};
  EXPECT_FALSE(calibrate(zigzag, 0.045, 0).bracketed.has_value());
}

TEST(Ft4Calibration, StudyFolderEndToEndRecoversTheFrictionOfASyntheticMeasurement) {
  // runs whose force grows linearly with mu: F = 4 mu N, M = 0.02 mu N m over 30 mm of descent
  // -> gradient g(mu) = 0.02 mu / (R tan a) + 4 mu from 39 mm down, and the step from the rest
  // row at 40 mm (g = 0) a trapezoid of half of it: W(mu) = g(mu) x 0.0295 m; a measurement
  // made at mu = 0.52
  const auto study = tempDir("study");
  int i = 0;
  for (double mu : {0.3, 0.45, 0.6, 0.75})
    syntheticRun(study / ("variant-0" + std::to_string(i++)), mu, 4 * mu, 0.02 * mu);
  syntheticRun(study / "variant-00.previous-1", 0.1, 100, 0);  // a replaced variant: not counted
  const double g = 0.02 * 0.52 / kLever + 4 * 0.52;
  const double w = g * 0.0295;
  write(study / "measured.csv",
        "energy_J\n" + std::to_string(w * 0.98) + "\n" + std::to_string(w * 1.02) + "\n");
  const auto measured = readMeasuredEnergy(study / "measured.csv");
  const auto runs = ft4Runs({study});
  ASSERT_EQ(runs.size(), 4u);
  const auto c = calibrate(calibrationPoints(runs, "mu_fric", measured), measured.mean_J(),
                           measured.standard_error_J());
  // the CSV holds 6 digits: mu back to 1e-5
  EXPECT_NEAR(c.parameter, 0.52, 1e-5);
  // the two replicates +-2 %: standard error 0.02 w, over the slope w / 0.52
  EXPECT_NEAR(c.sigma_measurement, 0.02 * 0.52, 1e-5);
  EXPECT_LT(c.sigma_study, 1e-5);
  // a measured profile over 35 .. 15 mm: the runs' energies over the same heights
  write(study / "profile.csv",
        "height_m,energy_J\n0.035,0\n0.015," + std::to_string(g * 0.020) + "\n");
  const auto prof = readMeasuredEnergy(study / "profile.csv");
  const auto cp = calibrate(calibrationPoints(runs, "mu_fric", prof), prof.mean_J(), 0);
  EXPECT_NEAR(cp.parameter, 0.52, 1e-5);
  EXPECT_THROW((void)ft4Runs({study / "nothing"}), std::runtime_error);
  fs::remove_all(study);
}

// The figures of `cosim ft4 energy` and `cosim ft4 calibrate -o`: the JSON the calibration plot
// reads holds the fit's numbers, and scripts/plot_ft4.py draws both (when a python3 with
// matplotlib is there; without one the line says what to install).
TEST(Ft4Plots, EnergyProfileAndCalibrationDrawnFromTheirFiles) {
  const auto d = tempDir("plots");
  for (int i = 0; i < 3; ++i)
    syntheticRun(d / ("run" + std::to_string(i)), 0.3 + 0.2 * i, 4 * (0.3 + 0.2 * i), 0.01);
  const auto profile = runFlowEnergy(d / "run1");
  write(d / "ft4_energy.csv", energyProfileCsv(profile));
  MeasuredEnergy m;
  m.replicates_J = {runFlowEnergy(d / "run1").total_J()};
  const auto c =
      calibrate(calibrationPoints(ft4Runs({d / "run0", d / "run1", d / "run2"}), "mu_fric", m),
                m.mean_J(), 0);
  const auto json = calibrationJson(c, "mu_fric");
  EXPECT_EQ(json.at("parameter_name"), "mu_fric");
  EXPECT_NEAR(json.at("parameter").get<double>(), 0.5, 1e-9);  // the force is linear in mu
  ASSERT_EQ(json.at("points").size(), 3u);
  EXPECT_NEAR(json.at("points")[2].at("parameter").get<double>(), 0.7, 1e-12);
  writeJsonFile(d / "ft4_calibration.json", json, 2);
  std::string why;
  if (findPython(why)) {
    for (const auto& [kind, input, png] :
         {std::tuple{"energy", d / "ft4_energy.csv", d / "ft4_energy.png"},
          std::tuple{"calibration", d / "ft4_calibration.json", d / "ft4_calibration.png"}}) {
      const auto line =
          drawFigure("plot_ft4.py", {kind, input.string(), png.string()}, png, d / "plot.log");
      EXPECT_EQ(line, "plot: " + png.string());
      std::ifstream in(png, std::ios::binary);
      char magic[4] = {};
      in.read(magic, 4);
      EXPECT_EQ(std::string(magic + 1, 3), "PNG") << png;
    }
    // several profiles over each other (the runs of a study)
    write(d / "run2" / "ft4_energy.csv", energyProfileCsv(runFlowEnergy(d / "run2")));
    const auto both = d / "both.png";
    EXPECT_EQ(drawFigure("plot_ft4.py",
                         {"energy", (d / "ft4_energy.csv").string(),
                          (d / "run2" / "ft4_energy.csv").string(), both.string()},
                         both, d / "plot.log"),
              "plot: " + both.string());
  }
  setenv("COSIM_PYTHON", "/nonexistent/python3", 1);
  const auto line = drawFigure(
      "plot_ft4.py", {"energy", (d / "ft4_energy.csv").string(), (d / "other.png").string()},
      d / "other.png", d / "plot.log");
  unsetenv("COSIM_PYTHON");
  EXPECT_EQ(line.rfind("no plot: ", 0), 0u) << line;
  EXPECT_NE(line.find("apt-get install python3-matplotlib"), std::string::npos) << line;
  fs::remove_all(d);
}

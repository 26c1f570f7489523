// The report's units and number text, the coating per real grain and as a layer, and Wen-Yu's
// minimum fluidization velocity: against hand-computed values.
#include "cosim/analysis/display_units.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cosim/analysis/grain_scale.h"
#include "cosim/analysis/minimum_fluidization.h"

using namespace cosim::analysis;

TEST(DisplayUnits, TheMassUnitIsTheOneInWhichTheValueReadsFrom1To1000) {
  EXPECT_EQ(massUnitFor(2.49e-10).name, "ng");  // 249 ng: the quick bed's mean after 1 s
  EXPECT_EQ(massUnitFor(8e-8).name, "µg");      // 80 µg
  EXPECT_EQ(massUnitFor(8e-8).ascii, "ug");
  EXPECT_EQ(massUnitFor(9.99e-7).name, "µg");  // 999 µg
  EXPECT_EQ(massUnitFor(1e-6).name, "mg");     // 1 mg
  EXPECT_EQ(massUnitFor(2.6e-12).name, "ng");  // 2.6 ng: the paper-size bed per parcel
  EXPECT_EQ(massUnitFor(2.6e-15).name, "pg");
  EXPECT_DOUBLE_EQ(massUnitFor(2.49e-10).si, 1e-12);
  EXPECT_DOUBLE_EQ(massUnitFor(2.49e-10).of(2.49e-10), 249.0);
  EXPECT_EQ(massUnitFor(3.0).name, "kg");
  EXPECT_EQ(massUnitFor(0.0).name, "kg");  // nothing coated: SI
  EXPECT_EQ(massUnitFor(std::nan("")).name, "kg");
  EXPECT_EQ(massUnitFor(1e-25).name, "fg");
  EXPECT_EQ(lengthUnitFor(4.7e-9).name, "nm");
  EXPECT_EQ(lengthUnitFor(1.13e-6).name, "µm");
  EXPECT_EQ(lengthUnitFor(3.9e-10).name, "nm");  // 0.39 nm, not pm
  EXPECT_EQ(lengthUnitFor(1.5e-3).name, "mm");
}

TEST(DisplayUnits, NumbersHaveTheirSignificantDigitsAndNothingToBreakAt) {
  EXPECT_EQ(htmlNumber(249.0), "249");
  EXPECT_EQ(htmlNumber(0.001992), "0.001992");
  EXPECT_EQ(htmlNumber(2.5, 4), "2.5");
  EXPECT_EQ(htmlNumber(995920.0), "995&#8239;900");  // 4 digits, grouped by narrow no-break spaces
  EXPECT_EQ(htmlNumber(12346.0), "12&#8239;350");
  EXPECT_EQ(htmlNumber(1234.0), "1234");
  EXPECT_EQ(htmlNumber(9.99996), "10");  // rounded before the decimals are chosen
  EXPECT_EQ(htmlNumber(-5.0), "&minus;5");
  EXPECT_EQ(htmlNumber(0.0), "0");
  EXPECT_EQ(htmlNumber(1.234e-12), "1.234&times;10<sup>&minus;12</sup>");
  EXPECT_EQ(htmlNumber(-2.5e7, 3), "&minus;2.5&times;10<sup>7</sup>");
  EXPECT_EQ(htmlNumber(std::nan("")), "&ndash;");
  EXPECT_EQ(textNumber(995920.0), "995\u202f900");
  EXPECT_EQ(textNumber(-1.234e-12), "\u22121.234\u00d710^\u221212");
  EXPECT_EQ(htmlQuantity(2.49e-10, massUnitFor(2.49e-10)), "249&nbsp;ng");
  EXPECT_EQ(htmlDuration(0.05), "50&nbsp;ms");
  EXPECT_EQ(htmlDuration(1.0), "1&nbsp;s");
  EXPECT_EQ(htmlDuration(1200.0), "20&nbsp;min");
  EXPECT_EQ(htmlFixed(12.345, 1), "12.3");
  EXPECT_EQ(htmlFixed(-0.04, 1), "0.0");  // no "-0.0"
  EXPECT_EQ(htmlFixed(-2.5, 0), "&minus;2");
  EXPECT_EQ(htmlPercent(0.125), "12.50&nbsp;%");
  EXPECT_EQ(htmlPercent(0.011, 1), "1.1&nbsp;%");
  EXPECT_EQ(htmlPercent(std::nan("")), "&ndash;");
  EXPECT_EQ(textPercent(0.7654), "76.5\u00a0%");
  EXPECT_EQ(textDuration(0.234), "234\u00a0ms");
  EXPECT_EQ(textDuration(3600.0), "60\u00a0min");
  EXPECT_EQ(textQuantity(2.49e-10, massUnitFor(2.49e-10)), "249\u00a0ng");
  for (double v : {1.0, 0.5, 123456.0, 1e-9, -0.02}) {
    EXPECT_EQ(htmlNumber(v).find(' '), std::string::npos) << v;
    EXPECT_EQ(htmlNumber(v).find('-'), std::string::npos) << v << ": a hyphen allows a line break";
  }
}

TEST(GrainScale, CoatingPerRealGrainAndAsALayerByHand) {
  // The quick bed after 1 s: 249 ng per parcel, cg 5, grains of 300 um, coating 1500 kg/m3.
  const GrainScale s{5.0, 300e-6, 1500.0};
  EXPECT_NEAR(s.perGrain(2.49e-10), 1.992e-12, 1e-24);  // 249 ng / 125
  // 1.992e-12 kg / (1500 kg/m3 x pi x (3e-4 m)^2 = 4.2412e-4 kg/m2) = 4.6968e-9 m
  EXPECT_NEAR(s.thickness(2.49e-10), 4.69684e-9, 1e-5 * 4.69684e-9);
  EXPECT_TRUE(std::isnan(GrainScale{5.0}.thickness(1e-10)));  // no diameter: no thickness
}

TEST(MinimumFluidization, WenYuForTheRealGrainsInNitrogen) {
  // N2 at 1 bar and 300 K: 1e5 x 0.0280134 / (8.314462618 x 300) = 1.12308 kg/m3.
  const double rho = idealGasDensity(1e5, 0.0280134, 300.0);
  EXPECT_NEAR(rho, 1.12308, 1e-5);
  // Ar = (3e-4)^3 x 1.12308 x (1750 - 1.12308) x 9.81 / (1.8e-5)^2 = 1605.67,
  // Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7 = 0.958354, u_mf = Re mu / (rho d) = 0.0511996 m/s
  // (docs/physics.md: 0.051 m/s for the real 300 um grains).
  EXPECT_NEAR(wenYuMinimumFluidization(300e-6, 1750.0, rho, 1.8e-5), 0.0511996, 1e-6);
  EXPECT_TRUE(std::isnan(wenYuMinimumFluidization(0.0, 1750.0, rho, 1.8e-5)));
}

// Unit strings -> SI factors (framework/core/include/radchain/units.hpp). References: SI brochure (9th ed.) prefixes,
// IAU 2012 B2 (1 AU = 149 597 870 700 m exactly), 1 deg = π/180 rad. Exact decimal conversions are held to a
// few ulp (1e-15 relative); nothing here is a measured value.
#include "radchain/constants.hpp"
#include "radchain/units.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <stdexcept>
#include <string>

namespace {
using namespace radchain;

constexpr double exact = 1e-15;  // relative: decimal prefixes multiply exactly up to rounding

// "400 km" -> number * factor into `si_unit`.
double to_si(const std::string& text, const std::string& si_unit) {
  const units::ParsedQuantity q = units::split_quantity(text);
  return q.number * units::conversion(q.unit, si_unit).factor;
}

TEST(Units, SplitQuantity) {
  const auto q = units::split_quantity("  400 km ");
  EXPECT_EQ(q.number, 400.0);
  EXPECT_EQ(q.unit, "km");
  const auto bare = units::split_quantity("-26.73");
  EXPECT_EQ(bare.number, -26.73);
  EXPECT_EQ(bare.unit, "");
  // "1e5 e-": the exponent belongs to the number, "e-" is the unit.
  const auto electrons = units::split_quantity("1e5 e-");
  EXPECT_EQ(electrons.number, 1e5);
  EXPECT_EQ(electrons.unit, "e-");
  EXPECT_THROW(units::split_quantity("km 400"), std::invalid_argument);
  EXPECT_THROW(units::split_quantity(""), std::invalid_argument);
}

TEST(Units, Lengths) {
  EXPECT_NEAR(to_si("400 km", "m"), 4e5, 4e5 * exact);
  EXPECT_NEAR(to_si("7 um", "m"), 7e-6, 7e-6 * exact);
  EXPECT_NEAR(to_si("832 mm", "m"), 0.832, 0.832 * exact);
  EXPECT_NEAR(to_si("15 cm", "m"), 0.15, 0.15 * exact);
}

TEST(Units, ExposureMicrojoulePerSquareCentimetre) {
  // 0.0002 µJ/cm² = 2e-4 × 1e-6 J / 1e-4 m² = 2e-6 J/m².
  EXPECT_NEAR(to_si("0.0002 uJ/cm2", "J m-2"), 2e-6, 2e-6 * 1e-14);
  EXPECT_NEAR(to_si("0.0002 uJ/cm2", "J/m2"), 2e-6, 2e-6 * 1e-14);
}

TEST(Units, ElectronCountsAndRates) {
  EXPECT_NEAR(to_si("18 e-/s", "electron/s"), 18.0, 18.0 * exact);
  EXPECT_NEAR(to_si("18 electron/s", "electron/s"), 18.0, 18.0 * exact);
  EXPECT_NEAR(to_si("18 electrons/s", "e-/s"), 18.0, 18.0 * exact);
  EXPECT_EQ(units::dimension_of("e-/s"), units::dimension_of("electron/s"));
  // "e-" is rewritten wherever it stands as a factor, and only there.
  EXPECT_NEAR(to_si("18 e-.s-1", "electron/s"), 18.0, 18.0 * exact);
  EXPECT_NEAR(to_si("18 (e-)/s", "electron/s"), 18.0, 18.0 * exact);
  EXPECT_NEAR(to_si("18 e- s-1", "electron/s"), 18.0, 18.0 * exact);
  EXPECT_NEAR(to_si("4 e-^2", "electron2"), 4.0, 4.0 * exact);
  EXPECT_FALSE(units::parses("e-x"));
  EXPECT_NEAR(to_si("1e5 e-", "electron"), 1e5, 1e5 * exact);
  EXPECT_NEAR(to_si("6 e-", "electron"), 6.0, 6.0 * exact);
  // An electron count is not a rate, and not dimensionless.
  EXPECT_THROW(units::conversion("e-", "electron/s"), std::domain_error);
  EXPECT_THROW(units::conversion("e-", "1"), std::domain_error);
}

TEST(Units, ASystemGainAloneReadsAReciprocal) {
  // ADC counts are plain numbers under either name.
  EXPECT_EQ(units::conversion("DN/e-", "electron-1").factor, 1.0);
  EXPECT_EQ(units::conversion("ADU/e-", "electron-1").factor, 1.0);
  EXPECT_EQ(units::reciprocal_conversion("e-/ADU", "electron-1"), 1.0);
  EXPECT_EQ(units::reciprocal_conversion("e-/DN", "electron-1"), 1.0);
  // Not a gain's own unit, not another dimension, not another key's reciprocal.
  EXPECT_FALSE(units::reciprocal_conversion("DN/e-", "electron-1"));
  EXPECT_FALSE(units::reciprocal_conversion("e-/s", "electron-1"));
  EXPECT_FALSE(units::reciprocal_conversion("Hz", "s"));
  EXPECT_FALSE(units::reciprocal_conversion("", "electron-1"));
}

TEST(Units, ElementaryChargeIsNotAnElectronCount) {
  // udunits reads "e" as the elementary charge (coulomb): it must never pass for electrons.
  EXPECT_TRUE(units::parses("e"));
  EXPECT_THROW(units::conversion("e", "electron"), std::domain_error);
  EXPECT_THROW(units::conversion("e/s", "electron/s"), std::domain_error);
  // (udunits' own "e" is the CODATA 2006 value 1.602176487e-19 C; radchain never uses it.)
  EXPECT_NEAR(units::conversion("e", "C").factor, constants::elementary_charge_C, constants::elementary_charge_C * 1e-6);
}

TEST(Units, AnglesKeepTheirDimension) {
  const double deg = units::conversion("deg", "rad").factor;
  EXPECT_NEAR(deg, std::numbers::pi / 180.0, std::numbers::pi / 180.0 * exact);
  EXPECT_NEAR(to_si("90 deg", "rad"), std::numbers::pi / 2, std::numbers::pi / 2 * exact);
  EXPECT_NEAR(to_si("1 mrad", "rad"), 1e-3, 1e-3 * exact);
}

TEST(Units, AstronomicalUnitIsTheIau2012Value) {
  EXPECT_NEAR(to_si("1 AU", "m"), constants::astronomical_unit_m, constants::astronomical_unit_m * exact);
  EXPECT_EQ(constants::astronomical_unit_m, 149597870700.0);
}

TEST(Units, LinePairsPerMillimetre) {
  EXPECT_NEAR(to_si("86 lp/mm", "m-1"), 86000.0, 86000.0 * exact);
  EXPECT_NEAR(to_si("86 cy/mm", "1/m"), 86000.0, 86000.0 * exact);
}

TEST(Units, RadiometricUnits) {
  EXPECT_NEAR(to_si("1 W m-2 nm-1", "W m-2 m-1"), 1e9, 1e9 * exact);
  EXPECT_NEAR(to_si("1 W/m2/um", "W m-2 m-1"), 1e6, 1e6 * exact);
  EXPECT_NEAR(to_si("1361 W/m2", "W m-2"), 1361.0, 1361.0 * exact);
  EXPECT_NEAR(to_si("1.3e5 lx", "lx"), 1.3e5, 1.3e5 * exact);
  EXPECT_NEAR(to_si("5778 K", "K"), 5778.0, 5778.0 * exact);
  EXPECT_NEAR(to_si("0.625 s", "s"), 0.625, 0.625 * exact);
  EXPECT_NEAR(to_si("10 ms", "s"), 0.01, 0.01 * exact);
}

TEST(Units, WrongDimensionIsADomainError) {
  EXPECT_THROW(units::conversion("kg", "m"), std::domain_error);
  EXPECT_THROW(units::conversion("s", "m"), std::domain_error);
  EXPECT_THROW(units::conversion("W m-2", "W m-2 m-1"), std::domain_error);
  // A radiance is not an irradiance: the steradian is kept as a dimension.
  EXPECT_THROW(units::conversion("W m-2 sr-1", "W m-2"), std::domain_error);
}

TEST(Units, OffsetUnitsAreRefused) {
  EXPECT_THROW(units::conversion("degC", "K"), std::domain_error);
}

TEST(Units, UnparsableUnitIsAnInvalidArgument) {
  EXPECT_FALSE(units::parses("furlongz"));
  EXPECT_THROW(units::conversion("furlongz", "m"), std::invalid_argument);
  EXPECT_THROW(units::conversion("cmm", "m"), std::invalid_argument);
  EXPECT_THROW(units::dimension_of("m/"), std::invalid_argument);
  EXPECT_TRUE(units::parses("W m-2 nm-1"));
}

// Found by tests/fuzz/overrides_fuzz: a zero factor followed by a name made udunits2 leak that name
// (LeakSanitizer in the ASan build reports it at exit). Refused like any unparsable unit; the units after it parse.
TEST(Units, ZeroFactorIsRefusedWithoutLeak) {
  // The '.' that multiplies (after a name or an exponent; spectrum_csv_fuzz, seed 1: "wavelength_m,_pk.0X").
  for (const char* unit : {"m 0A", "m/0A", "m*0.0A", "pt 0Aics.apertc", "A 0e0A", "pk.0X", "m.0X", "m2.0X", "W m -0nm"})
    EXPECT_THROW(units::conversion(unit, "m"), std::invalid_argument) << unit;
  EXPECT_DOUBLE_EQ(units::conversion("cm", "m").factor, 0.01);
  EXPECT_DOUBLE_EQ(units::conversion("2.0 cm", "m").factor, 0.02);      // a decimal point, not a product
  EXPECT_DOUBLE_EQ(units::conversion("kg.m", "kg m").factor, 1.0);
  EXPECT_DOUBLE_EQ(units::conversion("10 cm", "m").factor, 0.1);
  EXPECT_DOUBLE_EQ(units::conversion("0.5 m", "m").factor, 0.5);
}

TEST(Units, DimensionNames) {
  EXPECT_EQ(units::dimension_name("m"), "a length");
  EXPECT_EQ(units::dimension_name("electron"), "an electron count");
  EXPECT_EQ(units::dimension_name("W m-2 m-1"), "a spectral irradiance");
  EXPECT_EQ(units::dimension_name("kg"), "a quantity in kg");
}

}  // namespace

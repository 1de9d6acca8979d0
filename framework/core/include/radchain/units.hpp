#pragma once
// Unit strings -> SI doubles, through udunits2 (Debian libudunits2). udunits reads "e" as the elementary
// charge and has no "deg", so the registry adds, deliberately:
//   electron counts:  "e-", "electron(s)" as a new base dimension (so "6 e-" is a count, "18 e-/s" a rate);
//   "deg" = arc degree, "AU" = astronomical unit, "lp" (line pairs) = 1, so "86 lp/mm" = 86 mm-1;
//   "DN" and "ADU" (ADC counts) = 1, so a system gain reads "0.25 DN/e-" (or, reciprocal, "4 e-/ADU").
// Angles keep their own dimension (radian) here: a length per steradian is not a length.
#include <optional>
#include <string>

namespace radchain::units {

// A unit resolved against an SI target: value_si = value * factor (no offset units are accepted).
struct Conversion {
  double factor = 1.0;
};

// The SI "signature" of a unit string ("kg.m-1.s-3"), i.e. its dimension; throws std::invalid_argument
// with a short reason when the unit does not parse.
std::string dimension_of(const std::string& unit);

// Factor converting values in `unit` to `si_unit`. Throws std::invalid_argument when `unit` does not
// parse, or std::domain_error when the two have different dimensions.
Conversion conversion(const std::string& unit, const std::string& si_unit);

// The factor f of a unit that is the reciprocal of `si_unit`'s dimension where that reading is accepted: value_si =
// 1 / (value × f). Only a system gain (si_unit "electron-1": "1.6 e-/DN" is K = 0.625 DN/e-); nullopt otherwise.
std::optional<double> reciprocal_conversion(const std::string& unit, const std::string& si_unit);

// true when `unit` parses.
bool parses(const std::string& unit);

// Human name of the dimension of an SI unit, for error messages: "a length", "a time", "an irradiance"...
std::string dimension_name(const std::string& si_unit);

// A quantity written as text: "400 km", "0.0002 uJ/cm2", "1e5 e-", "-26.73" (no unit).
struct ParsedQuantity {
  double number = 0.0;
  std::string unit;         // trimmed; empty when the text was a bare number
  std::string number_text;  // the number as written ("519.6", "1e5")
};
// Throws std::invalid_argument if the text does not start with a number.
ParsedQuantity split_quantity(const std::string& text);

// A number in a unit, in SI: number × factor. A power-of-ten factor 10^k (a prefix: um, nm, cm, ms) is applied as
// a division by the exact 10^-k (or a product by the exact 10^k), one correctly rounded operation: "7.5 um" is then
// the double nearest 7.5e-6, as "0.0000075 m" is, where 7.5 × 1e-6 (1e-6 itself rounded) landed an ulp away and
// the same input written in other units gave other bits downstream. Sweeps and files convert the same way.
double to_si(double number, double factor);
// A number as written, in SI: with a power-of-ten factor the decimal exponent is shifted in the text, which is
// parsed once: "519.6 nm" is the double nearest 5.196e-7, as "0.5196 um" and "5.196e-7 m" are (519.6 is not a
// double, and dividing its nearest double by 1e9 can land an ulp away). Else to_si(number, factor).
double to_si(const ParsedQuantity& quantity, double factor);

}  // namespace radchain::units

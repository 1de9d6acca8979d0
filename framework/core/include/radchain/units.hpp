#pragma once
// Unit strings -> SI doubles, through udunits2 (Debian libudunits2). udunits reads "e" as the elementary
// charge and has no "deg", so the registry adds, deliberately:
//   electron counts:  "e-", "electron(s)" as a new base dimension (so "6 e-" is a count, "18 e-/s" a rate);
//   "deg" = arc degree, "AU" = astronomical unit, "lp" (line pairs) = 1, so "86 lp/mm" = 86 mm-1.
// Angles keep their own dimension (radian) here: a length per steradian is not a length.
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

// true when `unit` parses.
bool parses(const std::string& unit);

// Human name of the dimension of an SI unit, for error messages: "a length", "a time", "an irradiance"...
std::string dimension_name(const std::string& si_unit);

// A quantity written as text: "400 km", "0.0002 uJ/cm2", "1e5 e-", "-26.73" (no unit).
struct ParsedQuantity {
  double number = 0.0;
  std::string unit;  // trimmed; empty when the text was a bare number
};
// Throws std::invalid_argument if the text does not start with a number.
ParsedQuantity split_quantity(const std::string& text);

}  // namespace radchain::units

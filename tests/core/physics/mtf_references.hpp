#pragma once
// Independent references for diffraction MTFs, shared by the physics tests and the catalogue's imager test.
#include <cmath>
#include <numbers>

namespace radchain::test {

// O'Neill, J. Opt. Soc. Am. 46 (1956) 285: closed form of the annular-pupil MTF as the sum A + B + C over
// (1 − ε²), x = ν/ν_c, φ = acos((1 + ε² − 4x²)/(2ε)) — a different route from the library's disc overlaps.
inline double oneill_annular_mtf(double x, double e) {
  const double a = x <= 1 ? 2 / std::numbers::pi * (std::acos(x) - x * std::sqrt(1 - x * x)) : 0.0;
  const double b = (e > 0 && x <= e) ? 2 * e * e / std::numbers::pi * (std::acos(x / e) - x / e * std::sqrt(1 - x * x / (e * e))) : 0.0;
  double c = 0;
  if (x <= (1 - e) / 2) {
    c = -2 * e * e;
  } else if (x < (1 + e) / 2) {
    const double phi = std::acos((1 + e * e - 4 * x * x) / (2 * e));
    c = -2 * e * e + 2 * e / std::numbers::pi * std::sin(phi) + (1 + e * e) / std::numbers::pi * phi -
        2 * (1 - e * e) / std::numbers::pi * std::atan((1 + e) / (1 - e) * std::tan(phi / 2));
  }
  return (a + b + c) / (1 - e * e);
}

}  // namespace radchain::test

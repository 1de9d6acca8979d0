#pragma once
// Where the Sun is for an Earth-observation scene: its declination and distance on a day of the year (Spencer's
// Fourier series), and its zenith angle at a latitude and local solar time (spherical astronomy).
//   J. W. Spencer, "Fourier series representation of the position of the Sun", Search 2 (1971) 172: with the day
//   angle Γ = 2π (d − 1)/365,
//     δ = 0.006918 − 0.399912 cos Γ + 0.070257 sin Γ − 0.006758 cos 2Γ + 0.000907 sin 2Γ − 0.002697 cos 3Γ
//         + 0.00148 sin 3Γ                                                    (rad; max error 0.0006 rad)
//     (r₀/r)² = 1.000110 + 0.034221 cos Γ + 0.001280 sin Γ + 0.000719 cos 2Γ + 0.000077 sin 2Γ
//   (the distance meets the Almanac's perihelion and aphelion to 4e-4 AU, 0.08 % in irradiance: tests)
//   cos θ_s = sin φ sin δ + cos φ cos δ cos h, h = π (t − 12 h)/(12 h) the hour angle at local solar time t
//   (e.g. Iqbal, An Introduction to Solar Radiation (1983) §1.5; Duffie & Beckman, Solar Engineering of Thermal
//   Processes, eq. 1.6.5).
#include <algorithm>
#include <cmath>
#include <numbers>

namespace radchain::physics {

inline double spencer_day_angle_rad(double day_of_year) { return 2 * std::numbers::pi * (day_of_year - 1) / 365.0; }

inline double solar_declination_rad(double day_of_year) {
  const double g = spencer_day_angle_rad(day_of_year);
  return 0.006918 - 0.399912 * std::cos(g) + 0.070257 * std::sin(g) - 0.006758 * std::cos(2 * g) +
         0.000907 * std::sin(2 * g) - 0.002697 * std::cos(3 * g) + 0.00148 * std::sin(3 * g);
}

// The Earth–Sun distance in astronomical units: r/r₀ = ((r₀/r)²)^(−½).
inline double earth_sun_distance_au(double day_of_year) {
  const double g = spencer_day_angle_rad(day_of_year);
  const double inverse_square = 1.000110 + 0.034221 * std::cos(g) + 0.001280 * std::sin(g) + 0.000719 * std::cos(2 * g) +
                                0.000077 * std::sin(2 * g);
  return 1.0 / std::sqrt(inverse_square);
}

// Solar zenith angle (rad) at latitude φ, declination δ and local solar time t (seconds after midnight); above
// π/2 the Sun is below the horizon.
inline double solar_zenith_rad(double latitude_rad, double declination_rad, double local_solar_time_s) {
  const double hour_angle = std::numbers::pi * (local_solar_time_s - 43200.0) / 43200.0;
  const double cos_zenith = std::sin(latitude_rad) * std::sin(declination_rad) +
                            std::cos(latitude_rad) * std::cos(declination_rad) * std::cos(hour_angle);
  return std::acos(std::clamp(cos_zenith, -1.0, 1.0));
}

// Relative optical air mass of a path at zenith angle z (Kasten & Young 1989, Applied Optics 28, 4735, eq. 3):
// X = 1 / (cos z + 0.50572 (96.07995° − z)^−1.6364), z in degrees inside the bracket: 0.3 % below sec z at 60°,
// 1.3 % at 75°, 37.92 at the horizon (where the plane-parallel sec z diverges).
inline double kasten_young_airmass(double zenith_rad) {
  const double z_deg = zenith_rad * 180.0 / std::numbers::pi;
  return 1.0 / (std::cos(zenith_rad) + 0.50572 * std::pow(96.07995 - z_deg, -1.6364));
}

// The relative air mass on an RT table's airmass axis: Kasten & Young 1989, held at 1 where the fit dips below it
// near the zenith. Relative air mass is the slant column over the vertical one, 1 at the zenith by definition;
// the fit gives 0.99971 there and reaches 1 at z ≈ 1.4°, which would put a nadir view or an overhead Sun just
// below a table's X = 1 node.
inline double relative_airmass(double zenith_rad) { return std::max(1.0, kasten_young_airmass(zenith_rad)); }

}  // namespace radchain::physics

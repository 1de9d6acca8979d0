#pragma once
// Physical constants: the exact SI-2019 defining constants and quantities derived from them, in SI units.
// Source: BIPM, The International System of Units (SI), 9th edition (2019), Table 1; CODATA 2018.
#include <numbers>

namespace radchain::constants {

inline constexpr double planck_J_s = 6.62607015e-34;          // h, exact
inline constexpr double speed_of_light_m_s = 299792458.0;      // c, exact
inline constexpr double boltzmann_J_K = 1.380649e-23;          // k_B, exact
inline constexpr double elementary_charge_C = 1.602176634e-19; // e, exact
// K_cd: luminous efficacy of 540 THz radiation, exact. CIE uses K_m = 683.002 lm/W at the peak of V(λ)
// (555.017 nm); the papers and most tools use 683, which is what photometry.hpp defaults to.
inline constexpr double luminous_efficacy_540THz_lm_W = 683.0;
inline constexpr double astronomical_unit_m = 149597870700.0;  // IAU 2012 Resolution B2, exact

// Second radiation constant c2 = h c / k_B = 1.438776877...e-2 m K.
inline constexpr double second_radiation_m_K = planck_J_s * speed_of_light_m_s / boltzmann_J_K;
// First radiation constant for spectral radiance c1L = 2 h c^2 (W m^2 sr^-1).
inline constexpr double first_radiation_radiance_W_m2_sr = 2.0 * planck_J_s * speed_of_light_m_s * speed_of_light_m_s;
// Stefan-Boltzmann sigma = 2 pi^5 k^4 / (15 h^3 c^2) = 5.670374419e-8 W m^-2 K^-4.
inline constexpr double stefan_boltzmann_W_m2_K4 =
    2.0 * std::numbers::pi * std::numbers::pi * std::numbers::pi * std::numbers::pi * std::numbers::pi *
    boltzmann_J_K * boltzmann_J_K * boltzmann_J_K * boltzmann_J_K /
    (15.0 * planck_J_s * planck_J_s * planck_J_s * speed_of_light_m_s * speed_of_light_m_s);
// Wien displacement constant b = c2 / x, x = 4.965114231744276 the root of x = 5 (1 - e^-x).
inline constexpr double wien_displacement_m_K = second_radiation_m_K / 4.965114231744276303;

// Historical c2 values, for sources specified on an older temperature scale (see docs/sources.md).
inline constexpr double second_radiation_1931_m_K = 1.435e-2;   // CIE illuminant A definition (2848 K)
inline constexpr double second_radiation_ipts48_m_K = 1.438e-2; // IPTS-48 ("2854 K" lamps)
inline constexpr double second_radiation_ipts68_m_K = 1.4388e-2;// IPTS-68 ("2856 K")

}  // namespace radchain::constants

#pragma once
// Photometry and visual magnitudes.
//   Luminous quantity X_v = K_m ∫ V(λ) X_λ dλ   (CIE 015:2018 §6; K_m = 683 lm/W, CIE 1924 V(λ))
//   Pan et al. 2010 eq. (1): E_t = 10^{0.4 (m_sun - m)} E_sun, m_sun = -26.73 (the paper's value)
#include "radchain/constants.hpp"
#include "radchain/spectrum.hpp"

namespace radchain::physics {

inline constexpr double sun_visual_magnitude_pan2010 = -26.73;

// K_m ∫ V X dλ over the overlap of both spectra (V in "1", X spectral radiometric, per metre).
double luminous(const Spectrum& spectral_radiometric, const Spectrum& v_lambda,
                double km_lm_W = constants::luminous_efficacy_540THz_lm_W);

// Pan 2010 eq. (1): the ratio E_t / E_sun for an object of visual magnitude m.
double magnitude_ratio(double magnitude, double sun_magnitude = sun_visual_magnitude_pan2010);
// Inverse of eq. (1): m = m_sun - 2.5 lg(E_t / E_sun).
double magnitude_from_ratio(double ratio, double sun_magnitude = sun_visual_magnitude_pan2010);

// Photon count per joule at λ: λ / (h c) (Pan 2010 eq. 6).
inline double photons_per_joule(double wavelength_m) {
  return wavelength_m / (constants::planck_J_s * constants::speed_of_light_m_s);
}

}  // namespace radchain::physics

#pragma once
// Photometry, visual magnitudes and photon counts.
//   Luminous quantity X_v = K_m ∫ V(λ) X_λ dλ   (CIE 015:2018 §6; K_m = 683 lm/W, CIE 1924 V(λ))
//   Pan et al. 2010 eq. (1): E_t = 10^{0.4 (m_sun - m)} E_sun, m_sun = -26.73 (the paper's value)
//   Pan et al. 2010 eqs. (3)-(5): a luminous flux F with relative spectral distribution Φr(λ) is the
//     radiometric spectral flux Φ_λ = Φ_λmax Φr(λ), Φ_λmax = F / (K_m ∫ V Φr dλ)
//   Pan et al. 2010 eqs. (6)-(7): photon rate n(λ) = Φ_λ λ/(hc); electrons n_e = ∫ n(λ) η(λ) dλ
#include "radchain/constants.hpp"
#include "radchain/lanes.hpp"
#include "radchain/spectrum.hpp"

#include <string>

namespace radchain::physics {

inline constexpr double sun_visual_magnitude_pan2010 = -26.73;

// K_m ∫ V X dλ over the overlap of both spectra (V in "1", X spectral radiometric, per metre).
double luminous(const Spectrum& spectral_radiometric, const Spectrum& v_lambda,
                double km_lm_W = constants::luminous_efficacy_540THz_lm_W);

// Pan 2010 eq. (1): the ratio E_t / E_sun for an object of visual magnitude m.
double magnitude_ratio(double magnitude, double sun_magnitude = sun_visual_magnitude_pan2010);
Lanes magnitude_ratio(const Lanes& magnitude, const Lanes& sun_magnitude);
// Inverse of eq. (1): m = m_sun - 2.5 lg(E_t / E_sun).
double magnitude_from_ratio(double ratio, double sun_magnitude = sun_visual_magnitude_pan2010);

// Photon count per joule at λ: λ / (h c) (Pan 2010 eq. 6).
inline double photons_per_joule(double wavelength_m) {
  return wavelength_m / (constants::planck_J_s * constants::speed_of_light_m_s);
}

// Pan 2010 eqs. (3)-(5): Φ_λmax = F / (K_m ∫ V Φr dλ), the factor that turns the relative spectral
// distribution Φr(λ) (any normalisation) into the radiometric spectral quantity whose luminous value is
// `luminous_value` (lm -> W m^-1, lx -> W m^-2 m^-1). The photometric integral runs over the overlap of
// Φr and V (the CIE table: 360-830 nm; Pan writes 0.38 µm to ∞, and 0.38-0.76 µm in eq. 8).
double radiometric_scale_from_luminous(double luminous_value, const Spectrum& relative_distribution,
                                       const Spectrum& v_lambda,
                                       double km_lm_W = constants::luminous_efficacy_540THz_lm_W);
// Pan 2010 eqs. (3)-(5): Φ_λ = F Φr(λ) / (K_m ∫ V Φr dλ), on Φr's grid, in `unit` (e.g. "W m-1").
Spectrum radiometric_from_luminous(double luminous_value, const Spectrum& relative_distribution,
                                   const Spectrum& v_lambda, std::string unit,
                                   double km_lm_W = constants::luminous_efficacy_540THz_lm_W);

// Pan 2010 eqs. (6)-(7): n = ∫_{lo}^{hi} Φ_λ λ/(hc) η(λ) dλ. Photons per second (for Φ_λ in W m^-1),
// or photoelectrons per second when a quantum efficiency curve η(λ) is given (nullptr: η = 1).
double photon_rate(const Spectrum& spectral_radiometric, double lo_m, double hi_m,
                   const Spectrum* quantum_efficiency = nullptr);

// Pan 2010 eqs. (3)-(7) together: photons (or, with η, electrons) per second in [lo, hi] for each lumen of
// a source with relative spectral distribution Φr, i.e. ∫ Φr λ/(hc) η dλ / (K_m ∫ V Φr dλ).
// Multiply by a luminous flux in lm (or an illuminance in lx for a rate per m^2).
double photons_per_lumen(const Spectrum& relative_distribution, const Spectrum& v_lambda, double lo_m,
                         double hi_m, const Spectrum* quantum_efficiency = nullptr,
                         double km_lm_W = constants::luminous_efficacy_540THz_lm_W);

}  // namespace radchain::physics

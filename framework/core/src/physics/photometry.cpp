#include "radchain/physics/photometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace radchain::physics {

double luminous(const Spectrum& spectral_radiometric, const Spectrum& v_lambda, double km_lm_W) {
  const double lo = std::max(spectral_radiometric.min_wavelength_m(), v_lambda.min_wavelength_m());
  const double hi = std::min(spectral_radiometric.max_wavelength_m(), v_lambda.max_wavelength_m());
  return km_lm_W * band_integral({&spectral_radiometric, &v_lambda}, lo, hi);
}

// 10^{0.4 Δm} as e^{0.4 ln 10 Δm}: exp is the cheaper call (a limiting-magnitude solve evaluates this ~10 times).
double magnitude_ratio(double magnitude, double sun_magnitude) {
  return std::exp(0.4 * std::numbers::ln10 * (sun_magnitude - magnitude));
}
// Per lane with glibc's exp (dispatched to its FMA form at run time): faster than Eigen's SSE2 packet exp, and the
// same bits as the scalar form.
// Equal neighbours (a solver's pass at one bracket end for every lane) share one exponential.
Lanes magnitude_ratio(const Lanes& magnitude, const Lanes& sun_magnitude) {
  Lanes ratio;
  ratio(0) = magnitude_ratio(magnitude(0), sun_magnitude(0));
  for (int i = 1; i < lane_count; ++i)
    ratio(i) = magnitude(i) == magnitude(i - 1) && sun_magnitude(i) == sun_magnitude(i - 1)
                   ? ratio(i - 1)
                   : magnitude_ratio(magnitude(i), sun_magnitude(i));
  return ratio;
}

double magnitude_from_ratio(double ratio, double sun_magnitude) { return sun_magnitude - 2.5 * std::log10(ratio); }

double radiometric_scale_from_luminous(double luminous_value, const Spectrum& relative_distribution,
                                       const Spectrum& v_lambda, double km_lm_W) {
  // Pan 2010 eqs. (3)-(5): F = ∫ K(λ) Φ_λmax Φr(λ) dλ with K(λ) = K_m V(λ).
  const double luminous_per_unit = luminous(relative_distribution, v_lambda, km_lm_W);
  if (!(luminous_per_unit > 0))
    throw std::invalid_argument("radiometric_scale_from_luminous: the distribution has no light where V(λ) > 0");
  return luminous_value / luminous_per_unit;
}

Spectrum radiometric_from_luminous(double luminous_value, const Spectrum& relative_distribution,
                                   const Spectrum& v_lambda, std::string unit, double km_lm_W) {
  return relative_distribution.scaled(
      radiometric_scale_from_luminous(luminous_value, relative_distribution, v_lambda, km_lm_W), std::move(unit));
}

double photon_rate(const Spectrum& spectral_radiometric, double lo_m, double hi_m, const Spectrum* quantum_efficiency) {
  // Pan 2010 eq. (6): n(λ) = Φ_λ λ/(hc); eq. (7): n_e = ∫ n(λ) η_λ dλ.
  if (quantum_efficiency) return band_integral({&spectral_radiometric, quantum_efficiency}, lo_m, hi_m, Weight::photons);
  return band_integral({&spectral_radiometric}, lo_m, hi_m, Weight::photons);
}

double photons_per_lumen(const Spectrum& relative_distribution, const Spectrum& v_lambda, double lo_m, double hi_m,
                         const Spectrum* quantum_efficiency, double km_lm_W) {
  return radiometric_scale_from_luminous(1.0, relative_distribution, v_lambda, km_lm_W) *
         photon_rate(relative_distribution, lo_m, hi_m, quantum_efficiency);
}

}  // namespace radchain::physics

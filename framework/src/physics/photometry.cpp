#include "radchain/physics/photometry.hpp"

#include <cmath>

namespace radchain::physics {

double luminous(const Spectrum& spectral_radiometric, const Spectrum& v_lambda, double km_lm_W) {
  const double lo = std::max(spectral_radiometric.min_wavelength_m(), v_lambda.min_wavelength_m());
  const double hi = std::min(spectral_radiometric.max_wavelength_m(), v_lambda.max_wavelength_m());
  return km_lm_W * band_integral({&spectral_radiometric, &v_lambda}, lo, hi);
}

double magnitude_ratio(double magnitude, double sun_magnitude) { return std::pow(10.0, 0.4 * (sun_magnitude - magnitude)); }

double magnitude_from_ratio(double ratio, double sun_magnitude) { return sun_magnitude - 2.5 * std::log10(ratio); }

}  // namespace radchain::physics

#include "radchain/physics/planck.hpp"

#include <cmath>
#include <numbers>

namespace radchain::physics {

double planck_spectral_radiance(double wavelength_m, double temperature_K, double c2_m_K) {
  const double x = c2_m_K / (wavelength_m * temperature_K);
  const double l5 = std::pow(wavelength_m, 5);
  return constants::first_radiation_radiance_W_m2_sr / l5 / std::expm1(x);
}

double planck_spectral_exitance(double wavelength_m, double temperature_K, double c2_m_K) {
  return std::numbers::pi * planck_spectral_radiance(wavelength_m, temperature_K, c2_m_K);
}

double planck_photon_spectral_exitance(double wavelength_m, double temperature_K) {
  return planck_spectral_exitance(wavelength_m, temperature_K) * wavelength_m /
         (constants::planck_J_s * constants::speed_of_light_m_s);
}

double blackbody_exitance(double temperature_K) {
  const double t2 = temperature_K * temperature_K;
  return constants::stefan_boltzmann_W_m2_K4 * t2 * t2;
}

double wien_peak_wavelength_m(double temperature_K) { return constants::wien_displacement_m_K / temperature_K; }

double blackbody_fraction_below(double wavelength_m, double temperature_K, double c2_m_K) {
  if (wavelength_m <= 0) return 0.0;
  const double x = c2_m_K / (wavelength_m * temperature_K);
  double sum = 0.0;
  for (int n = 1; n < 2000; ++n) {
    const double dn = n;
    const double term = std::exp(-dn * x) / dn * (x * x * x + 3 * x * x / dn + 6 * x / (dn * dn) + 6 / (dn * dn * dn));
    sum += term;
    if (term < 1e-17 * sum) break;
  }
  const double pi2 = std::numbers::pi * std::numbers::pi;
  return 15.0 / (pi2 * pi2) * sum;
}

}  // namespace radchain::physics

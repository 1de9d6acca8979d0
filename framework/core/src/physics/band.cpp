#include "radchain/physics/band.hpp"

#include "radchain/physics/planck.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace radchain::physics {

WavelengthRange support(const Spectrum& spectrum) { return {spectrum.min_wavelength_m(), spectrum.max_wavelength_m()}; }

double fraction_below(const Spectrum& source, double wavelength_m) {
  const double total = source.integral();
  if (!(total > 0)) throw std::invalid_argument("fraction_below: the spectrum's integral is not positive");
  if (wavelength_m <= source.min_wavelength_m()) return 0.0;
  if (wavelength_m >= source.max_wavelength_m()) return 1.0;
  return source.integral(source.min_wavelength_m(), wavelength_m) / total;
}

double band_fraction(const Spectrum& source, double lo_m, double hi_m) {
  return fraction_below(source, hi_m) - fraction_below(source, lo_m);
}

double blackbody_band_fraction(double lo_m, double hi_m, double temperature_K, double c2_m_K) {
  return blackbody_fraction_below(hi_m, temperature_K, c2_m_K) - blackbody_fraction_below(lo_m, temperature_K, c2_m_K);
}

double utilisation_coefficient(const Spectrum& source, const Spectrum& relative_response,
                               WavelengthRange response_range, WavelengthRange source_range, Counting counting) {
  // Photon counting weights both integrands by λ/(hc) (the constant cancels in the ratio).
  const Weight weight = counting == Counting::photons ? Weight::photons : Weight::energy;
  const double used = band_integral({&source, &relative_response}, response_range.lo_m, response_range.hi_m, weight);
  const double available = band_integral({&source}, source_range.lo_m, source_range.hi_m, weight);
  if (!(available > 0)) throw std::invalid_argument("utilisation_coefficient: no source radiation in the source range");
  return used / available;
}

Spectrum normalised_to_peak(const Spectrum& spectrum) {
  const double peak = spectrum.peak_value();
  if (!(peak > 0)) throw std::invalid_argument("normalised_to_peak: the spectrum has no positive value");
  return spectrum.scaled(1.0 / peak, "1");
}

Spectrum per_watt_relative_response(const Spectrum& quantum_efficiency) {
  const Spectrum per_watt(quantum_efficiency.wavelength_m(), quantum_efficiency.value() * quantum_efficiency.wavelength_m(),
                          "m", quantum_efficiency.extrapolation());
  return normalised_to_peak(per_watt);
}

Eigen::ArrayXd planck_grid_m() {
  constexpr int uv_steps = 1000;       // 10 nm -> 100 nm, logarithmic
  constexpr int linear_points = 2401;  // 100, 101, ..., 2500 nm
  constexpr int log_steps = 2000;      // 2500 nm -> 100 µm
  constexpr int far_ir_steps = 1500;   // 100 µm -> 1 mm
  std::vector<double> grid;
  grid.reserve(uv_steps + linear_points + log_steps + far_ir_steps);
  auto logarithmic = [&](double from, double to, int steps) {  // (from, to]
    const double ratio = std::log(to / from) / steps;
    for (int k = 1; k < steps; ++k) grid.push_back(from * std::exp(ratio * k));
    grid.push_back(to);
  };
  grid.push_back(10e-9);
  logarithmic(10e-9, 100e-9, uv_steps);
  for (int i = 1; i < linear_points; ++i) grid.push_back((100.0 + i) * 1e-9);
  logarithmic(2500e-9, 100e-6, log_steps);
  logarithmic(100e-6, 1e-3, far_ir_steps);
  return Eigen::Map<const Eigen::ArrayXd>(grid.data(), static_cast<Eigen::Index>(grid.size()));
}

Spectrum blackbody_exitance_spectrum(double temperature_K, double c2_m_K, const Eigen::ArrayXd& grid_m) {
  if (!(temperature_K > 0)) throw std::invalid_argument("blackbody_exitance_spectrum: temperature must be > 0 K");
  return Spectrum::sampled(grid_m, [&](double l) { return planck_spectral_exitance(l, temperature_K, c2_m_K); },
                           "W m-2 m-1");
}

}  // namespace radchain::physics

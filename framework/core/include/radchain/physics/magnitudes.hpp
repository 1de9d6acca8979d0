#pragma once
// Magnitude systems in a bandpass, counted in photons (the convention of photon-counting detectors;
// Bessell & Murphy 2012, PASP 124, 140, eqs. A1-A3; Fukugita et al. 1996, AJ 111, 1748 eq. 7; synphot):
//   m = −2.5 lg( ∫ f_λ T λ dλ / ∫ f_λ,ref T λ dλ ) + m_ref
// with the reference spectrum of the system:
//   AB (Oke & Gunn 1983, ApJ 266, 713):   f_ν,ref = 10^{-0.4·48.60} erg s⁻¹ cm⁻² Hz⁻¹ = 3630.8 Jy (flat in f_ν),
//                                          f_λ,ref = f_ν,ref c / λ²
//   ST (HST convention, Koornneef et al. 1986; synphot): f_λ,ref = 10^{-0.4·21.10} erg s⁻¹ cm⁻² Å⁻¹ (flat in f_λ)
//   Vega: the spectrum of α Lyr (CALSPEC alpha_lyr_stis, Bohlin & Gilliland 2004), m_ref = Vega's magnitude
//         in the system (0 by definition of the pure Vega system; Bessell & Murphy 2012 use V = 0.03).
// The zero point N₀ = ∫ f_λ,ref T λ/(hc) dλ is the photon rate per m² of magnitude 0 through T; a source of
// magnitude m delivers 10^{-0.4 (m − m_ref)} N₀ in the band.
#include "radchain/constants.hpp"
#include "radchain/spectrum.hpp"

#include <algorithm>
#include <cmath>

namespace radchain::physics {

// AB and ST zero points in SI: W m⁻² Hz⁻¹ and W m⁻² m⁻¹ (1 erg s⁻¹ cm⁻² Hz⁻¹ = 1e-3 W m⁻² Hz⁻¹;
// 1 erg s⁻¹ cm⁻² Å⁻¹ = 1e7 W m⁻² m⁻¹).
inline const double ab_zero_f_nu_W_m2_Hz = std::pow(10.0, -0.4 * 48.60) * 1e-3;
inline const double st_zero_f_lambda_W_m3 = std::pow(10.0, -0.4 * 21.10) * 1e7;

// A log-spaced wavelength grid over [lo, hi] with `per_e_fold` points per factor e (at least 2 points in all), its
// ends exactly lo and hi (exp(log(x)) may round).
inline Eigen::ArrayXd log_wavelength_grid(double lo_m, double hi_m, double per_e_fold) {
  const int n = std::max(2, static_cast<int>(std::ceil(std::log(hi_m / lo_m) * per_e_fold)) + 1);
  Eigen::ArrayXd grid = Eigen::ArrayXd::LinSpaced(n, std::log(lo_m), std::log(hi_m)).exp();
  grid(0) = lo_m, grid(n - 1) = hi_m;
  return grid;
}

// The AB and ST reference spectra (f_λ, W m⁻² m⁻¹) sampled on n log-spaced points over [lo, hi]. The ST spectrum
// is flat in f_λ but still sampled densely: a photon count weights it by λ/(hc), which varies across every segment
// of a coarse bandpass table, and a 2-point constant would add no nodes, so the trapezoid would average the weight
// only between the table's points (1.3e-3 off for the ST zero point through Bessell R; here ~1e-9).
inline Spectrum ab_reference_spectrum(double lo_m, double hi_m, int n = 4001) {
  Eigen::ArrayXd grid = Eigen::ArrayXd::LinSpaced(n, std::log(lo_m), std::log(hi_m)).exp();
  grid(0) = lo_m, grid(n - 1) = hi_m;
  return Spectrum::sampled(grid, [](double l) { return ab_zero_f_nu_W_m2_Hz * constants::speed_of_light_m_s / (l * l); },
                           "W m-2 m-1");
}
inline Spectrum st_reference_spectrum(double lo_m, double hi_m, int n = 4001) {
  Eigen::ArrayXd grid = Eigen::ArrayXd::LinSpaced(n, std::log(lo_m), std::log(hi_m)).exp();
  grid(0) = lo_m, grid(n - 1) = hi_m;
  return Spectrum::sampled(grid, [](double) { return st_zero_f_lambda_W_m3; }, "W m-2 m-1");
}

// An SED without a table of its own (flat in f_ν or in f_λ) is the shape of a whole source, not of the band that
// normalises it: it spans every band a chain may integrate, from the far UV to the far infrared. 2000 log-spaced
// points per factor e (relative spacing 5e-4: the trapezoid's error on λ⁻¹ is ~2e-8). Built once, shared.
inline constexpr double untabulated_sed_min_wavelength_m = 10e-9, untabulated_sed_max_wavelength_m = 1e-3;
inline const Spectrum& flat_f_nu_sed() {
  static const Spectrum sed = [] {
    const Eigen::ArrayXd grid = log_wavelength_grid(untabulated_sed_min_wavelength_m, untabulated_sed_max_wavelength_m, 2000);
    return Spectrum::sampled(grid, [](double l) { return ab_zero_f_nu_W_m2_Hz * constants::speed_of_light_m_s / (l * l); },
                             "W m-2 m-1");
  }();
  return sed;
}
inline const Spectrum& flat_f_lambda_sed() {
  static const Spectrum sed = [] {
    const Eigen::ArrayXd grid = log_wavelength_grid(untabulated_sed_min_wavelength_m, untabulated_sed_max_wavelength_m, 2000);
    return Spectrum::sampled(grid, [](double) { return st_zero_f_lambda_W_m3; }, "W m-2 m-1");
  }();
  return sed;
}

// Photons s⁻¹ m⁻² of a spectral irradiance f_λ (W m⁻² m⁻¹) through the bandpass T over T's whole table.
inline double band_photon_rate(const Spectrum& f_lambda, const Spectrum& bandpass) {
  return band_integral({&f_lambda, &bandpass}, bandpass.min_wavelength_m(), bandpass.max_wavelength_m(), Weight::photons);
}

// The magnitude of f_λ in the system whose zero point through the same bandpass is `zero_point_rate`.
inline double band_magnitude(double photon_rate, double zero_point_rate, double reference_magnitude = 0.0) {
  return -2.5 * std::log10(photon_rate / zero_point_rate) + reference_magnitude;
}

// Photon-weighted mean wavelength-density of the zero point: N₀ / ∫ T dλ (photons s⁻¹ m⁻² m⁻¹), the figure
// tables quote as "photons cm⁻² s⁻¹ Å⁻¹" (Bessell, Castelli & Plez 1998, Table A2).
inline double zero_point_photon_density(double zero_point_rate, const Spectrum& bandpass) {
  return zero_point_rate / bandpass.integral();
}

}  // namespace radchain::physics

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

#include <cmath>

namespace radchain::physics {

// AB and ST zero points in SI: W m⁻² Hz⁻¹ and W m⁻² m⁻¹ (1 erg s⁻¹ cm⁻² Hz⁻¹ = 1e-3 W m⁻² Hz⁻¹;
// 1 erg s⁻¹ cm⁻² Å⁻¹ = 1e7 W m⁻² m⁻¹).
inline const double ab_zero_f_nu_W_m2_Hz = std::pow(10.0, -0.4 * 48.60) * 1e-3;
inline const double st_zero_f_lambda_W_m3 = std::pow(10.0, -0.4 * 21.10) * 1e7;

// The AB and ST reference spectra (f_λ, W m⁻² m⁻¹) sampled on n points over [lo, hi] (log-spaced).
inline Spectrum ab_reference_spectrum(double lo_m, double hi_m, int n = 4001) {
  Eigen::ArrayXd grid = Eigen::ArrayXd::LinSpaced(n, std::log(lo_m), std::log(hi_m)).exp();
  grid(0) = lo_m, grid(n - 1) = hi_m;  // exactly the limits (exp(log(x)) may round)
  return Spectrum::sampled(grid, [](double l) { return ab_zero_f_nu_W_m2_Hz * constants::speed_of_light_m_s / (l * l); },
                           "W m-2 m-1");
}
inline Spectrum st_reference_spectrum(double lo_m, double hi_m) {
  return Spectrum::constant(st_zero_f_lambda_W_m3, "W m-2 m-1", lo_m, hi_m);
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

#pragma once
// Planck's law and blackbody band fractions. All wavelengths in metres, temperatures in kelvin.
// Source: M. Planck (1901); closed forms as in Wolfe & Zissis, The Infrared Handbook (1978), ch. 1;
// the band-fraction series in Widger & Woodall, Bull. Am. Meteorol. Soc. 57 (1976) 1217.
#include "radchain/constants.hpp"

namespace radchain::physics {

// Spectral radiance L_λ = c1L / λ^5 / (exp(c2/(λT)) - 1), W m^-2 sr^-1 m^-1. `c2` selects the temperature
// scale convention (constants::second_radiation_*); c1L stays exact SI.
double planck_spectral_radiance(double wavelength_m, double temperature_K,
                                double c2_m_K = constants::second_radiation_m_K);
// Spectral exitance M_λ = π L_λ, W m^-2 m^-1.
double planck_spectral_exitance(double wavelength_m, double temperature_K,
                                double c2_m_K = constants::second_radiation_m_K);
// Photon spectral exitance M_qλ = M_λ λ / (h c), photons s^-1 m^-2 m^-1.
double planck_photon_spectral_exitance(double wavelength_m, double temperature_K);
// Total exitance σ T^4 (Stefan-Boltzmann).
double blackbody_exitance(double temperature_K);
// Wavelength of maximum M_λ (Wien): b / T.
double wien_peak_wavelength_m(double temperature_K);

// Fraction of σT^4 emitted below λ: F(0→λT) = (15/π^4) Σ_n e^{-nx}/n (x^3 + 3x^2/n + 6x/n^2 + 6/n^3),
// x = c2/(λT); converged to 1e-15.
double blackbody_fraction_below(double wavelength_m, double temperature_K,
                                double c2_m_K = constants::second_radiation_m_K);

}  // namespace radchain::physics

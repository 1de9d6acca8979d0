#pragma once
// A point target that moves across the focal plane during the exposure: its image is the PSF
// convolved with a line segment of length L = ω t f' (angular rate ω relative to where the telescope points,
// exposure t, focal length f'). With sidereal tracking the target streaks (ω = its rate against the stars); with
// rate tracking the target stays a point and the stars streak by the same length.
//   Streaked Gaussian on the pixel grid (the streak along a pixel row, centred on a pixel centre):
//     f_ij = s_i g_j,  g_j = Φ((j+½)/σ) − Φ((j−½)/σ)                       (the static column profile)
//     s_i = (1/L) ∫_{−L/2}^{L/2} [Φ((i+½−u)/σ) − Φ((i−½−u)/σ)] du
//         = (σ/L) [G((c₊+L/2)/σ) − G((c₊−L/2)/σ) − G((c₋+L/2)/σ) + G((c₋−L/2)/σ)],  c± = i ± ½,
//     G(z) = ∫Φ = z Φ(z) + φ(z)   (the antiderivative of the normal CDF: d/dz [zΦ + φ] = Φ + zφ − zφ = Φ).
//   Noise-equivalent area of PSF-weighted photometry of the streak (the matched filter along the streak):
//     n_eff = 1 / Σ f_ij² (King 1983, PASP 95, 163; LSST SMTN-002), the same definition as the static PSF's
//     (physics/emva1288.hpp); L → 0 gives the static value.
//   Trailing loss of a background-limited source: SNR ∝ 1/√n_eff, so the magnitude that keeps the SNR moves by
//     Δm = 1.25 lg(n_eff,streak / n_eff,static)
//   (the "SNR trailing loss" dmagTrail of Jones et al. 2018, Icarus 303, 181, fitted there as
//   1.25 lg(1 + a x²/(1 + b x)), x = ω t / FWHM, for a well-sampled PSF; tests/core/physics/streak_test.cpp
//   compares with the fit's coefficients as LSST's code uses them).
// The streak is taken along a pixel row (a diagonal streak samples the pixel grid slightly differently; for a
// PSF of a few pixels the difference is the pixel term p²/12 per axis).
#include "radchain/physics/emva1288.hpp"

#include <cmath>
#include <numbers>

namespace radchain::physics {

// G(z) = ∫_{−∞}^{z} Φ(u) du = z Φ(z) + φ(z).
inline double integrated_normal_cdf(double z) {
  const double cdf = 0.5 * std::erfc(-z / std::numbers::sqrt2);
  const double pdf = std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi);
  return z * cdf + pdf;
}

// s_i: the fraction of a Gaussian PSF (σ in pixels) smeared uniformly over `length_px` along the row that falls
// in pixel column i, the streak centred `offset_px` off pixel 0's centre. length 0: the static fraction.
inline double streaked_gaussian_pixel_fraction(int i, double sigma_px, double length_px, double offset_px = 0.0) {
  if (length_px == 0.0) return gaussian_pixel_fraction(i, sigma_px, offset_px);
  const double h = 0.5 * length_px;
  auto smeared_cdf = [&](double c) {  // ∫_{−L/2}^{L/2} Φ((c − u)/σ) du / L
    return sigma_px / length_px * (integrated_normal_cdf((c + h) / sigma_px) - integrated_normal_cdf((c - h) / sigma_px));
  };
  return smeared_cdf(i + 0.5 - offset_px) - smeared_cdf(i - 0.5 - offset_px);
}

// n_eff = 1/Σ f_ij² of a Gaussian PSF of FWHM `fwhm_px` streaked over `length_px` along a row, on the pixel grid,
// centred on a pixel. length 0: exactly gaussian_noise_equivalent_area_px(fwhm_px).
inline double streak_noise_equivalent_area_px(double fwhm_px, double length_px) {
  if (length_px == 0.0) return gaussian_noise_equivalent_area_px(fwhm_px);
  const double sigma = fwhm_px / (2.0 * std::sqrt(2.0 * std::numbers::ln2));
  const int across = static_cast<int>(std::ceil(8.0 * sigma)) + 1;
  const int along = static_cast<int>(std::ceil(8.0 * sigma + 0.5 * length_px)) + 1;
  double rows = 0.0, columns = 0.0;
  for (int j = -across; j <= across; ++j) columns += std::pow(gaussian_pixel_fraction(j, sigma), 2);
  for (int i = -along; i <= along; ++i) rows += std::pow(streaked_gaussian_pixel_fraction(i, sigma, length_px), 2);
  return 1.0 / (rows * columns);
}

// The brightest pixel's fraction of a streak centred on a pixel (for saturation): s_0 g_0.
inline double streak_peak_pixel_fraction(double fwhm_px, double length_px) {
  const double sigma = fwhm_px / (2.0 * std::sqrt(2.0 * std::numbers::ln2));
  return streaked_gaussian_pixel_fraction(0, sigma, length_px) * gaussian_pixel_fraction(0, sigma);
}

// Trailing loss of a background-limited source in magnitudes: 1.25 lg(n_eff,streak / n_eff,static).
inline double trailing_loss_mag(double streak_neff, double static_neff) {
  return 1.25 * std::log10(streak_neff / static_neff);
}

}  // namespace radchain::physics

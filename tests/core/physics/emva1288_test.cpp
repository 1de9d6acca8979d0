// EMVA 1288 noise model and PSF-weighted photometry (physics/emva1288.hpp) against hand computation from the
// standard's equations and a brute-force 2D integration of the PSF over pixels (n_eff = 1/Σ f_i², King 1983).
#include "radchain/physics/emva1288.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace {
using namespace radchain::physics;

// EMVA 1288 R4.0 eq. 6 with §2.4's spatial terms: μ_e = 1000 e-, σ_d0 = 10 e-, K = 0.1 DN/e-: σ_q²/K² = 100/12,
// variance 1000 + 100 + 8.333 = 1108.33, SNR = 30.037; with μ_I t = 50 e-, DSNU 3 e-, PRNU 1 %:
// 1000 + 100 + 50 + 8.333 + 9 + 100 = 1267.33, SNR = 28.090.
TEST(PhysicsEmva1288, PixelSnrByHand) {
  EXPECT_NEAR(emva_quantisation_variance_e2(0.1), 100.0 / 12.0, 1e-12);
  EXPECT_NEAR(emva_pixel_snr(1000, 10, 0, 1, 0.1), 1000 / std::sqrt(1108.0 + 1.0 / 3.0), 1e-9);
  EXPECT_NEAR(emva_pixel_snr(1000, 10, 5, 10, 0.1, 3, 0.01), 1000 / std::sqrt(1267.0 + 1.0 / 3.0), 1e-9);
}

// n_eff of a pixelated Gaussian against a brute-force midpoint integral of the 2D Gaussian over each pixel.
double brute_force_neff(double fwhm_px, double offset_x = 0, double offset_y = 0) {
  const double sigma = fwhm_px / (2 * std::sqrt(2 * std::numbers::ln2));
  const int half = static_cast<int>(8 * sigma) + 2, sub = 80;
  double sum_sq = 0, total = 0;
  for (int i = -half; i <= half; ++i)
    for (int j = -half; j <= half; ++j) {
      double f = 0;
      for (int a = 0; a < sub; ++a)
        for (int b = 0; b < sub; ++b) {
          const double x = i - 0.5 + (a + 0.5) / sub - offset_x, y = j - 0.5 + (b + 0.5) / sub - offset_y;
          f += std::exp(-(x * x + y * y) / (2 * sigma * sigma)) / (2 * std::numbers::pi * sigma * sigma) / (sub * sub);
        }
      sum_sq += f * f;
      total += f;
    }
  EXPECT_NEAR(total, 1.0, 1e-4);
  return 1.0 / sum_sq;
}

// The sum takes each column edge's erf once (columns share edges and are symmetric): the textbook sum of
// [Φ(i + ½) − Φ(i − ½)]² over every column, two erfs each, to rounding, over FWHMs from 0.05 to 40 pixels.
TEST(PhysicsEmva1288, NoiseEquivalentAreaEqualsTheColumnByColumnSum) {
  for (int k = 0; k <= 200; ++k) {
    const double fwhm = 0.05 * std::pow(800.0, k / 200.0);
    const double sigma = fwhm / (2 * std::sqrt(2 * std::numbers::ln2));
    const int half = static_cast<int>(std::ceil(8 * sigma)) + 1;
    double sum = 0;
    for (int i = -half; i <= half; ++i) {
      const double g = gaussian_pixel_fraction(i, sigma);
      sum += g * g;
    }
    EXPECT_NEAR(gaussian_noise_equivalent_area_px(fwhm) * sum * sum, 1.0, 1e-13) << fwhm;
  }
}

TEST(PhysicsEmva1288, NoiseEquivalentAreaAgainstNumericalPsfIntegration) {
  for (double fwhm : {0.8, 2.0, 4.15})
    EXPECT_NEAR(gaussian_noise_equivalent_area_px(fwhm) / brute_force_neff(fwhm), 1.0, 2e-4) << fwhm;
  // Well sampled: 4π σ² (= 2.266 FWHM², SMTN-002) plus the pixel's own variance 1/12 per axis: 4π(σ² + 1/12).
  const double fwhm = 10.0, sigma = fwhm / (2 * std::sqrt(2 * std::numbers::ln2));
  EXPECT_NEAR(gaussian_noise_equivalent_area_px(fwhm) / (4 * std::numbers::pi * (sigma * sigma + 1.0 / 12)), 1.0, 1e-3);
  EXPECT_NEAR(4 * std::numbers::pi * sigma * sigma / (fwhm * fwhm), 2.266, 5e-4);
  // Undersampled: everything in one pixel, n_eff → 1.
  EXPECT_NEAR(gaussian_noise_equivalent_area_px(0.05), 1.0, 1e-6);
}

// The continuous Gaussian's 1/∫∫f² by numerical integration (independent of the closed form): 4πσ² = 2.266 FWHM².
TEST(PhysicsEmva1288, ContinuousNoiseEquivalentArea) {
  for (double fwhm : {0.5, 2.0, 4.15, 10.0}) {
    const double sigma = fwhm / (2 * std::sqrt(2 * std::numbers::ln2));
    double integral = 0;  // ∫ g(x)² dx of the normalised 1-D Gaussian, midpoint rule over ±10σ
    const int steps = 20000;
    const double dx = 20 * sigma / steps;
    for (int i = 0; i < steps; ++i) {
      const double x = -10 * sigma + (i + 0.5) * dx;
      const double g = std::exp(-x * x / (2 * sigma * sigma)) / (sigma * std::sqrt(2 * std::numbers::pi));
      integral += g * g * dx;
    }
    EXPECT_NEAR(gaussian_continuous_noise_equivalent_area_px(fwhm) * integral * integral, 1.0, 1e-9) << fwhm;
  }
  EXPECT_NEAR(gaussian_continuous_noise_equivalent_area_px(1.0), 2.266, 5e-4);  // SMTN-002's coefficient
  // The pixel-sampled n_eff tends to it (plus the pixel's 1/12 per axis) for FWHM ≫ 1.
  EXPECT_NEAR(gaussian_noise_equivalent_area_px(40.0) / gaussian_continuous_noise_equivalent_area_px(40.0), 1.0, 2e-3);
}

TEST(PhysicsEmva1288, PeakPixelFraction) {
  // erf(1/(2√2 σ))²; FWHM 2 px: σ = 0.8493, erf(0.41628)² = 0.44375² = 0.19691.
  EXPECT_NEAR(gaussian_peak_pixel_fraction(2.0), std::pow(std::erf(1 / (2 * std::sqrt(2.0) * 0.849322)), 2), 1e-6);
  EXPECT_NEAR(gaussian_peak_pixel_fraction(1e-3), 1.0, 1e-12);
}

TEST(PhysicsEmva1288, SeeingWithAirmassAndDiffraction) {
  EXPECT_NEAR(seeing_at_airmass(0.7, 2.0), 0.7 * 1.515717, 1e-6);  // 2^0.6 = 1.515717
  EXPECT_NEAR(diffraction_fwhm_rad(500e-9, 1.0), 5.14e-7, 1e-15);
}

}  // namespace

// A streaked point image (physics/streak.hpp): n_eff of the Gaussian PSF convolved with a line segment on the
// pixel grid against (1) a brute-force 2D midpoint integration over pixels and along the streak, (2) the exact
// continuous closed form for a well-sampled PSF, (3) the published trailing-loss fit of Jones et al. 2018, and
// the limit of zero length (the static n_eff exactly).
#include "radchain/physics/streak.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace {
using namespace radchain::physics;

double sigma_of(double fwhm) { return fwhm / (2 * std::sqrt(2 * std::numbers::ln2)); }

// f_ij by brute force: the 2D Gaussian density summed at sub×sub midpoints of each pixel and at `steps`
// midpoints along the streak (a row through pixel 0's centre), nothing separable or closed-form used.
double brute_force_streak_neff(double fwhm_px, double length_px) {
  const double sigma = sigma_of(fwhm_px);
  const int across = static_cast<int>(6 * sigma) + 2, along = static_cast<int>(6 * sigma + length_px / 2) + 2;
  const int sub = 24, steps = 96;
  double sum_sq = 0, total = 0;
  for (int i = -along; i <= along; ++i)
    for (int j = -across; j <= across; ++j) {
      double f = 0;
      for (int k = 0; k < steps; ++k) {
        const double u = -length_px / 2 + (k + 0.5) * length_px / steps;
        for (int a = 0; a < sub; ++a)
          for (int b = 0; b < sub; ++b) {
            const double x = i - 0.5 + (a + 0.5) / sub - u, y = j - 0.5 + (b + 0.5) / sub;
            f += std::exp(-(x * x + y * y) / (2 * sigma * sigma));
          }
      }
      f /= 2 * std::numbers::pi * sigma * sigma * sub * sub * steps;
      sum_sq += f * f;
      total += f;
    }
  EXPECT_NEAR(total, 1.0, 1e-4);
  return 1.0 / sum_sq;
}

TEST(PhysicsStreak, NoiseEquivalentAreaAgainstNumericalIntegration) {
  // FWHM 2 px (a typical sampling) streaked over 0.5, 3 and 9 pixels. The midpoint rules (1/24 px, L/96) carry
  // their own error ≈ h²/(24σ²) ≈ 1e-4 (with 1/12 px it is 4× larger: 5-7e-4, as measured).
  for (double length : {0.5, 3.0, 9.0})
    EXPECT_NEAR(streak_noise_equivalent_area_px(2.0, length) / brute_force_streak_neff(2.0, length), 1.0, 3e-4) << length;
}

TEST(PhysicsStreak, FractionsSumToOne) {
  const double sigma = sigma_of(2.5);
  for (double length : {0.0, 0.3, 7.0, 40.0}) {
    double sum = 0;
    for (int i = -60; i <= 60; ++i) sum += streaked_gaussian_pixel_fraction(i, sigma, length, 0.3);
    EXPECT_NEAR(sum, 1.0, 1e-12) << length;
  }
}

// Continuous limit (FWHM ≫ pixel): ∫ s(x)² dx of a top hat of length L smoothed by a Gaussian σ is
//   (1/L²) ∫_{−L}^{L} (L − |d|) φ_τ(d) dd = [L (2Φ(L/τ) − 1) − 2τ² (φ_τ(0) − φ_τ(L))] / L²,  τ = √2 σ
// (the difference of two independent positions is N(0, 2σ²), weighted by the triangle of their overlap), and
// ∫ g² = 1/(2√π σ) across; the pixel adds its own variance 1/12 per axis: σ² → σ² + 1/12.
double continuous_streak_neff(double fwhm_px, double length_px) {
  const double sigma = std::sqrt(std::pow(sigma_of(fwhm_px), 2) + 1.0 / 12.0), tau = std::numbers::sqrt2 * sigma;
  auto phi = [&](double d) { return std::exp(-d * d / (2 * tau * tau)) / (tau * std::sqrt(2 * std::numbers::pi)); };
  const double cdf = 0.5 * std::erfc(-length_px / tau / std::numbers::sqrt2);
  const double along = (length_px * (2 * cdf - 1) - 2 * tau * tau * (phi(0) - phi(length_px))) / (length_px * length_px);
  const double across = 1.0 / (2 * std::sqrt(std::numbers::pi) * sigma);
  return 1.0 / (along * across);
}

TEST(PhysicsStreak, WellSampledAgainstContinuousClosedForm) {
  for (double length : {1.0, 10.0, 40.0, 200.0})
    EXPECT_NEAR(streak_noise_equivalent_area_px(20.0, length) / continuous_streak_neff(20.0, length), 1.0, 1e-6) << length;
}

// Jones et al. 2018 (Icarus 303, 181), the SNR trailing loss fitted as dmagTrail = 1.25 lg(1 + a x²/(1 + b x)),
// x = v t / FWHM; a = 0.761, b = 1.162 as LSST's moving-object code applies it (github.com/lsst-sims/
// legacy_sims_movingObjects @ 1ab1c43b, python/lsst/sims/movingObjects/baseObs.py, calcTrailingLosses; the
// paper's printed coefficients could not be read here). A fit to trailed sources, not an exact law: for a
// Gaussian PSF it agrees within 0.06 mag over x ≤ 20 (largest near x = 1, where the Gaussian loses 0.108 mag and
// the fit says 0.164), and for long trails both tend to 1.25 lg(c x) with c = 2√(ln2/π) = 0.664 (Gaussian)
// against a/b = 0.655 (fit): 0.008 mag apart at x = 20.
TEST(PhysicsStreak, TrailingLossAgainstJones2018Fit) {
  const double fwhm = 20.0, neff0 = streak_noise_equivalent_area_px(fwhm, 0.0);
  double worst = 0;
  for (double x = 0.05; x <= 20.0; x += 0.05) {
    const double jones = 1.25 * std::log10(1 + 0.761 * x * x / (1 + 1.162 * x));
    worst = std::max(worst, std::abs(trailing_loss_mag(streak_noise_equivalent_area_px(fwhm, x * fwhm), neff0) - jones));
  }
  EXPECT_LT(worst, 0.06);
  EXPECT_GT(worst, 0.04);  // the fit's shape really differs near x = 1 (documented above): not a test that cannot fail
  const double at20 = trailing_loss_mag(streak_noise_equivalent_area_px(fwhm, 20 * fwhm), neff0);
  EXPECT_NEAR(at20, 1.25 * std::log10(1 + 0.761 * 400 / (1 + 1.162 * 20)), 0.01);
  // Long-trail asymptote of the Gaussian: n_eff → L · 2√π σ' / (1 − 2σ'/(√π L)) (the closed form above for L ≫ σ'; the
  // second factor is the two blurred ends), i.e. Δm → 1.25 lg(x FWHM / (2√π σ')) (pixel term σ'² = σ² + 1/12).
  const double sigma = std::sqrt(std::pow(sigma_of(fwhm), 2) + 1.0 / 12.0), length = 2000.0;
  const double asymptote = length * 2 * std::sqrt(std::numbers::pi) * sigma / (1 - 2 * sigma / (std::sqrt(std::numbers::pi) * length));
  EXPECT_NEAR(streak_noise_equivalent_area_px(fwhm, length) / asymptote, 1.0, 1e-4);
}

TEST(PhysicsStreak, ZeroLengthIsTheStaticCase) {
  for (double fwhm : {0.8, 2.0, 4.15}) {
    EXPECT_EQ(streak_noise_equivalent_area_px(fwhm, 0.0), gaussian_noise_equivalent_area_px(fwhm));
    EXPECT_EQ(streak_peak_pixel_fraction(fwhm, 0.0), gaussian_peak_pixel_fraction(fwhm));
    // and continuously so: 1e-6 px of motion changes n_eff by less than 1e-9
    EXPECT_NEAR(streak_noise_equivalent_area_px(fwhm, 1e-6) / gaussian_noise_equivalent_area_px(fwhm), 1.0, 1e-9);
  }
  EXPECT_EQ(trailing_loss_mag(5.0, 5.0), 0.0);
}

TEST(PhysicsStreak, PeakFractionFallsAsOneOverLength) {
  // A streak much longer than the PSF spreads the column profile over L pixels: s_0 → 1/L.
  const double fwhm = 2.0, g0 = gaussian_pixel_fraction(0, sigma_of(fwhm));
  EXPECT_NEAR(streak_peak_pixel_fraction(fwhm, 100.0) / (g0 / 100.0), 1.0, 1e-9);
  EXPECT_LT(streak_peak_pixel_fraction(fwhm, 3.0), gaussian_peak_pixel_fraction(fwhm));
}

}  // namespace

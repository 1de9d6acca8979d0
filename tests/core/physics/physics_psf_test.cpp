// physics/psf.hpp against independent references: Born & Wolf's encircled energies at the Airy dark rings
// (83.8 %, 91.0 %, 93.8 %), the zeros of J1, brute-force integration of the PSF itself (radial for the
// encircled energy, Cartesian over the square for the ensquared energy), and the Gaussian's erf product.
#include "radchain/physics/psf.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace {
using namespace radchain::physics;

constexpr double um = 1e-6;
constexpr double pi = std::numbers::pi;
constexpr double lambda = 0.6 * um, f_number = 3.0, lambda_n = lambda * f_number;

// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n), for the brute-force references.
void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(n, 0), w.assign(n, 0);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(pi * (i + 0.75) / (n + 0.5)), dp = 0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1, p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    x[i] = z, w[i] = 2.0 / ((1 - z * z) * dp * dp);
  }
}

// ∫ f over [a, b] by composite Gauss-Legendre (panels × 20 nodes).
template <class F>
double composite(F f, double a, double b, int panels) {
  std::vector<double> x, w;
  gauss_legendre(20, x, w);
  double sum = 0;
  const double h = (b - a) / panels;
  for (int p = 0; p < panels; ++p)
    for (int i = 0; i < 20; ++i) sum += 0.5 * h * w[i] * f(a + p * h + 0.5 * h * (x[i] + 1));
  return sum;
}

TEST(PhysicsPsf, AiryIntensityAndFirstDarkRing) {
  EXPECT_DOUBLE_EQ(airy_normalized_intensity(0.0), 1.0);
  // First zero of J1: j_{1,1} = 3.8317059702 (Abramowitz & Stegun Table 9.5); 1.21967 λN.
  EXPECT_NEAR(airy_first_dark_ring_v(0.0), 3.8317059702, 1e-9);
  EXPECT_NEAR(airy_first_dark_ring_radius_m(lambda, f_number) / lambda_n, 1.2196698912, 1e-9);
  EXPECT_NEAR(airy_normalized_intensity(3.8317059702), 0.0, 1e-18);
  // [2 J1(v)/v]² at v = 1.616340 is one half (the FWHM is 1.02899 λN).
  EXPECT_NEAR(airy_normalized_intensity(1.6163399), 0.5, 1e-6);
  // An obscuration moves the first dark ring inwards and the amplitude is zero there.
  for (double eps : {0.2, 0.3, 0.5}) {
    const double v = airy_first_dark_ring_v(eps);
    EXPECT_LT(v, 3.8317);
    EXPECT_NEAR(airy_normalized_intensity(v, eps), 0.0, 1e-20);
  }
  EXPECT_LT(airy_first_dark_ring_v(0.5), airy_first_dark_ring_v(0.3));
  EXPECT_THROW(airy_normalized_intensity(1.0, 1.0), std::domain_error);
}

TEST(PhysicsPsf, AiryEncircledEnergyAtTheDarkRings) {
  // Born & Wolf §8.5.2: 83.8 %, 91.0 %, 93.8 % inside the first three dark rings (zeros of J1).
  EXPECT_NEAR(airy_encircled_energy_v(3.8317059702), 0.838, 5e-4);
  EXPECT_NEAR(airy_encircled_energy_v(7.0155866698), 0.910, 5e-4);
  EXPECT_NEAR(airy_encircled_energy_v(10.1734681351), 0.938, 5e-4);
  EXPECT_EQ(airy_encircled_energy_v(0.0), 0.0);
}

TEST(PhysicsPsf, EncircledEnergyIsTheIntegralOfThePsf) {
  // 2π ∫0^R p(r) r dr by brute force, unobscured and annular, against the closed forms.
  for (double eps : {0.0, 0.3, 0.5}) {
    for (double r_over : {0.5, 1.22, 3.0, 7.5}) {
      const double radius = r_over * lambda_n;
      const double brute = composite([&](double r) { return 2 * pi * r * airy_psf_per_m2(r, lambda, f_number, eps); },
                                     0.0, radius, 200);
      EXPECT_NEAR(airy_encircled_energy(radius, lambda, f_number, eps), brute, 1e-10) << "eps " << eps << " R " << r_over;
    }
  }
  // The peak: E A/(λ f')² per unit energy, i.e. π (1 − ε²)/(4 (λN)²).
  EXPECT_NEAR(airy_psf_per_m2(0, lambda, f_number, 0.3) * lambda_n * lambda_n, pi * (1 - 0.09) / 4, 1e-15);
  // All of the energy at last (the annular cross term tends to ε/2); the tail falls as 2/(π v) for ε = 0.
  EXPECT_NEAR(airy_encircled_energy_v(2000.0, 0.3), 1.0, 2e-3);
  EXPECT_NEAR(airy_encircled_energy_v(2000.0, 0.0), 1.0 - 2.0 / (pi * 2000.0), 1e-4);
}

TEST(PhysicsPsf, AiryEnsquaredEnergyIsTheIntegralOverTheSquare) {
  // Cartesian product Gauss-Legendre over the square, 8 × 8 panels of 20² nodes: independent of the polar
  // reduction the library uses.
  for (double eps : {0.0, 0.3}) {
    for (double side_over : {0.5, 1.0, 2.44, 5.0}) {
      const double side = side_over * lambda_n, h = side / 2;
      const double brute = composite(
          [&](double x) {
            return composite([&](double y) { return airy_psf_per_m2(std::hypot(x, y), lambda, f_number, eps); }, -h, h, 8);
          },
          -h, h, 8);
      EXPECT_NEAR(airy_ensquared_energy(side, lambda, f_number, eps), brute, 1e-9) << "eps " << eps << " side " << side_over;
    }
  }
  // A tiny square holds the peak times its area; a large one everything, and more than the inscribed circle.
  const double tiny = 1e-3 * lambda_n;
  EXPECT_NEAR(airy_ensquared_energy(tiny, lambda, f_number) / (airy_psf_per_m2(0, lambda, f_number) * tiny * tiny), 1.0, 1e-6);
  EXPECT_NEAR(airy_ensquared_energy(400 * lambda_n, lambda, f_number), 1.0, 2e-3);
  const double side = 2.44 * lambda_n;
  EXPECT_GT(airy_ensquared_energy(side, lambda, f_number), airy_encircled_energy(side / 2, lambda, f_number));
  EXPECT_LT(airy_ensquared_energy(side, lambda, f_number), airy_encircled_energy(side / std::sqrt(2.0), lambda, f_number));
}

TEST(PhysicsPsf, Gaussian) {
  const double fwhm = 20 * um;
  const double sigma = gaussian_sigma_from_fwhm(fwhm);
  EXPECT_NEAR(fwhm / sigma, 2.3548200450309493, 1e-14);
  // Inside the half-maximum circle r = FWHM/2: 1 − e^{-ln 2} = 0.5.
  EXPECT_NEAR(gaussian_encircled_energy(fwhm / 2, fwhm), 0.5, 1e-15);
  for (double side_over : {0.3, 1.0, 2.0, 4.0}) {
    const double side = side_over * fwhm;
    const double e = std::erf(side / (2 * std::sqrt(2.0) * sigma));
    EXPECT_NEAR(gaussian_ensquared_energy(side, fwhm), e * e, 1e-15);
    // The polar reduction gives the same for the Gaussian's encircled energy: a check of the reduction itself.
    EXPECT_NEAR(ensquared_from_encircled([&](double r) { return gaussian_encircled_energy(r, fwhm); }, side), e * e, 1e-11);
  }
  EXPECT_EQ(ensquared_from_encircled([](double) { return 1.0; }, 0.0), 0.0);
}

// n_eff of a pixel-sampled Airy PSF (King 1983's 1/Σ f²) two independent ways: for p ≤ λN/2 in the frequency domain
// (Poisson summation, exact there) and pixel by pixel from the closed-form encircled energy; they must agree where
// both apply, for a clear and an obscured pupil. Coarse pixels: the central pixel's share is the ensquared energy,
// and n_eff lies between 1/f₀² (all other pixels dark) and 1/(f₀² + (1 − f₀)²) (the rest in one pixel).
TEST(AiryNoiseEquivalentArea, FrequencyDomainAndPixelSumsAgree) {
  const double lambda = 0.6e-6, f_number = 10.0, lambda_n = lambda * f_number;
  for (double eps : {0.0, 0.3})
    for (double p : {0.4, 0.5}) {
      const double spectral = airy_noise_equivalent_area_px(p * lambda_n, lambda, f_number, eps);
      const double pixels = airy_noise_equivalent_area_by_pixels(p * lambda_n, lambda, f_number, eps);
      EXPECT_NEAR(pixels / spectral, 1.0, 1e-6) << "eps " << eps << " p " << p << ": " << spectral << " vs " << pixels;
    }
}

TEST(AiryNoiseEquivalentArea, LimitsAndBounds) {
  const double lambda = 0.8e-6, f_number = 1.4, lambda_n = lambda * f_number;
  // Fine pixels: n_eff p² tends to the continuous 1/∫h²; halving the pitch quadruples n_eff but for the pixel's
  // own blur, which raises n_eff p² at the coarser pitch (so the ratio stays below 4, within 2 %).
  const double fine = airy_noise_equivalent_area_px(0.1 * lambda_n, lambda, f_number);
  const double finer = airy_noise_equivalent_area_px(0.05 * lambda_n, lambda, f_number);
  EXPECT_NEAR(finer / fine, 4.0, 0.08);
  EXPECT_LT(finer / fine, 4.0);
  for (double eps : {0.0, 0.3})
    for (double p : {2.0, 13.4}) {  // 13.4: a TESS-like 15 µm pixel at f/1.4, 0.8 µm
      const double f0 = airy_ensquared_energy(p * lambda_n, lambda, f_number, eps);
      const double neff = airy_noise_equivalent_area_px(p * lambda_n, lambda, f_number, eps);
      EXPECT_LT(neff, 1.0 / (f0 * f0)) << p;
      EXPECT_GT(neff, 1.0 / (f0 * f0 + (1 - f0) * (1 - f0))) << p;
    }
  EXPECT_THROW(airy_noise_equivalent_area_px(0.0, lambda, f_number), std::domain_error);
}

}  // namespace

// MTF models (radchain/physics/mtf.hpp) against independent references: closed forms, a numerical
// autocorrelation of the pupil, O'Neill's (1956) closed form for the annulus, Boost bisection and brute-force
// scans for the roots, and the numbers Kolobrodov 1996 prints (eqs. 11, 12, 15).
#include "radchain/physics/mtf.hpp"
#include "mtf_references.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <initializer_list>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

namespace {

using namespace radchain::physics;
constexpr double pi = std::numbers::pi;
constexpr double per_mm = 1e3;  // 1 mm^-1 in m^-1
constexpr double um = 1e-6;

// Numerical autocorrelation of an annular pupil (outer radius 1, inner ε) shifted by d along x, over its
// area: integrate, row by row, the length common to the row and the shifted row (midpoint rule in y).
double numerical_pupil_otf(double d, double e, int rows = 200000) {
  using Interval = std::pair<double, double>;
  auto row = [e](double y, double shift) {
    std::vector<Interval> out;
    if (std::abs(y) >= 1) return out;
    const double s1 = std::sqrt(1 - y * y);
    if (std::abs(y) < e) {
      const double s2 = std::sqrt(e * e - y * y);
      out = {{-s1 + shift, -s2 + shift}, {s2 + shift, s1 + shift}};
    } else {
      out = {{-s1 + shift, s1 + shift}};
    }
    return out;
  };
  double area = 0;
  const double h = 2.0 / rows;
  for (int i = 0; i < rows; ++i) {
    const double y = -1 + (i + 0.5) * h;
    for (const auto& a : row(y, 0))
      for (const auto& b : row(y, d)) area += std::max(0.0, std::min(a.second, b.second) - std::max(a.first, b.first));
  }
  return area * h / (pi * (1 - e * e));
}

// ---- Diffraction-limited objective ----------------------------------------------------------------------

TEST(MtfDiffraction, CutoffIsOneOverLambdaN) {
  // ν_c = D/(λ f'): D = 206 mm, f' = 832 mm, λ = 0.63 µm → 393.0 mm^-1.
  EXPECT_NEAR(diffraction_cutoff_frequency_per_m(0.63 * um, 0.832 / 0.206) / per_mm, 206 / (0.63e-3 * 832), 1e-9);
}

TEST(MtfDiffraction, ClosedFormValues) {
  EXPECT_DOUBLE_EQ(diffraction_mtf_normalized(0.0), 1.0);
  EXPECT_DOUBLE_EQ(diffraction_mtf_normalized(1.0), 0.0);
  EXPECT_DOUBLE_EQ(diffraction_mtf_normalized(1.7), 0.0);
  // M(½) = (2/π)(π/3 − (½)(√3/2)) = 2/3 − √3/(2π) = 0.3910022...
  EXPECT_NEAR(diffraction_mtf_normalized(0.5), 2.0 / 3.0 - std::sqrt(3.0) / (2 * pi), 1e-15);
  EXPECT_NEAR(diffraction_mtf_normalized(0.5), 0.3910, 5e-5);
  // Slope at 0 is −4/π.
  const double h = 1e-7;
  EXPECT_NEAR((diffraction_mtf_normalized(h) - 1.0) / h, -4.0 / pi, 1e-6);
  // Even in frequency; in absolute units the same.
  EXPECT_DOUBLE_EQ(diffraction_mtf_normalized(-0.3), diffraction_mtf_normalized(0.3));
  const double nu_c = diffraction_cutoff_frequency_per_m(0.5 * um, 8.0);
  EXPECT_NEAR(diffraction_mtf(0.5 * nu_c, 0.5 * um, 8.0), 0.39100221895577, 1e-13);
}

TEST(MtfDiffraction, MatchesNumericalAutocorrelationOfDisc) {
  for (double x : {0.05, 0.2, 0.35, 0.5, 0.65, 0.8, 0.95})
    EXPECT_NEAR(diffraction_mtf_normalized(x), numerical_pupil_otf(2 * x, 0.0), 2e-6) << "x = " << x;
}

TEST(MtfDiffraction, ObscuredMatchesONeillAndNumericalAutocorrelation) {
  for (double e : {0.1, 0.3, 0.5, 0.8}) {
    for (int i = 0; i <= 40; ++i) {
      const double x = i / 40.0;
      EXPECT_NEAR(diffraction_mtf_normalized(x, e), radchain::test::oneill_annular_mtf(x, e), 1e-8) << "e = " << e << ", x = " << x;
    }
    for (double x : {0.07, 0.23, 0.41, 0.6, 0.77, 0.93})
      EXPECT_NEAR(diffraction_mtf_normalized(x, e), numerical_pupil_otf(2 * x, e), 2e-5) << "e = " << e << ", x = " << x;
  }
  // Limits: ε → 0 gives the clear disc; the obscured MTF is still 1 at 0 and 0 at the cut-off.
  EXPECT_NEAR(diffraction_mtf_normalized(0.37, 1e-9), diffraction_mtf_normalized(0.37), 1e-12);
  EXPECT_NEAR(diffraction_mtf_normalized(0.0, 0.4), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(diffraction_mtf_normalized(1.0, 0.4), 0.0);
  EXPECT_THROW(diffraction_mtf_normalized(0.3, 1.0), std::invalid_argument);
}

TEST(MtfDiffraction, FrequencyAtContrast) {
  // Independent: Boost bisection on the closed form. M(x) = ½ at x = 0.4039727532995...
  auto f = [](double x) { return 2 / pi * (std::acos(x) - x * std::sqrt(1 - x * x)) - 0.5; };
  const auto [lo, hi] = boost::math::tools::bisect(f, 0.0, 1.0, boost::math::tools::eps_tolerance<double>(50));
  EXPECT_NEAR(diffraction_normalized_frequency_at_contrast(0.5), 0.5 * (lo + hi), 1e-13);
  EXPECT_NEAR(diffraction_normalized_frequency_at_contrast(0.5), 0.40397275, 1e-8);
  EXPECT_NEAR(diffraction_frequency_at_contrast_per_m(0.5, 0.5 * um, 4.0), 0.40397275 / (0.5e-6 * 4.0), 1e-2);
  // With ε = 0.5 the MTF has a shoulder and rises again (M(0.5) < M(0.6)); the first crossing is reported.
  EXPECT_LT(diffraction_mtf_normalized(0.5, 0.5), diffraction_mtf_normalized(0.6, 0.5));
  const double x = diffraction_normalized_frequency_at_contrast(0.5, 0.5);
  EXPECT_NEAR(diffraction_mtf_normalized(x, 0.5), 0.5, 1e-12);
  for (int i = 0; i < 100; ++i) EXPECT_GT(diffraction_mtf_normalized(x * i / 100.0, 0.5), 0.5);
  EXPECT_THROW(diffraction_normalized_frequency_at_contrast(1.0), std::invalid_argument);
}

// ---- Kolobrodov eq. (7): linear objective MTF -----------------------------------------------------------

TEST(MtfKolobrodovLinear, SlopeIsTheChordThroughHalfCutoff) {
  // 1.218 = (1 − M(½))/½: the line of eq. (7) with η = 1 meets the diffraction MTF at ν_c/2.
  EXPECT_NEAR((1 - diffraction_mtf_normalized(0.5)) / 0.5, kolobrodov_linear_mtf_slope, 5e-6);
  const double lambda = 0.6 * um, n = 5.0, nu_c = diffraction_cutoff_frequency_per_m(lambda, n);
  EXPECT_NEAR(kolobrodov_linear_mtf(0.5 * nu_c, lambda, n, 1.0), diffraction_mtf(0.5 * nu_c, lambda, n), 5e-6);
  // Not the tangent at 0 (4/π = 1.273) nor the chord through M = ½ (0.5/0.40397 = 1.2377).
  EXPECT_GT(4 / pi - kolobrodov_linear_mtf_slope, 0.05);
}

TEST(MtfKolobrodovLinear, ValuesAndHalfContrastFrequency) {
  const double lambda = 0.63 * um, n = 4.0, eta = 0.8;
  EXPECT_DOUBLE_EQ(kolobrodov_linear_mtf(0.0, lambda, n, eta), 1.0);
  const double nu = 50 * per_mm;
  EXPECT_NEAR(kolobrodov_linear_mtf(nu, lambda, n, eta), 1 - 1.218 * n * lambda * nu / eta, 1e-15);
  // η = (1 − M_od)/(1 − M_0): the ratio eq. (7) implies (the paper prints it inverted; see the errata doc).
  EXPECT_NEAR((1 - kolobrodov_linear_mtf(nu, lambda, n, 1.0)) / (1 - kolobrodov_linear_mtf(nu, lambda, n, eta)), eta,
              1e-14);
  // Clamped at 0 beyond the line's zero.
  EXPECT_DOUBLE_EQ(kolobrodov_linear_mtf(2 * eta / (1.218 * n * lambda), lambda, n, eta), 0.0);
  // Eq. (11), first form: ν_x1 = η / (2.436 (f'/D) λ).
  const double nu_x1 = kolobrodov_linear_frequency_at_contrast_per_m(0.5, lambda, n, eta);
  EXPECT_NEAR(nu_x1, eta / (2.436 * n * lambda), 1e-9);
  EXPECT_NEAR(kolobrodov_linear_mtf(nu_x1, lambda, n, eta), 0.5, 1e-14);
}

// ---- Detector element, eq. (8) ------------------------------------------------------------------------

TEST(MtfDetector, SincValues) {
  EXPECT_DOUBLE_EQ(sinc_pi(0.0), 1.0);
  EXPECT_NEAR(sinc_pi(0.5), 2 / pi, 1e-15);
  EXPECT_NEAR(sinc_pi(1.0), 0.0, 1e-16);
  EXPECT_NEAR(sinc_pi(1e-5), std::sin(pi * 1e-5) / (pi * 1e-5), 1e-16);
  EXPECT_NEAR(sinc_pi(1.5), -2 / (3 * pi), 1e-15);
  // Eq. (8) for V_D = 7 µm: 2/π at ν = 1/(2 V_D) (the Nyquist frequency of a 7 µm pitch), 0 at 1/V_D, modulus beyond.
  EXPECT_NEAR(detector_pixel_mtf(1 / (2 * 7 * um), 7 * um), 2 / pi, 1e-15);
  EXPECT_NEAR(detector_pixel_mtf(1 / (7 * um), 7 * um), 0.0, 1e-15);
  EXPECT_NEAR(detector_pixel_mtf(1.5 / (7 * um), 7 * um), 2 / (3 * pi), 1e-15);
}

TEST(MtfDetector, SincHalfContrastRoot) {
  // Hand value 0.60335456440161... and an independent Boost bisection on sin(πu)/(πu) − ½.
  EXPECT_NEAR(sinc_half_contrast_root(), 0.6033545644016, 1e-12);
  auto f = [](double u) { return std::sin(pi * u) / (pi * u) - 0.5; };
  const auto [lo, hi] = boost::math::tools::bisect(f, 0.1, 1.0, boost::math::tools::eps_tolerance<double>(50));
  EXPECT_NEAR(sinc_half_contrast_root(), 0.5 * (lo + hi), 1e-13);
  EXPECT_NEAR(sinc_pi(sinc_half_contrast_root()), 0.5, 1e-15);
  // Other contrasts, checked by substitution.
  for (double c : {0.1, 0.3, 0.7, 0.9}) EXPECT_NEAR(sinc_pi(sinc_root_at_contrast(c)), c, 1e-14) << c;
  EXPECT_THROW(sinc_root_at_contrast(0.0), std::invalid_argument);
}

TEST(MtfDetector, PaperHalfContrastFrequency) {
  // Kolobrodov eq. (11) / example step 1: ν_x1 = 0.6 / 7e-3 mm = 86 mm^-1 (printed). 0.6/7 µm = 85.71 mm^-1;
  // with the exact root 0.603355/7 µm = 86.19 mm^-1. Both print as 86.
  const double printed_mm = 86;
  EXPECT_NEAR(kolobrodov_sinc_half_root_printed / (7 * um) / per_mm, printed_mm, 0.5);
  EXPECT_NEAR(kolobrodov_sinc_half_root_printed / (7 * um) / per_mm, 85.714, 1e-3);
  EXPECT_NEAR(detector_frequency_at_contrast_per_m(0.5, 7 * um) / per_mm, printed_mm, 0.5);
  EXPECT_NEAR(detector_frequency_at_contrast_per_m(0.5, 7 * um) / per_mm, 86.194, 1e-3);
}

// ---- Matching, eqs. (10)-(15) -------------------------------------------------------------------------

TEST(MtfKolobrodovMatching, EtaCoefficient) {
  // Eq. (12): 2 · 1.218 · 0.6 = 1.4616, printed 1.46; with the exact root 1.469772.
  EXPECT_NEAR(kolobrodov_eta_coefficient(kolobrodov_sinc_half_root_printed), 1.4616, 1e-12);
  EXPECT_NEAR(kolobrodov_eta_coefficient(kolobrodov_sinc_half_root_printed), kolobrodov_eta_coefficient_printed, 0.005);
  EXPECT_NEAR(kolobrodov_eta_coefficient(sinc_half_contrast_root()), 1.469772, 1e-6);
  // η and the largest matched f-number are inverse.
  const double coef = kolobrodov_eta_coefficient(sinc_half_contrast_root());
  const double eta = kolobrodov_eta(0.63 * um, 4.0, 7 * um, coef);
  EXPECT_NEAR(eta, coef * 4.0 * 0.63 / 7.0, 1e-14);
  EXPECT_NEAR(kolobrodov_max_f_number(0.63 * um, 7 * um, eta, coef), 4.0, 1e-13);
}

TEST(MtfKolobrodovMatching, ObjectiveAndDetectorMeetAtHalfContrast) {
  // With η from eq. (12) (same root u), both forms of eq. (11) give the same ν_x1.
  for (double u : {kolobrodov_sinc_half_root_printed, sinc_half_contrast_root()}) {
    const double lambda = 0.7 * um, vd = 7 * um, n = 3.5;
    const double eta = kolobrodov_eta(lambda, n, vd, kolobrodov_eta_coefficient(u));
    EXPECT_NEAR(kolobrodov_linear_frequency_at_contrast_per_m(0.5, lambda, n, eta), u / vd, 1e-6) << u;
  }
}

// Independent brute-force scan for the root of eq. (15), written out as printed in the paper:
// (1 − V_D/(2 V_s)) sin(π V_D u/V_s)/(π V_D u/V_s) = ½, scanned in V_s/V_D with successive refinement.
double brute_force_eq15(double u) {
  auto g = [u](double k) {
    const double a = pi * u / k;
    return (1 - 1 / (2 * k)) * std::sin(a) / a - 0.5;
  };
  double lo = 1.0, hi = 3.0;
  for (int pass = 0; pass < 6; ++pass) {
    const int steps = 1000;
    const double step = (hi - lo) / steps;
    for (int i = 0; i < steps; ++i) {
      const double a = lo + i * step, b = a + step;
      if ((g(a) < 0) != (g(b) < 0)) {
        lo = a;
        hi = b;
        break;
      }
    }
  }
  return 0.5 * (lo + hi);
}

TEST(MtfKolobrodovMatching, SystemElementRatioEq15) {
  const double with_paper_root = kolobrodov_system_element_ratio(kolobrodov_sinc_half_root_printed);
  const double with_exact_root = kolobrodov_system_element_ratio(sinc_half_contrast_root());
  EXPECT_NEAR(with_paper_root, brute_force_eq15(kolobrodov_sinc_half_root_printed), 1e-12);
  EXPECT_NEAR(with_exact_root, brute_force_eq15(sinc_half_contrast_root()), 1e-12);
  EXPECT_NEAR(with_paper_root, 1.4876985, 1e-6);
  EXPECT_NEAR(with_exact_root, 1.4922245, 1e-6);
  // Printed (15): V_s = 1.49 V_D. Both follow at the paper's rounding.
  EXPECT_NEAR(with_paper_root, kolobrodov_system_element_ratio_printed, 0.005);
  EXPECT_NEAR(with_exact_root, kolobrodov_system_element_ratio_printed, 0.005);
  EXPECT_NEAR(kolobrodov_eq15_residual(with_paper_root, kolobrodov_sinc_half_root_printed), 0.0, 1e-15);
}

TEST(MtfKolobrodovMatching, Eq15IsEq10AtTheRectangleFrequency) {
  // The reduced eq. (15) is exact: with η from eq. (12), the full system MTF (10) at ν_x2 = u/V_s is ½.
  for (double u : {kolobrodov_sinc_half_root_printed, sinc_half_contrast_root()}) {
    const double lambda = 0.63 * um, vd = 7 * um, n = 4.2;
    const double eta = kolobrodov_eta(lambda, n, vd, kolobrodov_eta_coefficient(u));
    const double vs = kolobrodov_system_element_ratio(u) * vd;
    EXPECT_NEAR(kolobrodov_system_mtf(u / vs, lambda, n, eta, vd), 0.5, 1e-13) << u;
  }
  // The same for another matching contrast (the generalised residual), e.g. 0.3.
  const double u = sinc_root_at_contrast(0.3), lambda = 0.63 * um, vd = 7 * um, n = 4.2;
  // η such that eq. (7) reaches 0.3 where the element does: (1 − 0.3) η/(1.218 N λ) = u/V_D.
  const double eta = 1.218 * n * lambda * u / ((1 - 0.3) * vd);
  EXPECT_NEAR(kolobrodov_linear_frequency_at_contrast_per_m(0.3, lambda, n, eta), u / vd, 1e-6);
  const double vs = kolobrodov_system_element_ratio(u, 0.3) * vd;
  EXPECT_NEAR(kolobrodov_system_mtf(u / vs, lambda, n, eta, vd), 0.3, 1e-13);
}

}  // namespace

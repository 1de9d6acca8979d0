// Spectrum (framework/core/include/radchain/spectrum.hpp): linear interpolation, the two extrapolation rules, and
// the band integrals, checked against values worked by hand and closed-form integrals of linear functions.
#include "radchain/constants.hpp"
#include "radchain/curve_components.hpp"
#include "radchain/spectrum.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace {
using radchain::Extrapolation;
using radchain::Spectrum;

Eigen::ArrayXd array(std::initializer_list<double> values) {
  Eigen::ArrayXd a(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (double v : values) a(i++) = v;
  return a;
}

// Grid in micrometres for readability; values at 1, 2, 4 µm.
Spectrum three_points(Extrapolation rule) {
  return Spectrum(array({1e-6, 2e-6, 4e-6}), array({1.0, 3.0, -1.0}), "1", rule);
}

TEST(Spectrum, InterpolatesLinearly) {
  const Spectrum s = three_points(Extrapolation::zero);
  EXPECT_DOUBLE_EQ(s(1e-6), 1.0);
  EXPECT_DOUBLE_EQ(s(2e-6), 3.0);
  EXPECT_DOUBLE_EQ(s(4e-6), -1.0);
  EXPECT_NEAR(s(1.5e-6), 2.0, 1e-15);   // halfway between 1 and 3
  EXPECT_NEAR(s(1.25e-6), 1.5, 1e-15);
  EXPECT_NEAR(s(3e-6), 1.0, 1e-15);     // halfway between 3 and -1
  EXPECT_NEAR(s(3.5e-6), 0.0, 1e-15);
  const Eigen::ArrayXd many = s(array({0.5e-6, 1.5e-6, 3e-6, 5e-6}));
  EXPECT_EQ(many(0), 0.0);
  EXPECT_NEAR(many(1), 2.0, 1e-15);
  EXPECT_NEAR(many(2), 1.0, 1e-15);
  EXPECT_EQ(many(3), 0.0);
}

TEST(Spectrum, ZeroExtrapolation) {
  const Spectrum s = three_points(Extrapolation::zero);
  EXPECT_EQ(s(0.999e-6), 0.0);
  EXPECT_EQ(s(4.001e-6), 0.0);
  EXPECT_EQ(s(0.0), 0.0);
  EXPECT_EQ(s(1.0), 0.0);
}

TEST(Spectrum, ClampExtrapolation) {
  const Spectrum s = three_points(Extrapolation::clamp);
  EXPECT_EQ(s(0.5e-6), 1.0);
  EXPECT_EQ(s(10e-6), -1.0);
  const Spectrum flat = Spectrum::constant(0.56, "1");
  EXPECT_EQ(flat(1e-9), 0.56);
  EXPECT_EQ(flat(5e-7), 0.56);
  EXPECT_EQ(flat(1.0), 0.56);
}

TEST(Spectrum, RejectsBadGrids) {
  EXPECT_THROW(Spectrum(array({1e-6, 3e-6, 2e-6}), array({1, 2, 3}), "1"), std::invalid_argument);  // not monotonic
  EXPECT_THROW(Spectrum(array({1e-6, 2e-6, 2e-6}), array({1, 2, 3}), "1"), std::invalid_argument);  // repeated point
  EXPECT_THROW(Spectrum(array({1e-6, 2e-6}), array({1, 2, 3}), "1"), std::invalid_argument);        // sizes differ
  EXPECT_THROW(Spectrum(array({1e-6}), array({1}), "1"), std::invalid_argument);                    // one point
  EXPECT_THROW(Spectrum(array({1e-6, NAN}), array({1, 2}), "1"), std::invalid_argument);            // NaN is not increasing
}

TEST(Spectrum, IntegralOfALinearFunctionIsExact) {
  // f(λ) = a + b λ sampled on an irregular grid; piecewise-linear interpolation of a linear function is the
  // function itself, so the trapezoid rule is exact, also with limits between grid points.
  const double a = 2.5, b = -3.0e5;  // λ in metres: f falls from 2.2 to 1.3 over 1..4 µm
  const Eigen::ArrayXd grid = array({1e-6, 1.1e-6, 1.7e-6, 2.0e-6, 3.3e-6, 4e-6});
  const Spectrum s = Spectrum::sampled(grid, [&](double l) { return a + b * l; }, "1");
  auto exact = [&](double lo, double hi) { return a * (hi - lo) + 0.5 * b * (hi * hi - lo * lo); };
  EXPECT_NEAR(s.integral(), exact(1e-6, 4e-6), 1e-12 * std::abs(exact(1e-6, 4e-6)));
  EXPECT_NEAR(s.integral(1.234e-6, 3.456e-6), exact(1.234e-6, 3.456e-6), 1e-12 * std::abs(exact(1.234e-6, 3.456e-6)));
  EXPECT_EQ(s.integral(3e-6, 2e-6), 0.0);  // empty interval
}

// The one-spectrum integral sums its table in blocks of 16 intervals (spectrum.cpp, trapezoid_sum), with the last
// short block padded: every length from 1 to 40 intervals, both weights, against the trapezoid summed one interval
// at a time in long double. An interval dropped or counted twice at a block edge is off by ~1/n; rounding is 1e-15.
TEST(Spectrum, IntegralOfEveryTableLengthMatchesTheTrapezoidSummedInLongDouble) {
  const double per_m = 1.0 / (radchain::constants::planck_J_s * radchain::constants::speed_of_light_m_s);
  for (int intervals = 1; intervals <= 40; ++intervals) {
    SCOPED_TRACE(intervals);
    Eigen::ArrayXd grid(intervals + 1), values(intervals + 1);
    for (int i = 0; i <= intervals; ++i) {
      grid(i) = 0.4e-6 + 0.01e-6 * i + 0.003e-6 * std::sin(1.7 * i);  // irregular steps, increasing
      values(i) = 1.0 + 0.5 * std::cos(0.9 * i) + 0.01 * i;
    }
    const Spectrum s(grid, values, "1");
    long double energy = 0, photons = 0;
    for (int i = 0; i < intervals; ++i) {
      const long double h = static_cast<long double>(grid(i + 1)) - grid(i);
      energy += h * (static_cast<long double>(values(i)) + values(i + 1)) / 2;
      photons += h * (static_cast<long double>(values(i)) * grid(i) + static_cast<long double>(values(i + 1)) * grid(i + 1)) / 2;
    }
    EXPECT_NEAR(s.integral() / static_cast<double>(energy), 1.0, 1e-14);
    const double counted = radchain::band_integral({&s}, grid(0), grid(intervals), radchain::Weight::photons);
    EXPECT_NEAR(counted / (static_cast<double>(photons) * per_m), 1.0, 1e-14);
  }
}

TEST(Spectrum, IntegralBeyondTheGridFollowsTheExtrapolationRule) {
  // 1 on [1, 2] µm. Zero extrapolation: nothing outside, so ∫ over [0, 3] µm is 1 µm, not a trapezoid ramp.
  const Spectrum zero(array({1e-6, 2e-6}), array({1.0, 1.0}), "1", Extrapolation::zero);
  EXPECT_NEAR(zero.integral(0.0, 3e-6), 1e-6, 1e-21);
  EXPECT_NEAR(zero.integral(0.5e-6, 1.5e-6), 0.5e-6, 1e-21);
  EXPECT_EQ(zero.integral(2.5e-6, 3e-6), 0.0);
  // Clamp extrapolation: 1 everywhere.
  const Spectrum clamp(array({1e-6, 2e-6}), array({1.0, 1.0}), "1", Extrapolation::clamp);
  EXPECT_NEAR(clamp.integral(0.0, 3e-6), 3e-6, 1e-21);
}

TEST(Spectrum, BandIntegralOfAProductOnDifferentGridsByHand) {
  // A: a hat 0 -> 1 -> 0 on {1, 2, 3} µm; B: 2 on [1.5, 2.5] µm rising to 4 at 3 µm; both zero outside.
  // Union grid clipped to the overlap [1.5, 3]: nodes 1.5, 2, 2.5, 3 with
  //   A = 0.5, 1, 0.5, 0;  B = 2, 2, 2, 4;  A·B = 1, 2, 1, 0.
  // Trapezoid (0.5 µm steps): 0.25 µm × [(1+2) + (2+1) + (1+0)] = 1.75 µm.
  const Spectrum a(array({1e-6, 2e-6, 3e-6}), array({0.0, 1.0, 0.0}), "1");
  const Spectrum b(array({1.5e-6, 2.5e-6, 3e-6}), array({2.0, 2.0, 4.0}), "1");
  EXPECT_NEAR(radchain::band_integral({&a, &b}, 0.0, 1e-5), 1.75e-6, 1e-20);
  // Limits inside the grids are inserted as nodes: over [1.5, 2.25] µm, A·B = 1, 2, 1.5 at 1.5, 2, 2.25:
  //   0.25 µm × (1+2) + 0.125 µm × (2+1.5) = 0.75 + 0.4375 = 1.1875 µm.
  EXPECT_NEAR(radchain::band_integral({&a, &b}, 1.5e-6, 2.25e-6), 1.1875e-6, 1e-20);
  // Photon counting weighs by λ/(hc) = (λ/µm) × 1 µm/(hc): nodes 1.5, 2, 2.5, 3 give A·B·λ/µm = 1.5, 4, 2.5, 0:
  //   0.25 µm × [(1.5+4) + (4+2.5) + (2.5+0)] = 0.25 × 14.5 = 3.625 µm, times 1 µm/(hc).
  const double per_um = 1e-6 / (radchain::constants::planck_J_s * radchain::constants::speed_of_light_m_s);
  EXPECT_NEAR(radchain::band_integral({&a, &b}, 0.0, 1e-5, radchain::Weight::photons) / (3.625e-6 * per_um), 1.0, 1e-14);
  // The product spectrum carries the same nodes, so its own integral is the same number.
  const Spectrum ab = a.product(b);
  EXPECT_EQ(ab.min_wavelength_m(), 1.5e-6);
  EXPECT_EQ(ab.max_wavelength_m(), 3e-6);
  EXPECT_EQ(ab.unit(), "1 1");
  EXPECT_NEAR(ab.integral(), 1.75e-6, 1e-20);
}

TEST(Spectrum, BandIntegralWithAConstantFactor) {
  // A constant (clamped, two equal points) adds no nodes and multiplies the integral.
  const Spectrum a(array({1e-6, 2e-6, 3e-6}), array({0.0, 1.0, 0.0}), "1");
  const Spectrum tau = Spectrum::constant(0.56, "1");
  EXPECT_NEAR(radchain::band_integral({&a, &tau}, 0.0, 1e-5), 0.56e-6, 1e-21);
  EXPECT_EQ(radchain::union_grid({&a, &tau}, 0.5e-6, 2.5e-6).size(), 4);  // 0.5, 1, 2, 2.5
}

TEST(Spectrum, ProductOfDisjointSpectraThrows) {
  const Spectrum a(array({1e-6, 2e-6}), array({1.0, 1.0}), "1");
  const Spectrum b(array({3e-6, 4e-6}), array({1.0, 1.0}), "1");
  EXPECT_THROW(a.product(b), std::invalid_argument);
  EXPECT_EQ(radchain::band_integral({&a, &b}, 0.0, 1e-5), 0.0);
}

TEST(Spectrum, ScaledResampledPeak) {
  const Spectrum s = three_points(Extrapolation::zero);
  const Spectrum twice = s.scaled(2.0, "W m-2 m-1");
  EXPECT_EQ(twice.unit(), "W m-2 m-1");
  EXPECT_EQ(twice(2e-6), 6.0);
  EXPECT_EQ(s.peak_value(), 3.0);
  EXPECT_EQ(s.peak_wavelength_m(), 2e-6);
  const Spectrum r = s.resampled(array({1e-6, 1.5e-6, 3e-6, 4e-6}));
  EXPECT_EQ(r.size(), 4);
  EXPECT_NEAR(r(1.5e-6), 2.0, 1e-15);
  EXPECT_NEAR(r(3e-6), 1.0, 1e-15);
}

TEST(Spectrum, UnionGridIsSortedAndClipped) {
  const Spectrum a(array({1e-6, 2e-6, 3e-6}), array({0.0, 1.0, 0.0}), "1");
  const Spectrum b(array({1.5e-6, 2e-6, 2.5e-6}), array({1.0, 1.0, 1.0}), "1");
  const Eigen::ArrayXd grid = radchain::union_grid({&a, &b}, 1.2e-6, 2.7e-6);
  const Eigen::ArrayXd expected = array({1.2e-6, 1.5e-6, 2e-6, 2.5e-6, 2.7e-6});
  ASSERT_EQ(grid.size(), expected.size());
  for (Eigen::Index i = 0; i < grid.size(); ++i) EXPECT_EQ(grid(i), expected(i)) << i;
}

// passband_m (curve_components.hpp): the first and last grid points at ≥ 1 % of the peak; a curve that never
// drops below it is its whole table.
TEST(CurveComponents, PassbandIsWhereTheCurveReachesOnePercentOfItsPeak) {
  Eigen::ArrayXd w(7), v(7);
  w << 400e-9, 450e-9, 500e-9, 550e-9, 600e-9, 650e-9, 700e-9;
  v << 0.001, 0.005, 0.2, 0.9, 0.5, 0.0095, 0.0;
  const auto [lo, hi] = passband_m(Spectrum(w, v, "1"));
  EXPECT_EQ(lo, 500e-9);  // 0.005 < 0.009 = 1 % of 0.9 ≤ 0.2
  EXPECT_EQ(hi, 650e-9);  // 0.0095 ≥ 0.009
  Eigen::ArrayXd flat = Eigen::ArrayXd::Constant(7, 0.9);
  EXPECT_EQ(passband_m(Spectrum(w, flat, "1")), std::make_pair(400e-9, 700e-9));
}

}  // namespace

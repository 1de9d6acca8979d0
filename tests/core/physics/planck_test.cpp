// Planck's law, band fractions and the constants header (physics/planck.hpp, constants.hpp), against
// CODATA 2018 values, closed forms (Stefan-Boltzmann, Wien, photon exitance with ζ(3)), Boost.Math quadrature
// and the CIE illuminant A table (Planck at 2848 K with c2 = 1.435e-2 m K, CIE 015:2018 eq. 3.1).
#include "radchain/constants.hpp"
#include "radchain/physics/planck.hpp"
#include "radchain/spectrum_csv.hpp"

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/minima.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace {
using namespace radchain;
namespace c = radchain::constants;

// ∫_a^b f by adaptive Gauss-Kronrod (61 points), relative tolerance 1e-13.
template <class F>
double integrate(F f, double a, double b) {
  double error = 0;
  return boost::math::quadrature::gauss_kronrod<double, 61>::integrate(f, a, b, 20, 1e-13, &error);
}

// ∫_a^b M_λ dλ over a wide range, integrated in u = ln λ (M_λ spans many decades).
double exitance_between(double lo_m, double hi_m, double temperature_K) {
  return integrate([&](double u) {
    const double l = std::exp(u);
    return physics::planck_spectral_exitance(l, temperature_K) * l;
  }, std::log(lo_m), std::log(hi_m));
}

TEST(Constants, Codata2018) {
  // CODATA 2018 (exact to the digits shown, derived from the exact SI-2019 defining constants).
  EXPECT_NEAR(c::stefan_boltzmann_W_m2_K4, 5.670374419e-8, 5.670374419e-8 * 1e-9);
  EXPECT_NEAR(c::second_radiation_m_K, 1.438776877e-2, 1.438776877e-2 * 1e-9);
  EXPECT_NEAR(c::wien_displacement_m_K, 2.897771955e-3, 2.897771955e-3 * 1e-9);
  EXPECT_NEAR(c::first_radiation_radiance_W_m2_sr, 1.191042972e-16, 1.191042972e-16 * 1e-9);
  EXPECT_NEAR(std::numbers::pi * c::first_radiation_radiance_W_m2_sr, 3.741771852e-16, 3.741771852e-16 * 1e-9);  // c1
  EXPECT_EQ(c::planck_J_s, 6.62607015e-34);
  EXPECT_EQ(c::boltzmann_J_K, 1.380649e-23);
  EXPECT_EQ(c::speed_of_light_m_s, 299792458.0);
  EXPECT_EQ(c::elementary_charge_C, 1.602176634e-19);
}

TEST(Constants, WienRootSatisfiesItsEquation) {
  // x = 5 (1 - e^-x) defines the Wien constant b = c2 / x.
  const double x = c::second_radiation_m_K / c::wien_displacement_m_K;
  EXPECT_NEAR(x, 5.0 * (1.0 - std::exp(-x)), 1e-14);
}

TEST(Planck, StefanBoltzmannFromTheSpectrum) {
  // ∫ M_λ over 0.1..1000 µm at 5778 K vs σT^4.
  const double t = 5778.0;
  const double sigma_t4 = c::stefan_boltzmann_W_m2_K4 * std::pow(t, 4);
  EXPECT_NEAR(physics::blackbody_exitance(t), sigma_t4, sigma_t4 * 1e-14);
  const double in_range = exitance_between(0.1e-6, 1000e-6, t);
  EXPECT_NEAR(in_range, sigma_t4, sigma_t4 * 1e-4);
  // The tails are 4e-8 (below 0.1 µm) and 8e-10 (above 1 mm) of the total; with them, agreement is to 1e-10.
  const double fraction = physics::blackbody_fraction_below(1000e-6, t) - physics::blackbody_fraction_below(0.1e-6, t);
  EXPECT_NEAR(in_range, sigma_t4 * fraction, sigma_t4 * 1e-10);
  // And at a cold temperature, where the range is 1..10^5 µm.
  EXPECT_NEAR(exitance_between(1e-6, 0.1, 300.0), physics::blackbody_exitance(300.0), physics::blackbody_exitance(300.0) * 1e-8);
}

TEST(Planck, WienPeakByMaximisation) {
  for (const double t : {300.0, 2856.0, 5778.0}) {
    SCOPED_TRACE(t);
    const double b_over_t = 2.897771955e-3 / t;
    // Brent in micrometres: Boost's tolerance has an absolute part (2^-bits/4) that metres would swamp.
    const double um = 1e-6;
    const auto [peak_um, minus_max] = boost::math::tools::brent_find_minima(
        [&](double l_um) { return -physics::planck_spectral_exitance(l_um * um, t); }, 0.5 * b_over_t / um,
        2.0 * b_over_t / um, 40);
    (void)minus_max;
    const double peak = peak_um * um;
    // A maximum is flat: its position is known to about sqrt(eps).
    EXPECT_NEAR(peak, b_over_t, b_over_t * 1e-7);
    EXPECT_NEAR(physics::wien_peak_wavelength_m(t), b_over_t, b_over_t * 1e-9);
  }
}

TEST(Planck, PhotonExitanceClosedForm) {
  // M_q = ∫ M_λ λ/(hc) dλ = 4π ζ(3) (kT)^3 / (h^3 c^2),  ζ(3) = 1.2020569031595942.
  const double t = 5778.0;
  const double kt = c::boltzmann_J_K * t;
  const double expected = 4.0 * std::numbers::pi * 1.2020569031595942 * kt * kt * kt /
                          (c::planck_J_s * c::planck_J_s * c::planck_J_s * c::speed_of_light_m_s * c::speed_of_light_m_s);
  const double computed = integrate([&](double u) {
    const double l = std::exp(u);
    return physics::planck_photon_spectral_exitance(l, t) * l;
  }, std::log(0.05e-6), std::log(1.0));  // 50 nm .. 1 m: the tails are below 1e-12
  EXPECT_NEAR(computed, expected, expected * 1e-8);
}

TEST(Planck, RayleighJeansAndWienLimits) {
  // λT >> c2: L_λ -> 2 c k T / λ^4 (relative difference about x/2, x = c2/(λT)).
  const double t = 300.0, l = 1.0;  // 1 m
  const double rj = 2.0 * c::speed_of_light_m_s * c::boltzmann_J_K * t / std::pow(l, 4);
  const double x = c::second_radiation_m_K / (l * t);
  EXPECT_NEAR(physics::planck_spectral_radiance(l, t) / rj, 1.0 - x / 2.0, 1e-9);
  // λT << c2: L_λ -> c1L / λ^5 e^{-x}.
  const double l2 = 0.2e-6, t2 = 1000.0;
  const double x2 = c::second_radiation_m_K / (l2 * t2);
  const double wien = c::first_radiation_radiance_W_m2_sr / std::pow(l2, 5) * std::exp(-x2);
  EXPECT_NEAR(physics::planck_spectral_radiance(l2, t2) / wien, 1.0, 1e-12);
  EXPECT_NEAR(physics::planck_spectral_exitance(l2, t2), std::numbers::pi * physics::planck_spectral_radiance(l2, t2), 1e-30);
}

TEST(Planck, FractionBelowMatchesQuadrature) {
  const double t = 5778.0;
  const double sigma_t4 = physics::blackbody_exitance(t);
  for (const double lambda_t_um_K : {500.0, 1000.0, 2000.0, 2897.77, 4000.0, 6000.0, 10000.0, 30000.0, 1e5}) {
    SCOPED_TRACE(lambda_t_um_K);
    const double l = lambda_t_um_K * 1e-6 / t;
    // Below λT = 50 µm K the exitance is e^-288 of its peak: start there.
    const double numeric = exitance_between(50e-6 / t, l, t) / sigma_t4;
    EXPECT_NEAR(physics::blackbody_fraction_below(l, t), numeric, numeric * 1e-6);
  }
  EXPECT_EQ(physics::blackbody_fraction_below(0.0, t), 0.0);
  EXPECT_NEAR(physics::blackbody_fraction_below(1.0, t), 1.0, 1e-9);  // 1 m at 5778 K
}

TEST(Planck, ClassicFractionValues) {
  // Tables (e.g. Wolfe & Zissis 1978; Incropera): F(0 -> λT) = 0.2501 at λT = 2898 µm K, 0.7378 at 6000 µm K.
  EXPECT_NEAR(physics::blackbody_fraction_below(2898e-6, 1.0), 0.2501, 1e-3);
  EXPECT_NEAR(physics::blackbody_fraction_below(6000e-6, 1.0), 0.7378, 1e-3);
  EXPECT_NEAR(physics::blackbody_fraction_below(1000e-6, 1.0), 0.00032, 1e-5);
}

TEST(Planck, FractionOfABandIsTheDifference) {
  // 8-14 µm at 300 K: about 37 % of σT^4 (thermal IR rule of thumb); quadrature to 1e-6.
  const double t = 300.0;
  const double band = physics::blackbody_fraction_below(14e-6, t) - physics::blackbody_fraction_below(8e-6, t);
  const double numeric = exitance_between(8e-6, 14e-6, t) / physics::blackbody_exitance(t);
  EXPECT_NEAR(band, numeric, numeric * 1e-6);
  EXPECT_NEAR(band, 0.37, 0.02);
}

TEST(Planck, CieIlluminantATable) {
  // CIE illuminant A: S(λ) = 100 × L_λ(λ, 2848 K, c2 = 1.435e-2) / L_λ(560 nm, ...), tabulated to 6 digits.
  const SpectrumFile a =
      load_spectrum_csv(std::string(RADCHAIN_SOURCE_DIR) + "/spectra/cie_illuminant_A_1nm.csv", "1");
  const double t = 2848.0, c2 = c::second_radiation_1931_m_K;
  const double at_560 = physics::planck_spectral_radiance(560e-9, t, c2);
  double worst = 0;
  for (Eigen::Index i = 0; i < a.spectrum.size(); ++i) {
    const double l = a.spectrum.wavelength_m()(i);
    const double model = 100.0 * physics::planck_spectral_radiance(l, t, c2) / at_560;
    worst = std::max(worst, std::abs(a.spectrum.value()(i) / model - 1.0));
  }
  EXPECT_LT(worst, 1e-5) << "largest relative difference over 300-830 nm";
  // With today's c2 the same temperature is off by far more: the c2 convention matters.
  const double modern = 100.0 * physics::planck_spectral_radiance(300e-9, t) / physics::planck_spectral_radiance(560e-9, t);
  EXPECT_GT(std::abs(a.spectrum(300e-9) / modern - 1.0), 1e-2);
}

}  // namespace

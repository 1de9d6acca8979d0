// Magnitude systems in bandpasses (physics/magnitudes.hpp) against their definitions and published offsets:
//   AB: f_ν = 3631 Jy (Oke & Gunn 1983) gives n_λ = f_ν/(hλ): 996 photons s⁻¹ cm⁻² Å⁻¹ at 550 nm, and
//       ∫ f_ν/(hλ) dλ = (f_ν/h) ln(λ2/λ1) through a box band (exact).
//   Vega (CALSPEC alpha_lyr_stis_002) in AB through Bessell 1990 B V R I: m_AB − m_Vega = −0.09, 0.02, 0.21, 0.45
//       (Blanton & Roweis 2007, AJ 133, 734, Table 1; two decimals → ±0.03 with the filters' weighting convention).
//   Vega in Gaia G: the EDR3 zero points G_Vega = 25.6874, G_AB = 25.8010 (Riello et al. 2021, A&A 649, A3,
//       Table 3) put Vega (G = 0.03 in the Gaia Vega system, which takes V_Vega = 0.03) at G_AB = 0.1436.
//   Vega V: mean f_λ of Vega in V = 363.1e-11 erg s⁻¹ cm⁻² Å⁻¹ × 10^{-0.4·0.03} for V = 0.03 (Bessell, Castelli &
//       Plez 1998, A&A 333, 231, Table A2: V = 0 ↔ 363.1e-11), photon-weighted, ±2 % (CALSPEC absolute 1-2 %).
#include "radchain/constants.hpp"
#include "radchain/physics/magnitudes.hpp"
#include "radchain/spectrum_csv.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace {
using namespace radchain;
using namespace radchain::physics;

const std::string spectra = std::string(RADCHAIN_SOURCE_DIR) + "/spectra/";
constexpr double nm = 1e-9;
constexpr double h = constants::planck_J_s;

const Spectrum& vega() {
  static const Spectrum s = load_spectrum_csv(spectra + "vega_alpha_lyr_stis_002.csv", "W m-2 m-1").spectrum;
  return s;
}
Spectrum band(const std::string& file) { return load_spectrum_csv(spectra + file, "1").spectrum; }

double vega_ab_magnitude(const Spectrum& t) {
  const double ab = band_photon_rate(ab_reference_spectrum(t.min_wavelength_m(), t.max_wavelength_m()), t);
  return band_magnitude(band_photon_rate(vega(), t), ab);
}

TEST(PhysicsMagnitudes, AbAndStReferenceFluxes) {
  EXPECT_NEAR(ab_zero_f_nu_W_m2_Hz, 3631e-26, 0.5e-26);   // 3630.8 Jy
  EXPECT_NEAR(st_zero_f_lambda_W_m3, 3.631e-2, 0.5e-5);   // 3.631e-9 erg s-1 cm-2 Å-1
  // AB photon density at 550 nm: f_ν/(hλ) in photons s-1 cm-2 Å-1.
  const double per_cm2_A = ab_zero_f_nu_W_m2_Hz / (h * 550 * nm) * 1e-4 * 1e-10;
  EXPECT_NEAR(per_cm2_A, 996.3, 0.5);
}

TEST(PhysicsMagnitudes, AbZeroPointThroughABoxBandIsAnalytic) {
  const Eigen::ArrayXd w = (Eigen::ArrayXd(2) << 500 * nm, 600 * nm).finished();
  const Spectrum box(w, Eigen::ArrayXd::Ones(2), "1");
  const double analytic = ab_zero_f_nu_W_m2_Hz / h * std::log(600.0 / 500.0);
  EXPECT_NEAR(band_photon_rate(ab_reference_spectrum(500 * nm, 600 * nm), box) / analytic, 1.0, 1e-6);
  // ST: f_λ λ/(hc) integrates to f_λ (λ2² − λ1²)/(2hc).
  const double st = st_zero_f_lambda_W_m3 * (std::pow(600 * nm, 2) - std::pow(500 * nm, 2)) /
                    (2 * h * constants::speed_of_light_m_s);
  EXPECT_NEAR(band_photon_rate(st_reference_spectrum(500 * nm, 600 * nm), box) / st, 1.0, 1e-9);
  // A magnitude is the log ratio; the zero point itself is magnitude 0.
  EXPECT_DOUBLE_EQ(band_magnitude(analytic, analytic), 0.0);
  EXPECT_NEAR(band_magnitude(analytic / 100, analytic), 5.0, 1e-12);
}

TEST(PhysicsMagnitudes, VegaInAbThroughJohnsonCousinsMatchesBlantonRoweis2007) {
  EXPECT_NEAR(vega_ab_magnitude(band("johnson_cousins_B_bessell1990.csv")), -0.09, 0.03);
  EXPECT_NEAR(vega_ab_magnitude(band("johnson_cousins_V_bessell1990.csv")), 0.02, 0.03);
  EXPECT_NEAR(vega_ab_magnitude(band("johnson_cousins_R_bessell1990.csv")), 0.21, 0.03);
  EXPECT_NEAR(vega_ab_magnitude(band("johnson_cousins_I_bessell1990.csv")), 0.45, 0.03);
}

TEST(PhysicsMagnitudes, VegaInAbThroughGaiaGMatchesRiello2021ZeroPoints) {
  EXPECT_NEAR(vega_ab_magnitude(band("gaia_dr3_G.csv")), 0.03 + (25.8010 - 25.6874), 0.02);
}

TEST(PhysicsMagnitudes, VegaMeanFluxInVMatchesBessellCastelliPlez1998) {
  const Spectrum v = band("johnson_cousins_V_bessell1990.csv");
  // Photon-weighted mean f_λ: ∫ f_λ T λ dλ / ∫ T λ dλ, in erg s-1 cm-2 Å-1 (1 W m-2 m-1 = 1e-7 erg s-1 cm-2 Å-1).
  const double lo = v.min_wavelength_m(), hi = v.max_wavelength_m();
  const double mean = band_integral({&vega(), &v}, lo, hi, Weight::photons) /
                      band_integral({&v}, lo, hi, Weight::photons) * 1e-7;
  EXPECT_NEAR(mean / (363.1e-11 * std::pow(10.0, -0.4 * 0.03)), 1.0, 0.02);
  // The Vega zero point of V as a photon density (Bessell et al. 1998 Table A2 quotes N_λ ≈ 1000 photons s-1
  // cm-2 Å-1 for V = 0 at the band's mean).
  const double density = zero_point_photon_density(band_photon_rate(vega(), v), v) * 1e-4 * 1e-10;
  EXPECT_NEAR(density, 1000.0, 50.0);
}

}  // namespace

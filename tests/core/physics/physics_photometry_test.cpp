// Photometry and photon counts (CIE 015; Pan et al. 2010 eqs. 1, 3-7) against the CIE V(λ) table, the
// definition of the lumen and an independent quadrature of Planck's photon exitance.
#include "radchain/constants.hpp"
#include "radchain/physics/band.hpp"
#include "radchain/physics/photometry.hpp"
#include "radchain/physics/planck.hpp"
#include "radchain/spectrum_csv.hpp"

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace {
using namespace radchain;
using namespace radchain::physics;

const std::string spectra = std::string(RADCHAIN_SOURCE_DIR) + "/spectra/";
constexpr double nm = 1e-9, um = 1e-6;
constexpr double hc = constants::planck_J_s * constants::speed_of_light_m_s;

const Spectrum& v_lambda() {
  static const Spectrum s = load_spectrum_csv(spectra + "cie_1924_photopic_V_1nm.csv", "1").spectrum;
  return s;
}
const Spectrum& e490() {
  static const Spectrum s = load_spectrum_csv(spectra + "am0_astm_e490_00a.csv", "W m-2 m-1").spectrum;
  return s;
}

TEST(PhysicsPhotometry, PhotopicVPeaksAtOneAt555nm) {
  EXPECT_DOUBLE_EQ(v_lambda().peak_value(), 1.0);
  EXPECT_NEAR(v_lambda().peak_wavelength_m(), 555 * nm, 1e-15);
  EXPECT_NEAR(v_lambda().min_wavelength_m(), 360 * nm, 1e-15);
  EXPECT_NEAR(v_lambda().max_wavelength_m(), 830 * nm, 1e-15);
}

// Solar illuminance at 1 AU from ASTM E-490 and CIE 1924 V(λ), K_m = 683 lm/W: 1.3332e5 lx (133 319 lx,
// spectra/README.md, computed there with numpy on the same files); luminous efficacy 97.59 lm/W.
TEST(PhysicsPhotometry, SolarIlluminanceOfE490) {
  const double ev = luminous(e490(), v_lambda());
  std::printf("solar illuminance (E-490, CIE 1924 V, K_m = 683): %.1f lx; efficacy %.3f lm/W\n", ev,
              ev / e490().integral());
  EXPECT_NEAR(ev, 1.3332e5, 1.3332e5 * 1e-3);
  EXPECT_NEAR(ev, 133319.0, 1.0);
  EXPECT_NEAR(ev / e490().integral(), 97.59, 0.01);
  // Pan 2010 writes the photometric integral over 0.38-0.76 µm (eq. 8); the CIE table runs 360-830 nm.
  const double pan_limits = constants::luminous_efficacy_540THz_lm_W * band_integral({&e490(), &v_lambda()}, 380 * nm, 760 * nm);
  std::printf("  over 380-760 nm only: %.1f lx (%.2e relative)\n", pan_limits, pan_limits / ev - 1);
  EXPECT_NEAR(pan_limits / ev, 1.0, 2e-4);
}

// Pan 2010 eqs. (3)-(5): the radiometric spectrum recovered from a luminous flux has that luminous flux.
TEST(PhysicsPhotometry, RadiometricFromLuminousRoundTrip) {
  const Spectrum relative = normalised_to_peak(e490());  // Pan's Φ(λ)r: the Sun's relative distribution
  const double flux_lm = 2.5e-14;
  const Spectrum phi = radiometric_from_luminous(flux_lm, relative, v_lambda(), "W m-1");
  EXPECT_EQ(phi.unit(), "W m-1");
  EXPECT_NEAR(luminous(phi, v_lambda()) / flux_lm, 1.0, 1e-13);
  // Φ_λmax = F / (K_m ∫ V Φr dλ), with ∫ V Φr dλ = 195.196 W m-2 / E_peak (spectra/README.md).
  const double phi_max = radiometric_scale_from_luminous(flux_lm, relative, v_lambda());
  EXPECT_NEAR(phi_max, flux_lm / (683.0 * 195.196 / e490().peak_value()), 1e-5 * phi_max);
  EXPECT_THROW(radiometric_scale_from_luminous(1.0, Spectrum::sampled(Eigen::ArrayXd::LinSpaced(3, 1 * um, 2 * um),
                                                                      [](double) { return 1.0; }, "1"),
                                               v_lambda()),
               std::invalid_argument);
}

// One lumen of (nearly) monochromatic 555 nm light is 1/683 W (definition of the candela, with the papers'
// K_m = 683 lm/W) = 555 nm / (h c 683) = 4.0907e15 photons per second.
TEST(PhysicsPhotometry, PhotonsPerLumenAt555nm) {
  Eigen::ArrayXd grid(3), value(3);
  grid << 554.9 * nm, 555.0 * nm, 555.1 * nm;
  value << 0, 1, 0;
  const Spectrum line(grid, value, "1");
  const double n = photons_per_lumen(line, v_lambda(), 500 * nm, 600 * nm);
  const double expected = 555 * nm / (hc * 683.0);
  EXPECT_NEAR(expected, 4.0907e15, 0.0001e15);
  EXPECT_NEAR(n / expected, 1.0, 1e-5);  // V(554.9..555.1 nm) differs from 1 by < 1e-5
  // With η(λ) = 0.27 (Pan 2010 Table 1 mean QE): electrons per lumen-second scale with it.
  const Spectrum qe = Spectrum::constant(0.27, "1");
  EXPECT_NEAR(photons_per_lumen(line, v_lambda(), 500 * nm, 600 * nm, &qe) / n, 0.27, 1e-12);
}

// Pan 2010 eqs. (6)-(7) on a blackbody: ∫ M_λ λ/(hc) dλ against Gauss-Kronrod quadrature of Planck's photon
// exitance.
TEST(PhysicsPhotometry, PhotonRateOfABlackbodyBand) {
  const double t = 5900.0, lo = 0.3 * um, hi = 0.9 * um;
  const double reference = boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
      [&](double l) { return planck_photon_spectral_exitance(l, t); }, lo, hi, 15, 1e-13);
  const double n = photon_rate(blackbody_exitance_spectrum(t), lo, hi);
  EXPECT_NEAR(n / reference, 1.0, 1e-6);
  const Spectrum half = Spectrum::constant(0.5, "1");
  EXPECT_NEAR(photon_rate(blackbody_exitance_spectrum(t), lo, hi, &half) / n, 0.5, 1e-12);
}

// Pan 2010 eqs. (3)-(7) for the Sun (E-490 shape), 0.3-0.9 µm as for the MSX SBV: photons per second per
// lumen at the pupil, and per lux per m^2.
TEST(PhysicsPhotometry, SolarPhotonsPerLumen) {
  const double n = photons_per_lumen(e490(), v_lambda(), 0.3 * um, 0.9 * um);
  // The same from the two integrals taken separately: photon irradiance in the band / illuminance.
  const double direct = photon_rate(e490(), 0.3 * um, 0.9 * um) / luminous(e490(), v_lambda());
  std::printf("sunlight (E-490), 0.3-0.9 um: %.5e photons s-1 lm-1\n", n);
  EXPECT_NEAR(n / direct, 1.0, 1e-13);
  EXPECT_NEAR(n, 1.8968e16, 0.0001e16);
}

// Pan 2010 eq. (1).
TEST(PhysicsPhotometry, MagnitudeRatio) {
  EXPECT_DOUBLE_EQ(magnitude_ratio(-26.73), 1.0);
  EXPECT_NEAR(magnitude_ratio(-21.73), 1e-2, 1e-15);
  EXPECT_NEAR(magnitude_from_ratio(magnitude_ratio(15.55)), 15.55, 1e-12);
}

}  // namespace

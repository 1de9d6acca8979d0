// Pan et al. 2010 (Acta Optica Sinica 30(10) 2935), the SBV and the auxiliary sensor at their limiting
// magnitudes: each noise term of eq. (9) against hand computation from Table 1, and the solved magnitude
// against the paper's closed form eqs. (11)-(12), evaluated here from the spectra without the chain.
#include "radchain/chain.hpp"
#include "radchain/constants.hpp"
#include "radchain/physics/photometry.hpp"
#include "radchain/spectrum.hpp"
#include "radchain/spectrum_csv.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace {
using namespace radchain;

const std::string sensors = std::string(RADCHAIN_SOURCE_DIR) + "/sensors/";
const std::string spectra = std::string(RADCHAIN_SOURCE_DIR) + "/spectra/";
constexpr double um = 1e-6;

const Spectrum& e490() {
  static const Spectrum s = load_spectrum_csv(spectra + "am0_astm_e490_00a.csv", "W m-2 m-1").spectrum;
  return s;
}
const Spectrum& v_lambda() {
  static const Spectrum s = load_spectrum_csv(spectra + "cie_1924_photopic_V_1nm.csv", "1").spectrum;
  return s;
}

// One of Pan's sensors, as typed from its table (not read from the chain).
struct PanSensor {
  double threshold, integration_time_s, aperture_m, qe, transmittance, dark_rate, read_noise, full_well, bits;
  double band_lo_m = 0.3 * um, band_hi_m = 0.9 * um;
};
const PanSensor sbv{5.0, 0.625, 0.15, 0.27, 0.56, 18.0, 6.0, 1e5, 12};        // Table 1, T = 5 (§3.3)
const PanSensor auxiliary{4.12, 0.5, 0.22, 0.66, 0.56, 18.0, 6.0, 1e5, 12};   // Table 3 (band, bits, well: SBV's)

double paper_quantisation_variance(const PanSensor& s) { return s.full_well / (std::exp2(s.bits) * std::sqrt(12.0)); }
double emva_quantisation_variance(const PanSensor& s) { return std::pow(s.full_well / std::exp2(s.bits), 2) / 12.0; }

// Eq. (11): S = [T² + √(T⁴ + 4T²(N_d + σ_o² + n_q²))]/2.
double eq11_signal(const PanSensor& s, double quantisation_variance) {
  const double t2 = s.threshold * s.threshold;
  const double floor = s.dark_rate * s.integration_time_s + s.read_noise * s.read_noise + quantisation_variance;
  return 0.5 * (t2 + std::sqrt(t2 * t2 + 4.0 * t2 * floor));
}

// Eq. (12): m = −26.73 − 2.5 lg[ (∫K Φr dλ / ∫_{λ1}^{λ2} Φr η λ dλ) · 2hc[T² + √(…)] / (π E_s D² K_trans s_int) ],
// Φr = the E-490 table (its normalisation cancels), K = 683 V(λ), E_s = 683 ∫ V E_sun dλ the Sun's illuminance.
// E_s over the whole CIE table (360-830 nm), as the sun plugin computes it; ∫KΦr over the same range by default
// (then, Φr being the spectrum E_s is computed from, E_s/∫KΦr = 1: the photometry cancels, as it must), or over
// the 0.38-0.76 µm the paper prints.
double eq12_magnitude(const PanSensor& s, double quantisation_variance, bool printed_photometric_limits = false) {
  const double km = constants::luminous_efficacy_540THz_lm_W;
  const double lo_v = v_lambda().min_wavelength_m(), hi_v = v_lambda().max_wavelength_m();
  const double e_s = km * band_integral({&e490(), &v_lambda()}, lo_v, hi_v);
  const double k_phi = printed_photometric_limits ? km * band_integral({&e490(), &v_lambda()}, 0.38 * um, 0.76 * um)
                                                  : km * band_integral({&e490(), &v_lambda()}, lo_v, hi_v);
  const double hc = constants::planck_J_s * constants::speed_of_light_m_s;
  const double phi_eta_lambda = s.qe * hc * band_integral({&e490()}, s.band_lo_m, s.band_hi_m, Weight::photons);  // ∫ Φr η λ dλ
  const double two_s = 2.0 * eq11_signal(s, quantisation_variance);  // T² + √(…)
  const double bracket = (k_phi / phi_eta_lambda) * 2.0 * hc * two_s /
                         (std::numbers::pi * e_s * s.aperture_m * s.aperture_m * s.transmittance * s.integration_time_s);
  return -26.73 - 2.5 * std::log10(bracket);
}

double solved(const std::string& file, const std::vector<Override>& overrides = {}) {
  Chain chain = load_sensor(sensors + file, overrides);
  const Report r = chain.run();
  EXPECT_TRUE(r.solves.at(0).converged) << r.solves.at(0).message;
  return r.solves.at(0).value_si;
}

TEST(Pan2010Noise, SbvNoiseTermsAtTheLimitingMagnitude) {
  Chain chain = load_sensor(sensors + "msx-sbv.toml");
  const Report r = chain.run();
  auto v = [&](const std::string& name) { return r.value(name).value(); };
  // Table 1: dark 18 e-/pixel/s × 0.625 s = 11.25 e-, √ = 3.3541 e-; read < 6 e- rms taken as 6.
  EXPECT_NEAR(v("detector.dark_electrons"), 18 * 0.625, 1e-12);
  EXPECT_NEAR(v("detector.dark_electrons"), 11.25, 1e-12);
  EXPECT_NEAR(v("detector.dark_noise"), std::sqrt(11.25), 1e-12);
  EXPECT_EQ(v("detector.read_noise"), 6.0);
  // §3.2 3) as printed: n_q² = 1e5/(4096 √12) = 7.0477 "e-²", n_q = 2.6548.
  EXPECT_NEAR(v("detector.quantisation_noise"), std::sqrt(1e5 / (4096 * std::sqrt(12.0))), 1e-12);
  EXPECT_NEAR(v("detector.quantisation_noise"), 2.6548, 5e-5);
  // Shot noise √S and the total of eq. (9); no sky, one pixel, all the energy in it (the paper's assumptions).
  const double s = v("detector.signal_electrons");
  EXPECT_NEAR(v("detector.shot_noise"), std::sqrt(s), 1e-12);
  EXPECT_EQ(v("detector.background_electrons"), 0.0);
  EXPECT_EQ(v("detector.ensquared_energy"), 1.0);
  EXPECT_EQ(v("detector.window_pixel_count"), 1.0);
  const double n = std::sqrt(11.25 + 36 + 1e5 / (4096 * std::sqrt(12.0)) + s);
  EXPECT_NEAR(v("detector.noise_electrons"), n, 1e-12);
  EXPECT_NEAR(v("detector.snr"), 5.0, 1e-10);
  // The signal of eq. (11): 51.406 e-.
  EXPECT_NEAR(s, eq11_signal(sbv, paper_quantisation_variance(sbv)), 1e-9);
  EXPECT_NEAR(s, 51.406, 1e-3);
}

TEST(Pan2010Noise, SolvedMagnitudeIsTheClosedFormOfEquations11And12) {
  // Paper convention (as printed): 15.5565 (printed 15.55) and 17.4052 (printed 17.37).
  const double m_sbv = solved("msx-sbv.toml"), m_aux = solved("pan2010-auxiliary-sensor.toml");
  EXPECT_NEAR(m_sbv, eq12_magnitude(sbv, paper_quantisation_variance(sbv)), 1e-6);
  EXPECT_NEAR(m_aux, eq12_magnitude(auxiliary, paper_quantisation_variance(auxiliary)), 1e-6);
  EXPECT_NEAR(m_sbv, 15.5565, 1e-4);
  EXPECT_NEAR(m_aux, 17.4052, 1e-4);
  // The printed limits 0.38-0.76 µm of the photometric integral miss 7e-6 of V(λ)-weighted sunlight: +8e-6 mag.
  const double printed_limits = eq12_magnitude(sbv, paper_quantisation_variance(sbv), true);
  EXPECT_NEAR(printed_limits - m_sbv, 7.6e-6, 0.5e-6);
  // EMVA 1288 quantisation (n_q = 7.05 e-): 15.3308 and 17.1582 (docs/physics/quantisation.md).
  const std::vector<Override> emva{{"detector.quantisation", "emva"}};
  const double e_sbv = solved("msx-sbv.toml", emva), e_aux = solved("pan2010-auxiliary-sensor.toml", emva);
  EXPECT_NEAR(e_sbv, eq12_magnitude(sbv, emva_quantisation_variance(sbv)), 1e-6);
  EXPECT_NEAR(e_aux, eq12_magnitude(auxiliary, emva_quantisation_variance(auxiliary)), 1e-6);
  EXPECT_NEAR(e_sbv, 15.3308, 1e-4);
  EXPECT_NEAR(e_aux, 17.1582, 1e-4);
  EXPECT_NEAR(std::sqrt(emva_quantisation_variance(sbv)), 7.0477, 1e-4);
}

TEST(Pan2010Noise, AuxiliarySensorNoiseTerms) {
  Chain chain = load_sensor(sensors + "pan2010-auxiliary-sensor.toml");
  const Report r = chain.run();
  auto v = [&](const std::string& name) { return r.value(name).value(); };
  EXPECT_NEAR(v("detector.dark_electrons"), 18 * 0.5, 1e-12);
  EXPECT_EQ(v("detector.read_noise"), 6.0);
  const double s = v("detector.signal_electrons");
  EXPECT_NEAR(s, eq11_signal(auxiliary, paper_quantisation_variance(auxiliary)), 1e-9);
  EXPECT_NEAR(v("detector.snr"), 4.12, 1e-10);
}

}  // namespace

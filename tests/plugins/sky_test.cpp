// The sky as its own radiation (issue 13 item 3): the site's sky (flat in f_ν, or a spectral radiance table
// such as Rubin's dark-sky SED) imaged by the telescope as an extended scene and counted by the emva1288
// detector by étendue. Every number against a hand integral on the tables' own grids, or a published value.
#include "radchain/chain.hpp"
#include "radchain/constants.hpp"
#include "radchain/spectrum_csv.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

namespace {
using namespace radchain;

const std::string spectra = std::string(RADCHAIN_SOURCE_DIR) + "/spectra/";
const std::string sensors = std::string(RADCHAIN_SOURCE_DIR) + "/sensors/";

// AB: f_ν = 10^{-0.4·48.60} erg s-1 cm-2 Hz-1 (Oke & Gunn 1983) = that × 1e-3 W m-2 Hz-1; one arcsec² in sr.
const double ab_f_nu = std::pow(10.0, -0.4 * 48.60) * 1e-3;
const double arcsec2_sr = std::pow(std::numbers::pi / (180.0 * 3600.0), 2);

std::string read(const std::string& path) {
  std::ostringstream s;
  s << std::ifstream(path).rdbuf();
  return s.str();
}

// sensors/rubin-lsst-r-m5.toml with its `sky_brightness = 21.2 ...` line replaced by `sky` and more lines appended.
Report run_rubin_r(const std::string& name, const std::string& sky, const std::string& extra = "") {
  std::string text = read(sensors + "rubin-lsst-r-m5.toml");
  const auto at = text.find("sky_brightness = 21.2");
  const auto end = text.find('\n', at);
  text.replace(at, end - at, sky);
  text += extra;
  const auto path = std::filesystem::temp_directory_path() / ("radchain_sky_" + std::to_string(::getpid()) + "_" + name + ".toml");
  std::ofstream(path) << text;
  Chain chain = load_sensor(path.string());
  Report r = chain.run();
  std::filesystem::remove(path);
  return r;
}

// ∫ a(λ) b(λ) w(λ) dλ by the trapezoid rule on a's grid (b interpolated), over a's whole table.
template <class W>
double trapezoid(const Spectrum& a, const Spectrum& b, W w) {
  double sum = 0;
  auto f = [&](Eigen::Index k) {
    const double l = a.wavelength_m()(k);
    return a.value()(k) * b(l) * w(l);
  };
  for (Eigen::Index i = 1; i < a.size(); ++i)
    sum += 0.5 * (f(i) + f(i - 1)) * (a.wavelength_m()(i) - a.wavelength_m()(i - 1));
  return sum;
}

// SMTN-002's dark sky in r is the AB magnitude of lsst/throughputs' darksky.dat through hardware_r (SMTN-002 text:
// "the value for the sky spectrum should be multiplied by only the hardware"; its notebook prints skyMag rounded
// to 0.01: 21.2 = 21.20). The table's AB mag/arcsec² in the hardware band, from the site, and by hand.
TEST(SkyTable, RubinDarkSkyInRIsSmtn002Value) {
  const Spectrum sky = load_spectrum_csv(spectra + "lsst_darksky_throughputs1.9.csv", "W m-2 sr-1 m-1").spectrum;
  const Spectrum hw = load_spectrum_csv(spectra + "lsst_hardware_r_throughputs1.9.csv", "1").spectrum;
  // Photon-counting AB magnitude: −2.5 lg(∫ L T λ dλ / ∫ L_AB T λ dλ), L_AB = f_ν c/λ² per arcsec².
  const double photons = trapezoid(hw, sky, [](double l) { return l; });
  const double ab_photons = trapezoid(hw, Spectrum::constant(1.0, "1"), [&](double l) {
    return ab_f_nu * constants::speed_of_light_m_s / (l * l) / arcsec2_sr * l;
  });
  const double by_hand = -2.5 * std::log10(photons / ab_photons);
  EXPECT_NEAR(by_hand, 21.20, 0.005);  // SMTN-002 dark-sky table, r (two decimals)

  const Report r = run_rubin_r("table", "sky_table = \"lsst_darksky_throughputs1.9.csv\"\nsky_band = \"lsst_hardware_r_throughputs1.9.csv\"");
  EXPECT_NEAR(r.value("atmosphere.sky_brightness").value(), by_hand, 1e-6);
  // The sky per pixel by étendue: t A Ω_pix ∫ L_λ S_hw λ/(hc) dλ, A = π 6.423²/4, Ω_pix = (10 µm / 10.31 m)² sr.
  const double area = std::numbers::pi / 4 * 6.423 * 6.423, omega = std::pow(10e-6 / 10.31, 2);
  const double sky_e = 30 * area * omega * photons / (constants::planck_J_s * constants::speed_of_light_m_s);
  EXPECT_NEAR(r.value("detector.sky_electrons_per_pixel").value() / sky_e, 1.0, 1e-6);

  // The flat 21.2 of the bundled file: the same count within 10^{0.4 (21.2 − m_table)} (hardware-only band).
  const Report flat = run_rubin_r("flat", "sky_brightness = 21.2");
  EXPECT_NEAR(r.value("detector.sky_electrons_per_pixel").value() / flat.value("detector.sky_electrons_per_pixel").value(),
              std::pow(10.0, 0.4 * (21.2 - by_hand)), 1e-6);
}

// A table normalised to m in the detector's own band counts exactly what a flat-f_ν sky of m counts.
TEST(SkyTable, NormalisedTableCountsLikeFlatSkyInTheSameBand) {
  const Report table = run_rubin_r("normalised", "sky_table = \"lsst_darksky_throughputs1.9.csv\"\n"
                                                 "sky_band = \"lsst_hardware_r_throughputs1.9.csv\"\nsky_brightness = 20.5");
  const Report flat = run_rubin_r("flat205", "sky_brightness = 20.5");
  EXPECT_DOUBLE_EQ(table.value("atmosphere.sky_brightness").value(), 20.5);
  EXPECT_NEAR(table.value("detector.sky_electrons_per_pixel").value() / flat.value("detector.sky_electrons_per_pixel").value(),
              1.0, 1e-6);
}

// The sky passes the optics' transmittance_curve like the target (it used to skip it). Without the atmosphere's
// table (which dims the star, not the sky), a flat-f_ν star and a flat-f_ν sky through the same curve lose the
// same fraction: ∫ T(λ) S(λ)/λ dλ / ∫ S(λ)/λ dλ (S the hardware curve, T the SDSS r curve as an optics curve).
TEST(SkyTable, SkyPassesTheOpticsTransmittanceCurve) {
  auto with_curve = [](const std::string& name, bool curve) {
    std::string text = read(sensors + "rubin-lsst-r-m5.toml");
    const auto table = text.find("transmittance_table");
    text.replace(table, text.find("seeing") - table, "extinction = 0\n");
    const std::string key = "transmittance = 1 ";
    if (curve) text.insert(text.find(key), "transmittance_curve = \"sdss_r_doi2010.csv\"\n");
    const auto path = std::filesystem::temp_directory_path() / ("radchain_sky_" + std::to_string(::getpid()) + "_" + name + ".toml");
    std::ofstream(path) << text;
    Chain chain = load_sensor(path.string());
    chain.solves.clear();  // at the file's start magnitude: signal and sky as they are
    Report r = chain.run();
    std::filesystem::remove(path);
    return r;
  };
  const Report plain = with_curve("plain", false), filtered = with_curve("curve", true);
  const Spectrum hw = load_spectrum_csv(spectra + "lsst_hardware_r_throughputs1.9.csv", "1").spectrum;
  const Spectrum t = load_spectrum_csv(spectra + "sdss_r_doi2010.csv", "1").spectrum;
  const double fraction = trapezoid(hw, t, [](double l) { return 1.0 / l; }) /
                          trapezoid(hw, Spectrum::constant(1.0, "1"), [](double l) { return 1.0 / l; });
  ASSERT_LT(fraction, 0.9);  // the curve matters
  auto ratio = [&](const std::string& n) { return filtered.value(n).value() / plain.value(n).value(); };
  EXPECT_NEAR(ratio("detector.sky_electrons_per_pixel"), fraction, 2e-3 * fraction);
  EXPECT_NEAR(ratio("detector.image_electrons"), fraction, 2e-3 * fraction);
  EXPECT_NEAR(ratio("detector.sky_electrons_per_pixel") / ratio("detector.image_electrons"), 1.0, 1e-5);
}

}  // namespace

// The sky as its own radiation: the site's sky (flat in f_ν, or a spectral radiance table
// such as Rubin's dark-sky SED) imaged by the telescope as an extended scene and counted by the emva1288
// detector by étendue. Every number against a hand integral on the tables' own grids, or a published value.
#include "radchain/chain.hpp"
#include "radchain/constants.hpp"
#include "radchain/physics/zodiacal.hpp"
#include "radchain/spectrum_csv.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
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

// Runs a sensor file's text (without its [[solve]] entries when `solve` is false).
Report run_text(const std::string& name, const std::string& text, bool solve = true) {
  const auto path = std::filesystem::temp_directory_path() / ("radchain_sky_" + std::to_string(::getpid()) + "_" + name + ".toml");
  std::ofstream(path) << text;
  Chain chain = load_sensor(path.string());
  if (!solve) chain.solves.clear();
  Report r = chain.run();
  std::filesystem::remove(path);
  return r;
}

// sensors/rubin-lsst-r-m5.toml with its `sky_brightness = 21.2 ...` line replaced by `sky`.
Report run_rubin_r(const std::string& name, const std::string& sky) {
  std::string text = read(sensors + "rubin-lsst-r-m5.toml");
  const auto at = text.find("sky_brightness = 21.2");
  text.replace(at, text.find('\n', at) - at, sky);
  return run_text(name, text);
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
// Seeing quoted at the zenith or along the line of sight (seeing_at): both are published; the same atmosphere said
// either way gives the same PSF and limit. At X = 1.5: θ(X) = θ_zenith X^0.6 (Roddier 1981).
TEST(SiteSeeing, ZenithOrLineOfSightAreOneAtmosphereSaidTwoWays) {
  const std::string rubin = read(sensors + "rubin-lsst-r-m5.toml");
  auto with = [&](const std::string& name, const std::string& seeing_lines) {
    std::string text = rubin;
    const auto at = text.find("seeing = \"0.83 arcsec\"");
    text.replace(at, text.find('\n', at) - at, seeing_lines);
    const auto x = text.find("airmass = 1.0");
    text.replace(x, std::string("airmass = 1.0").size(), "airmass = 1.5");
    return run_text(name, text);
  };
  const double arcsec = std::numbers::pi / (180.0 * 3600.0), x = 1.5, los = 0.83 * std::pow(x, 0.6);
  const Report zenith = with("seeing-zenith", "seeing = \"0.83 arcsec\"");
  const Report sight = with("seeing-los", fmt::format("seeing = \"{:.17g} arcsec\"\nseeing_at = \"line_of_sight\"", los));
  EXPECT_NEAR(*zenith.value("atmosphere.seeing_fwhm") / arcsec, los, 1e-12);
  EXPECT_NEAR(*zenith.value("atmosphere.seeing_zenith_fwhm") / arcsec, 0.83, 1e-12);
  EXPECT_NEAR(*sight.value("atmosphere.seeing_fwhm") / arcsec, los, 1e-12);
  EXPECT_NEAR(*sight.value("atmosphere.seeing_zenith_fwhm") / arcsec, 0.83, 1e-12);
  EXPECT_NEAR(*sight.value("detector.psf_fwhm"), *zenith.value("detector.psf_fwhm"), 1e-12 * *zenith.value("detector.psf_fwhm"));
  EXPECT_NEAR(*sight.value("target.magnitude"), *zenith.value("target.magnitude"), 1e-9);
  // and the zenith value quoted as if it were the line of sight's is a different, finer PSF: the key matters
  const Report mistaken = with("seeing-mistaken", "seeing = \"0.83 arcsec\"\nseeing_at = \"line_of_sight\"");
  EXPECT_GT(*mistaken.value("target.magnitude"), *zenith.value("target.magnitude") + 0.1);
}

// A site given only its airmass takes the extinction practice uses when a site has no curve of its own: Rubin's
// fiducial Cerro Pachón atmosphere (lsst/throughputs 1.9 baseline/atmos_10.dat, X = 1) as τ(λ)^X. The same as
// naming that table, to the bit; the same m5 as the file's own 400-900 nm cut of it; and the report says so.
TEST(SiteExtinction, TheDefaultIsRubinsCerroPachonCurve) {
  const std::string rubin = read(sensors + "rubin-lsst-r-m5.toml");
  auto with = [&](const std::string& name, const std::string& extinction_lines) {
    std::string text = rubin;
    const auto at = text.find("transmittance_table = ");
    const auto end = text.find('\n', text.find("table_airmass = ", at));
    text.replace(at, end - at, extinction_lines);
    const auto x = text.find("airmass = 1.0");
    text.replace(x, std::string("airmass = 1.0").size(), "airmass = 1.3");
    return run_text(name, text);
  };
  const Report by_default = with("extinction-default", "");
  const Report named = with("extinction-named", "transmittance_table = \"lsst_atmos_10_300-1150nm_throughputs1.9.csv\"");
  const Report cut = with("extinction-cut", "transmittance_table = \"lsst_atmos_10_throughputs1.9.csv\"\ntable_airmass = 1.0");
  ASSERT_TRUE(by_default.solves.at(0).converged);
  EXPECT_EQ(by_default.solves.at(0).value_si, named.solves.at(0).value_si);
  EXPECT_NEAR(by_default.solves.at(0).value_si, cut.solves.at(0).value_si, 1e-12);
  const auto row = std::find_if(by_default.results.begin(), by_default.results.end(),
                                [](const auto& r) { return r.name == "atmosphere.transmittance"; });
  ASSERT_NE(row, by_default.results.end());
  EXPECT_NE(row->equation.find("default site curve"), std::string::npos) << row->equation;
  // and extinction by a coefficient still replaces it: k = 0 is no atmosphere at all
  const Report clear = with("extinction-zero", "extinction = 0.0");
  EXPECT_GT(clear.solves.at(0).value_si, by_default.solves.at(0).value_si + 0.1);
}

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
    return run_text(name, text, false);  // at the file's start magnitude: signal and sky as they are
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

// ---- Space: zodiacal light (Leinert et al. 1998 Table 17) and stray light, plugins/atmosphere/space.cpp ----

// Table lookup: nodes exactly (10⁻⁸ W m⁻² sr⁻¹ µm⁻¹ = 1e-2 W m⁻² sr⁻¹ m⁻¹), a cell's centre is the mean of its four
// corners, the table is symmetric about the Sun-antisun line, and there is no value within ~15-30° of the Sun.
TEST(Zodiacal, LeinertTable17Lookup) {
  using physics::leinert_zodiacal_radiance_500nm;
  EXPECT_DOUBLE_EQ(leinert_zodiacal_radiance_500nm(90, 30).value(), 132e-2);   // Table 17: λ−λ⊙ = 90°, β = 30°
  EXPECT_DOUBLE_EQ(leinert_zodiacal_radiance_500nm(180, 0).value(), 230e-2);   // gegenschein
  EXPECT_DOUBLE_EQ(leinert_zodiacal_radiance_500nm(30, 0).value(), 2480e-2);
  for (double lon : {0.0, 45.0, 137.0}) EXPECT_DOUBLE_EQ(leinert_zodiacal_radiance_500nm(lon, 90).value(), 77e-2);
  EXPECT_NEAR(leinert_zodiacal_radiance_500nm(97.5, 27.5).value(), (147 + 132 + 133 + 119) / 4.0 * 1e-2, 1e-12);
  EXPECT_DOUBLE_EQ(leinert_zodiacal_radiance_500nm(270, -30).value(), leinert_zodiacal_radiance_500nm(90, 30).value());
  EXPECT_FALSE(leinert_zodiacal_radiance_500nm(10, 0).has_value());
  EXPECT_FALSE(leinert_zodiacal_radiance_500nm(12, 7).has_value());  // a corner (10°, 5°) has no value
}

// S10 → mag/arcsec² by hand: one V = 10 star per deg² spread over 3600² arcsec² is 10 + 5 lg 3600 = 27.78.
// The ecliptic pole, 77e-8 W m⁻² sr⁻¹ µm⁻¹ = 60.2 S10, is the published ≈ 23.3 V mag/arcsec² (Leinert et al.
// 1998). The S10 unit in W: the E-490 Sun at 500 nm dimmed to V = 10 (V⊙ = −26.73, Pan 2010 eq. 1) per deg².
TEST(Zodiacal, S10UnitsAndTheEclipticPole) {
  EXPECT_NEAR(physics::s10_to_mag_per_arcsec2(1.0), 10 + 5 * std::log10(3600.0), 1e-12);
  EXPECT_NEAR(physics::s10_to_mag_per_arcsec2(100.0), 27.782 - 5.0, 1e-3);
  const double pole_s10 = physics::leinert_zodiacal_radiance_500nm(0, 90).value() / physics::s10_W_m2_sr_m;
  EXPECT_NEAR(pole_s10, 60.2, 0.05);
  EXPECT_NEAR(physics::s10_to_mag_per_arcsec2(pole_s10), 23.3, 0.05);
  const Spectrum sun = load_spectrum_csv(spectra + "am0_astm_e490_00a.csv", "W m-2 m-1").spectrum;
  const double deg2_sr = std::pow(std::numbers::pi / 180, 2);
  const double s10 = sun(500e-9) * std::pow(10.0, -0.4 * (10 + 26.73)) / deg2_sr;
  EXPECT_NEAR(s10 / physics::s10_W_m2_sr_m, 1.0, 0.02);
}

std::string space_sensor(const std::string& atmosphere) {
  return R"([sensor]
name = "space"
[source]
plugin = "sun"
[atmosphere]
plugin = "space"
)" + atmosphere + R"(
[target]
plugin = "point_source"
system = "vega"
band = "johnson_cousins_V_bessell1990.csv"
magnitude = 15
[optics]
plugin = "telescope"
aperture = "15 cm"
focal_length = "0.5 m"
[detector]
plugin = "emva1288"
band_min = "0.4 um"
band_max = "0.9 um"
qe = 0.6
gain = "0.5 DN/e-"
read_noise = "3 e-"
full_well = "20000 e-"
adc_bits = 16
pixel_pitch = "5 um"
integration_time = "10 s"
)";
}

// The background electrons by étendue, by hand: L_λ = L_500 E⊙(λ)/E⊙(500 nm), one pixel of p² behind f/3.33
// sees Ω = π/(4N²): B = t qe p² Ω ∫ L_λ λ/(hc) dλ over 400-900 nm (trapezoid on the E-490 nodes).
TEST(Zodiacal, BackgroundElectronsByHandAndStrayLightAdds) {
  const Report zodi = run_text("zodi", space_sensor("zodiacal_longitude = \"90 deg\"\nzodiacal_latitude = \"30 deg\""));
  auto v = [](const Report& r, const std::string& n) { return r.value(n).value(); };
  EXPECT_DOUBLE_EQ(v(zodi, "atmosphere.zodiacal_radiance_500nm"), 1.32);
  EXPECT_NEAR(v(zodi, "atmosphere.zodiacal_surface_brightness"), physics::s10_to_mag_per_arcsec2(132 / 1.28), 1e-12);
  const Spectrum sun = load_spectrum_csv(spectra + "am0_astm_e490_00a.csv", "W m-2 m-1").spectrum;
  std::vector<double> l = {400e-9};
  for (Eigen::Index i = 0; i < sun.size(); ++i)
    if (sun.wavelength_m()(i) > 400e-9 && sun.wavelength_m()(i) < 900e-9 * (1 - 1e-12)) l.push_back(sun.wavelength_m()(i));
  l.push_back(900e-9);  // the band's limits as nodes (the table's "900" nm reads as 900e-9 within rounding)
  double photons = 0;
  auto f = [&](double x) { return 1.32 * sun(x) / sun(500e-9) * x / (constants::planck_J_s * constants::speed_of_light_m_s); };
  for (std::size_t i = 1; i < l.size(); ++i) photons += 0.5 * (f(l[i]) + f(l[i - 1])) * (l[i] - l[i - 1]);
  const double n = 0.5 / 0.15, omega = std::numbers::pi / (4 * n * n);
  const double expected = 10 * 0.6 * 25e-12 * omega * photons;
  EXPECT_NEAR(v(zodi, "detector.sky_electrons_per_pixel") / expected, 1.0, 1e-6);
  // Stray light of 1e-6 W m⁻² sr⁻¹ µm⁻¹ (= 1 W m⁻² sr⁻¹ m⁻¹) at 500 nm, same spectrum: the count scales by 2.32/1.32.
  const Report both = run_text("stray", space_sensor("zodiacal_longitude = \"90 deg\"\nzodiacal_latitude = \"30 deg\"\n"
                                                     "stray_light = \"1e-6 W m-2 sr-1 um-1\""));
  EXPECT_NEAR(v(both, "atmosphere.background_radiance_500nm"), 2.32, 1e-12);
  EXPECT_NEAR(v(both, "detector.sky_electrons_per_pixel") / v(zodi, "detector.sky_electrons_per_pixel"), 2.32 / 1.32, 1e-12);
  // No atmosphere on the line of sight: the star's signal equals that of atmosphere "none".
  std::string none = space_sensor("");
  none.replace(none.find("plugin = \"space\""), 16, "plugin = \"none\"");
  const Report vacuum = run_text("none", none);
  EXPECT_DOUBLE_EQ(v(zodi, "detector.image_electrons"), v(vacuum, "detector.image_electrons"));
}

// A stray-light table, two independent references:
// - a flat 1 W m⁻² sr⁻¹ m⁻¹ over 300-1000 nm behind the same optics and detector, in closed form:
//   B = t qe p² Ω ∫ L λ/(hc) dλ = t qe p² Ω L (λ₂² − λ₁²)/(2hc) over the band 400-900 nm;
// - the solar spectrum's shape at 1 W m⁻² sr⁻¹ m⁻¹ at 500 nm as a table: the same count as `stray_light` of that
//   radiance (the scalar form), and it adds to the zodiacal light.
TEST(Zodiacal, StrayLightTableFlatByHandAndSolarShapeAsTheScalarForm) {
  const auto dir = std::filesystem::temp_directory_path();
  const std::string flat_name = "radchain_sky_" + std::to_string(::getpid()) + "_flat_stray.csv";
  std::ofstream(dir / flat_name) << "# test: flat stray light\nwavelength_nm,radiance_W_m-2_sr-1_m-1\n300,1\n1000,1\n";
  const Report flat = run_text("flat_stray", space_sensor("stray_light_table = \"" + flat_name + "\""));
  auto v = [](const Report& r, const std::string& n) { return r.value(n).value(); };
  const double hc = constants::planck_J_s * constants::speed_of_light_m_s;
  const double n = 0.5 / 0.15, omega = std::numbers::pi / (4 * n * n);
  const double by_hand = 10 * 0.6 * 25e-12 * omega * 1.0 * (900e-9 * 900e-9 - 400e-9 * 400e-9) / (2 * hc);
  EXPECT_NEAR(v(flat, "detector.sky_electrons_per_pixel") / by_hand, 1.0, 1e-9);
  EXPECT_DOUBLE_EQ(v(flat, "atmosphere.stray_light_table_radiance_500nm"), 1.0);
  EXPECT_DOUBLE_EQ(v(flat, "atmosphere.background_radiance_500nm"), 1.0);

  const Spectrum sun = load_spectrum_csv(spectra + "am0_astm_e490_00a.csv", "W m-2 m-1").spectrum;
  const std::string solar_name = "radchain_sky_" + std::to_string(::getpid()) + "_solar_stray.csv";
  {
    std::ofstream out(dir / solar_name);
    out << "# test: the E-490 shape at 1 W m-2 sr-1 m-1 at 500 nm\nwavelength_nm,radiance_W_m-2_sr-1_m-1\n";
    out.precision(17);
    for (Eigen::Index i = 0; i < sun.size(); ++i)
      if (sun.wavelength_m()(i) >= 300e-9 && sun.wavelength_m()(i) <= 1000e-9)
        out << sun.wavelength_m()(i) * 1e9 << "," << sun.value()(i) / sun(500e-9) << "\n";
  }
  const std::string zodi = "zodiacal_longitude = \"90 deg\"\nzodiacal_latitude = \"30 deg\"\n";
  const Report table = run_text("solar_stray", space_sensor(zodi + "stray_light_table = \"" + solar_name + "\""));
  const Report scalar = run_text("scalar_stray", space_sensor(zodi + "stray_light = \"1e-6 W m-2 sr-1 um-1\""));
  EXPECT_NEAR(v(table, "detector.sky_electrons_per_pixel") / v(scalar, "detector.sky_electrons_per_pixel"), 1.0, 1e-9);
  EXPECT_NEAR(v(table, "atmosphere.background_radiance_500nm"), 2.32, 1e-9);
  EXPECT_DOUBLE_EQ(v(table, "atmosphere.zodiacal_radiance_500nm"), 1.32);
  std::filesystem::remove(dir / flat_name);
  std::filesystem::remove(dir / solar_name);
}

}  // namespace

// atmosphere/airmass_lut (issue 14 item 2: an RT code's tables with airmass as a LUT axis): the Rubin site's MODTRAN
// transmittances at X = 1.0, 1.5, 2.0, 2.5 (lsst/throughputs atmos/, shipped in spectra/). At a node the table
// itself; between nodes ln τ linear in X (τ_i^(1−w) τ_(i+1)^w), against band means computed here from the CSV rows;
// the path radiance linear in X; the bad inputs refused at their keys.
#include "radchain/chain.hpp"
#include "radchain/error.hpp"
#include "radchain/physics/solar_position.hpp"
#include "radchain/sensor_file.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace {
using namespace radchain;

const std::string spectra = std::string(RADCHAIN_SOURCE_DIR) + "/spectra/";

std::vector<std::pair<double, double>> rows_of(const std::string& file) {  // (λ nm, τ)
  std::ifstream in(spectra + file);
  std::vector<std::pair<double, double>> rows;
  std::string line;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#' && line[0] != 'w') {
      const auto comma = line.find(',');
      rows.emplace_back(std::stod(line.substr(0, comma)), std::stod(line.substr(comma + 1)));
    }
  return rows;
}

// Trapezoid over 400-700 nm of f(τ_a, τ_b) on the tables' shared 0.1 nm grid (400 and 700 are grid points), / 300 nm.
template <class F>
double band_mean(const std::string& a, const std::string& b, F f) {
  const auto ra = rows_of(a), rb = rows_of(b);
  double sum = 0;
  for (std::size_t i = 0; i + 1 < ra.size(); ++i) {
    const double l0 = ra[i].first, l1 = ra[i + 1].first;
    if (l0 < 400 - 1e-9 || l1 > 700 + 1e-9) continue;
    sum += 0.5 * (f(ra[i].second, rb[i].second) + f(ra[i + 1].second, rb[i + 1].second)) * (l1 - l0);
  }
  return sum / 300.0;
}

const std::string x10 = "lsst_atmos_aerosol_X10_throughputs1.9.csv", x15 = "lsst_atmos_aerosol_X15_throughputs1.9.csv";

std::string sensor(const std::string& atmosphere) {
  return R"([sensor]
name = "airmass LUT test"
[platform]
plugin = "earth_orbit"
altitude = "700 km"
[source]
plugin = "sun"
[atmosphere]
plugin = "airmass_lut"
tables = [")" + x10 + "\", \"" + x15 + R"(", "lsst_atmos_aerosol_X20_throughputs1.9.csv", "lsst_atmos_aerosol_X25_throughputs1.9.csv"]
airmasses = [1.0, 1.5, 2.0, 2.5]
)" + atmosphere + R"(
[target]
plugin = "reflectance_ground"
reflectance = 0.3
[optics]
plugin = "telescope"
aperture = "10 cm"
focal_length = "0.8 m"
[detector]
plugin = "emva1288"
band_min = "0.63 um"
band_max = "0.69 um"
qe = 0.5
gain = "0.1 DN/e-"
dark_noise = "20 e-"
saturation_capacity = "80000 e-"
adc_bits = 14
pixel_pitch = "10 um"
integration_time = "2 ms"
)";
}

Report run(const std::string& atmosphere) {
  Chain chain = load_sensor_text(sensor(atmosphere), "airmass_lut_test.toml");
  return chain.run();
}

double v(const Report& r, const std::string& name) { return r.value(name).value(); }

TEST(AirmassLut, NodesAreTheTablesAndBetweenThemLnTauIsLinearInAirmass) {
  const Report node = run("airmass = 1.5");
  EXPECT_NEAR(v(node, "atmosphere.transmittance"), band_mean(x15, x15, [](double a, double) { return a; }), 1e-9);
  EXPECT_EQ(v(node, "atmosphere.airmass"), 1.5);
  const Report between = run("airmass = 1.25");
  EXPECT_NEAR(v(between, "atmosphere.lut_weight"), 0.5, 1e-15);
  EXPECT_NEAR(v(between, "atmosphere.transmittance"), band_mean(x10, x15, [](double a, double b) { return std::sqrt(a * b); }), 1e-9);
  // The scene seen through it: darker than at X = 1, brighter than at X = 1.5 (τ crossed down and up).
  const double at1 = v(run("airmass = 1.0"), "detector.signal_electrons"), at15 = v(node, "detector.signal_electrons");
  EXPECT_GT(v(between, "detector.signal_electrons"), at15);
  EXPECT_LT(v(between, "detector.signal_electrons"), at1);
}

// A held-out RT run: a LUT of the X = 1.5 and 2.5 tables, read at X = 2.0, against MODTRAN's own X = 2.0 table.
// ln τ linear in X gives the 400-700 nm mean to 3.4e-4 (0.73897 vs 0.73872), where Beer's law from X = 1 (τ₁²)
// is further off; checked to 1e-3. (In the saturated O₂ A band, 759-770 nm, the LUT is within 0.3 % and Beer's
// τ₁^2.5 is 17 % low at X = 2.5: docs/eo-imagers.md.)
TEST(AirmassLut, InterpolationReproducesAHeldOutRtRun) {
  std::string text = sensor("airmass = 2.0");
  text.replace(text.find("tables = ["), text.find("]\n", text.find("tables = [")) - text.find("tables = [") + 1,
               "tables = [\"lsst_atmos_aerosol_X15_throughputs1.9.csv\", \"lsst_atmos_aerosol_X25_throughputs1.9.csv\"]");
  text.replace(text.find("[1.0, 1.5, 2.0, 2.5]"), 20, "[1.5, 2.5]");
  Chain chain = load_sensor_text(text, "airmass_lut_test.toml");
  const Report r = chain.run();
  const std::string x20 = "lsst_atmos_aerosol_X20_throughputs1.9.csv";
  const double modtran = band_mean(x20, x20, [](double a, double) { return a; });
  EXPECT_NEAR(v(r, "atmosphere.transmittance"), modtran, 1e-3 * modtran);
  const double beer = band_mean(x10, x10, [](double a, double) { return a * a; });
  EXPECT_GT(std::abs(beer - modtran), std::abs(v(r, "atmosphere.transmittance") - modtran));
}

TEST(AirmassLut, PathRadianceIsInterpolatedLinearly) {
  // 1 and 3 W m-2 sr-1 nm-1, flat over 400-700 nm, at the first two nodes (the others repeat 3).
  const auto dir = std::filesystem::temp_directory_path();
  std::vector<std::string> files;
  for (int k = 0; k < 4; ++k) {
    files.push_back((dir / ("radchain_lut_path_" + std::to_string(::getpid()) + "_" + std::to_string(k) + ".csv")).string());
    const int level = k == 0 ? 1 : 3;
    std::ofstream(files.back()) << "# test table\nwavelength_nm,path_radiance_W_m-2_sr-1_nm-1\n400," << level << "\n700," << level << "\n";
  }
  std::string list = "path_radiance_tables = [";
  for (std::size_t k = 0; k < files.size(); ++k) list += (k ? ", \"" : "\"") + files[k] + "\"";
  const Report r = run("airmass = 1.25\n" + list + "]");
  for (const auto& f : files) std::filesystem::remove(f);
  EXPECT_NEAR(v(r, "atmosphere.path_radiance"), 2.0 * 300.0, 1e-9);  // (1 + 3)/2 W m-2 sr-1 nm-1 over 300 nm
  EXPECT_GT(v(r, "detector.path_radiance_electrons"), 0.0);
}

// A low Sun over a nadir view: the down path at X_s, the line of sight at X_v. The Sun's band mean is its node's
// table; the scene's light crosses τ(X_s) τ(X_v), so swapping the two airmasses gives the same signal, which lies
// between the one-airmass scenes at either value; without sun_airmass both paths take the line of sight's.
TEST(AirmassLut, TheSunsPathAndTheLineOfSightHaveTheirOwnAirmasses) {
  const std::string x20 = "lsst_atmos_aerosol_X20_throughputs1.9.csv";
  const Report split = run("airmass = 1.0\nsun_airmass = 2.0");
  EXPECT_NEAR(v(split, "atmosphere.sun_transmittance"), band_mean(x20, x20, [](double a, double) { return a; }), 1e-9);
  EXPECT_NEAR(v(split, "atmosphere.transmittance"), band_mean(x10, x10, [](double a, double) { return a; }), 1e-9);
  EXPECT_EQ(v(split, "atmosphere.sun_airmass"), 2.0);
  EXPECT_EQ(v(split, "atmosphere.airmass"), 1.0);
  const double s12 = v(split, "detector.signal_electrons");
  const double s21 = v(run("airmass = 2.0\nsun_airmass = 1.0"), "detector.signal_electrons");
  EXPECT_NEAR(s12, s21, 1e-12 * s12);
  EXPECT_LT(s12, v(run("airmass = 1.0"), "detector.signal_electrons"));
  EXPECT_GT(s12, v(run("airmass = 2.0"), "detector.signal_electrons"));
  const Report same = run("airmass = 1.25");
  EXPECT_EQ(v(same, "atmosphere.sun_airmass"), 1.25);
  EXPECT_EQ(v(same, "detector.signal_electrons"), v(run("airmass = 1.25\nsun_airmass = 1.25"), "detector.signal_electrons"));
}

// The Sun's zenith given once, to the source: the target's cos θ_s and the down path's airmass follow from it.
// Kasten & Young 1989 against an independent fit, Hardie 1962's polynomial in sec z − 1 (to 0.2 % up to 75°), and
// the chain against the same numbers given by hand (the target's solar_zenith, the atmosphere's sun_airmass).
TEST(AirmassLut, TheSunsAirmassFollowsTheSourcesZenith) {
  using radchain::physics::kasten_young_airmass;
  const double deg = std::numbers::pi / 180;
  for (double z : {0.0, 30.0, 45.0, 60.0, 70.0, 75.0}) {
    const double s = 1 / std::cos(z * deg) - 1;
    const double hardie = s + 1 - 0.0018167 * s - 0.002875 * s * s - 0.0008083 * s * s * s;
    EXPECT_NEAR(kasten_young_airmass(z * deg) / hardie, 1.0, 2e-3) << z;
  }
  EXPECT_NEAR(kasten_young_airmass(90 * deg), 37.92, 0.01);
  auto with_sun = [](const std::string& sun, const std::string& atmosphere, const std::string& target) {
    std::string text = sensor(atmosphere);
    text.insert(text.find("plugin = \"sun\"\n") + 15, sun);
    text.insert(text.find("reflectance = 0.3\n") + 18, target);
    return load_sensor_text(text, "airmass_lut_test.toml").run();
  };
  const Report derived = with_sun("solar_zenith = \"60 deg\"\n", "airmass = 1.0", "");
  const double x_sun = kasten_young_airmass(60 * deg);
  EXPECT_NEAR(v(derived, "atmosphere.sun_airmass"), x_sun, 1e-12);
  EXPECT_NEAR(v(derived, "target.cos_solar_zenith"), 0.5, 1e-12);
  EXPECT_NEAR(v(derived, "source.solar_zenith"), 60 * deg, 1e-15);
  const Report by_hand = with_sun("", "airmass = 1.0\nsun_airmass = " + std::to_string(x_sun), "solar_zenith = \"60 deg\"\n");
  EXPECT_NEAR(v(derived, "detector.signal_electrons") / v(by_hand, "detector.signal_electrons"), 1.0, 1e-6);  // (to_string: 6 decimals)
  EXPECT_LT(v(derived, "atmosphere.sun_transmittance"), v(derived, "atmosphere.transmittance"));
  // Given twice, or a Sun too low for the tables: refused at a key, with the numbers.
  auto error_of = [&](const std::string& sun, const std::string& atmosphere, const std::string& target) {
    try {
      (void)with_sun(sun, atmosphere, target);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  const std::string sun60 = "solar_zenith = \"60 deg\"\n";
  EXPECT_NE(error_of(sun60, "airmass = 1.0", "solar_zenith = \"60 deg\"\n").find("the source gives solar_zenith"), std::string::npos);
  EXPECT_NE(error_of(sun60, "airmass = 1.0\nsun_airmass = 2", "").find("sun_airmass = 2: the source gives solar_zenith"), std::string::npos);
  EXPECT_NE(error_of("solar_zenith = \"70 deg\"\n", "airmass = 1.0", "").find("crosses 2.9"), std::string::npos)
      << error_of("solar_zenith = \"70 deg\"\n", "airmass = 1.0", "");
}

TEST(AirmassLut, BadTablesAreRefusedAtTheirKeys) {
  auto error_of = [](const std::string& text) {
    try {
      (void)load_sensor_text(text, "airmass_lut_test.toml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_NE(error_of(sensor("airmass = 3")).find("airmass = 3: 3 is outside the table's nodes [1, 2.5] (no extrapolation)"),
            std::string::npos);
  EXPECT_NE(error_of(sensor("airmass = 1\nsun_airmass = 2.6")).find("sun_airmass = 2.6: 2.6 is outside the table's nodes"),
            std::string::npos);
  EXPECT_NE(error_of(sensor("airmass = 1\nsun_airmass = 2\ndown_path = false")).find("sun_airmass = 2: down_path = false"),
            std::string::npos);
  std::string text = sensor("airmass = 1.2");
  text.replace(text.find("[1.0, 1.5, 2.0, 2.5]"), 20, "[1.0, 1.5, 2.0]");
  EXPECT_NE(error_of(text).find("3 airmasses for 4 tables: give one per table"), std::string::npos);
  text = sensor("airmass = 1.2");
  text.replace(text.find("[1.0, 1.5, 2.0, 2.5]"), 20, "[1.0, 2.0, 1.5, 2.5]");
  EXPECT_NE(error_of(text).find("the node airmasses must increase"), std::string::npos);
}

}  // namespace

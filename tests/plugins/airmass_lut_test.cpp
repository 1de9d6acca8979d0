// atmosphere/airmass_lut (an RT code's tables with airmass as a LUT axis): the Rubin site's MODTRAN
// transmittances at X = 1.0, 1.5, 2.0, 2.5 (lsst/throughputs atmos/, shipped in spectra/). At a node the table
// itself; between nodes ln τ linear in X (τ_i^(1−w) τ_(i+1)^w), against band means computed here from the CSV rows;
// the path radiance linear in X; the bad inputs refused at their keys.
#include "radchain/chain.hpp"
#include "radchain/error.hpp"
#include "radchain/physics/solar_position.hpp"
#include "radchain/sensor_file.hpp"

#include <fmt/format.h>
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

// A platform without a view (the line of sight's airmass is given by hand), and one with (earth_orbit: the view
// zenith at the ground point sets it).
const std::string circular = "plugin = \"circular_orbit\"\naltitude = \"700 km\"\n";
const std::string orbit = "plugin = \"earth_orbit\"\naltitude = \"700 km\"\n";

std::string sensor(const std::string& atmosphere, const std::string& platform = circular) {
  return R"([sensor]
name = "airmass LUT test"
[platform]
)" + platform + R"(
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
read_noise = "20 e-"
full_well = "80000 e-"
adc_bits = 14
pixel_pitch = "10 um"
integration_time = "2 ms"
)";
}

Report run(const std::string& atmosphere, const std::string& platform = circular) {
  Chain chain = load_sensor_text(sensor(atmosphere, platform), "airmass_lut_test.toml");
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

// The view zenith η at the ground point, independently of the plugin: the sine rule in the triangle Earth centre,
// satellite, ground point (Wertz & Larson, SMAD 3rd ed. §5.2): sin η = (R + h) sin θ / R, θ the off-nadir angle,
// cos θ = cos(roll) cos(pitch); R = 6371 km (earth_orbit's default), h = 700 km.
double off_nadir(double roll, double pitch) { return std::acos(std::cos(roll) * std::cos(pitch)); }
double view_zenith(double roll, double pitch) {
  const double r = 6371e3, h = 700e3;
  return std::asin((r + h) * std::sin(off_nadir(roll, pitch)) / r);
}
std::string look(double roll_deg, double pitch_deg = 0) {
  return orbit + fmt::format("roll = \"{:.17g} deg\"\npitch = \"{:.17g} deg\"\n", roll_deg, pitch_deg);
}
constexpr double deg = std::numbers::pi / 180;

std::string error_of_text(const std::string& text) {
  try {
    Chain chain = load_sensor_text(text, "airmass_lut_test.toml");
    (void)chain.run();
  } catch (const InputError& e) {
    return std::string(e.what());
  }
  return std::string("(no error)");
}

// The line of sight given once, by the platform: an earth_orbit's view zenith η sets the view airmass by Kasten &
// Young 1989, X_v = 1/(cos η + 0.50572 (96.07995° − η)^−1.6364) (the formula checked against Hardie 1962 above),
// held at 1 where the fit dips below it at nadir. η against the sine rule here (1e-12 rad); the chain's signal
// against the same chain with X_v given by hand to a platform without a view tilted by the same θ (1e-9).
TEST(AirmassLut, TheLineOfSightsAirmassFollowsThePlatformsViewZenith) {
  using radchain::physics::kasten_young_airmass;
  struct Look {
    double roll_deg, pitch_deg;
  };
  for (const Look l : {Look{30, 0}, Look{20, 15}, Look{45, 0}, Look{0, 35}}) {
    const double eta = view_zenith(l.roll_deg * deg, l.pitch_deg * deg);
    const double x = kasten_young_airmass(eta);
    const Report derived = run("", look(l.roll_deg, l.pitch_deg));
    EXPECT_NEAR(v(derived, "platform.view_zenith_angle"), eta, 1e-12) << l.roll_deg << " " << l.pitch_deg;
    EXPECT_NEAR(v(derived, "atmosphere.airmass"), x, 1e-12) << l.roll_deg << " " << l.pitch_deg;
    const std::string tilted = circular + fmt::format("tilt = \"{:.17g} rad\"\n", off_nadir(l.roll_deg * deg, l.pitch_deg * deg));
    const Report by_hand = run(fmt::format("airmass = {:.17g}", x), tilted);
    for (const char* name : {"atmosphere.transmittance", "atmosphere.lut_weight", "detector.signal_electrons", "detector.snr"})
      EXPECT_NEAR(v(derived, name) / v(by_hand, name), 1.0, 1e-9) << name << " at roll " << l.roll_deg;
  }
  // θ = 30° from 700 km: η = 33.706°, X_v = 1.2012 (sec η = 1.2022).
  EXPECT_NEAR(v(run("", look(30)), "atmosphere.airmass"), 1.2012, 1e-4);
  // Nadir: the fit gives 0.99971, below the X = 1 node; relative air mass is 1 there by definition.
  EXPECT_NEAR(kasten_young_airmass(0), 0.99971, 1e-5);
  const Report nadir = run("", orbit);
  EXPECT_EQ(v(nadir, "atmosphere.airmass"), 1.0);
  EXPECT_NEAR(v(nadir, "detector.signal_electrons") / v(run("airmass = 1.0"), "detector.signal_electrons"), 1.0, 1e-12);
  // The Sun and the line of sight both derived: the same as both given by hand (the target's θ_s, both airmasses).
  std::string both = sensor("", look(30));
  both.insert(both.find("plugin = \"sun\"\n") + 15, "solar_zenith = \"60 deg\"\n");
  const Report derived = load_sensor_text(both, "airmass_lut_test.toml").run();
  std::string text = sensor(fmt::format("airmass = {:.17g}\nsun_airmass = {:.17g}", kasten_young_airmass(view_zenith(30 * deg, 0)),
                                        kasten_young_airmass(60 * deg)),
                            circular + "tilt = \"30 deg\"\n");
  text.insert(text.find("reflectance = 0.3\n") + 18, "solar_zenith = \"60 deg\"\n");
  const Report by_hand = load_sensor_text(text, "airmass_lut_test.toml").run();
  EXPECT_NEAR(v(derived, "detector.signal_electrons") / v(by_hand, "detector.signal_electrons"), 1.0, 1e-9);
}

// The view zenith is a scalar result of roll, pitch and altitude, but the atmosphere reads it in its spectral
// phase: in this chain those parameters are spectral (Chain::set re-runs the spectral phase from the platform), so
// a chain changed through set() equals a chain loaded with the new value (the test of a stale spectral phase).
// Chains whose spectral phase does not read the view keep them scalar (WorldView-2's GIQE reads the view zenith
// in its scalar phase: a sweep over roll stays on the lanes).
TEST(AirmassLut, ChangingTheLookRerunsTheSpectralPhase) {
  Chain chain = load_sensor_text(sensor("", look(0)), "airmass_lut_test.toml");
  (void)chain.run();
  const ParameterRef roll = chain.parameter("platform.roll"), pitch = chain.parameter("platform.pitch");
  const ParameterRef altitude = chain.parameter("platform.altitude");
  EXPECT_TRUE(roll.spectral());
  EXPECT_TRUE(pitch.spectral());
  EXPECT_TRUE(altitude.spectral());
  EXPECT_TRUE(chain.parameter("platform.earth_radius").spectral());
  EXPECT_FALSE(chain.parameter("platform.earth_gm").spectral());  // the ground speed only
  EXPECT_FALSE(chain.parameter("detector.integration_time").spectral());
  EXPECT_THROW(chain.set_lanes(roll, constant_lanes(0.1)), std::logic_error);
  const char* names[] = {"platform.view_zenith_angle", "atmosphere.airmass", "atmosphere.transmittance", "atmosphere.lut_weight",
                         "detector.signal_electrons", "detector.snr"};
  auto same_as_fresh = [&](const std::string& platform, const std::string& what) {
    const Report fresh = run("", platform);
    for (const char* name : names) EXPECT_NEAR(chain.result(name), v(fresh, name), 1e-12 * std::abs(v(fresh, name))) << name << " " << what;
  };
  for (const double r : {40.0, 10.0, 0.0, 47.5}) {
    chain.set(roll, r * deg);
    chain.evaluate();
    same_as_fresh(look(r), fmt::format("roll {}", r));
  }
  chain.set(pitch, 20 * deg);
  chain.evaluate(Detail::essential);
  chain.evaluate();
  same_as_fresh(look(47.5, 20), "pitch 20");
  chain.set(altitude, 500e3);
  chain.evaluate();
  std::string lower = look(47.5, 20);
  lower.replace(lower.find("700 km"), 6, "500 km");
  same_as_fresh(lower, "altitude 500 km");
  // A spectral change further down after run() (which clears the values): the atmosphere's spectral phase re-runs
  // alone and still reads the platform's view zenith as the platform's spectral phase set it.
  chain.set(chain.parameter("atmosphere.sun_airmass"), 2.0);
  const Report after = chain.run();
  EXPECT_NEAR(v(after, "atmosphere.airmass"), radchain::physics::kasten_young_airmass(v(after, "platform.view_zenith_angle")), 1e-12);
  EXPECT_EQ(v(after, "atmosphere.sun_airmass"), 2.0);
  // No atmosphere reading the view: roll stays scalar.
  Chain wv2 = load_sensor(std::string(RADCHAIN_SOURCE_DIR) + "/sensors/worldview-2-pan-20deg.toml");
  EXPECT_FALSE(wv2.parameter("platform.roll").spectral());
  EXPECT_FALSE(wv2.parameter("platform.altitude").spectral());
}

// A [[solve]] on the roll: the look at which the SNR falls to a threshold. The threshold is a fresh chain's SNR at
// 40°; the solve (TOMS 748, never lanes: the unknown is spectral here) finds 40° back.
TEST(AirmassLut, ASolveOnTheRollRerunsTheSpectralPhase) {
  const double snr40 = v(run("", look(40)), "detector.snr");
  std::string text = sensor("", look(10)) + fmt::format(R"(
[criteria.snr]
plugin = "snr_threshold"
threshold = {:.17g}
[[solve]]
unknown = "platform.roll"
criterion = "snr"
bracket = ["0 deg", "55 deg"]
)",
                                                        snr40);
  Chain chain = load_sensor_text(text, "airmass_lut_test.toml");
  EXPECT_FALSE(chain.lanes_can_solve());
  const Report r = chain.run();
  ASSERT_EQ(r.solves.size(), 1u);
  EXPECT_TRUE(r.solves[0].converged) << r.solves[0].message;
  EXPECT_NEAR(r.solves[0].value_si, 40 * deg, 1e-9);
  EXPECT_NEAR(v(r, "atmosphere.airmass"), radchain::physics::kasten_young_airmass(view_zenith(40 * deg, 0)), 1e-8);
}

// The line of sight given twice (the platform's view and `airmass`) is refused at `airmass`, as the Sun given twice
// is at the second key; a look whose airmass is beyond the tables is refused at `airmasses` with the airmass it
// needs, for the file's roll and for one set later (a sweep's point); no platform view and no airmass: missing key.
TEST(AirmassLut, TheLineOfSightGivenTwiceOrBeyondTheTablesIsRefused) {
  EXPECT_NE(error_of_text(sensor("airmass = 1.2", look(30)))
                .find("atmosphere (plugin \"airmass_lut\"): airmass = 1.2: the platform gives the line of sight's view zenith "
                      "(platform.view_zenith_angle), which sets its airmass: give one of them"),
            std::string::npos)
      << error_of_text(sensor("airmass = 1.2", look(30)));
  // 58° from 700 km: η = 70.26°, X_v = 2.939 > 2.5.
  const std::string beyond = error_of_text(sensor("", look(58)));
  EXPECT_NE(beyond.find(": the line of sight at 70.26° (platform.view_zenith_angle) crosses 2.939 airmasses (Kasten & "
                        "Young 1989)"),
            std::string::npos)
      << beyond;
  EXPECT_NE(beyond.find("(plugin \"airmass_lut\"): airmasses = "), std::string::npos) << beyond;
  EXPECT_NE(beyond.find("outside the tables' nodes [1, 2.5]: add a table at that airmass"), std::string::npos) << beyond;
  EXPECT_EQ(beyond.rfind("airmass_lut_test.toml:", 0), 0u) << beyond;  // located
  Chain chain = load_sensor_text(sensor("", look(0)), "airmass_lut_test.toml");
  chain.set(chain.parameter("platform.roll"), 58 * deg);
  try {
    chain.evaluate();
    ADD_FAILURE() << "no error at roll 58°";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("crosses 2.9"), std::string::npos) << e.what();
  }
  EXPECT_NE(error_of_text(sensor("")).find("atmosphere (plugin \"airmass_lut\"): airmass: missing required key: the line of sight's airmass"), std::string::npos)
      << error_of_text(sensor(""));
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

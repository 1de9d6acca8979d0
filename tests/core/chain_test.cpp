// The chain and its solver with the real plugins, on sensors/msx-sbv.toml (Pan et al. 2010, Acta Optica
// Sinica 30(10) 2935: limiting magnitude of the MSX SBV at SNR 5). References: the paper's Table 2
// (15.55 at D = 15 cm, "about 17" at 30 cm), its closed form eq. (11), and first principles for the signal.
#include "radchain/chain.hpp"
#include "radchain/constants.hpp"
#include "radchain/error.hpp"
#include "radchain/sensor_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

namespace {
using namespace radchain;

const std::string sbv = std::string(RADCHAIN_SOURCE_DIR) + "/sensors/msx-sbv.toml";

double value(const Report& report, const std::string& name) {
  const auto v = report.value(name);
  EXPECT_TRUE(v.has_value()) << "no result " << name;
  return v.value_or(NAN);
}

// Pan 2010 eq. (11): the signal at SNR = T solves S^2 = T^2 (S + N_d + σ_o^2 + n_q^2), i.e.
//   S = [T^2 + sqrt(T^4 + 4 T^2 (N_d + σ_o^2 + n_q^2))] / 2.
double pan_eq11_signal(double threshold, double dark_electrons, double read_noise, double quantisation_noise) {
  const double t2 = threshold * threshold;
  const double noise_floor = dark_electrons + read_noise * read_noise + quantisation_noise * quantisation_noise;
  return 0.5 * (t2 + std::sqrt(t2 * t2 + 4.0 * t2 * noise_floor));
}

class MsxSbv : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    Chain chain = load_sensor(sbv);
    report_ = new Report(chain.run());
  }
  static void TearDownTestSuite() {
    delete report_;
    report_ = nullptr;
  }
  static Report* report_;
};
Report* MsxSbv::report_ = nullptr;

TEST_F(MsxSbv, LimitingMagnitudeMatchesPan2010) {
  const Report& r = *report_;
  ASSERT_EQ(r.solves.size(), 1u);
  EXPECT_TRUE(r.solves[0].converged) << r.solves[0].message;
  EXPECT_EQ(r.solves[0].spec.unknown, "target.magnitude");
  // Pan 2010 Table 2: 15.55 (design specification 15.5).
  EXPECT_NEAR(r.solves[0].value_si, 15.55, 0.05);
  EXPECT_EQ(value(r, "target.magnitude"), r.solves[0].value_si);
  EXPECT_TRUE(r.all_passed());
  ASSERT_EQ(r.expectations.size(), 1u);
  EXPECT_TRUE(r.expectations[0].found);
  EXPECT_TRUE(r.expectations[0].passed);
}

TEST_F(MsxSbv, SnrEqualsTheThresholdAtTheSolution) {
  const Report& r = *report_;
  EXPECT_EQ(value(r, "criteria.detection.threshold"), 5.0);
  EXPECT_NEAR(value(r, "detector.snr"), 5.0, 1e-9);
  EXPECT_NEAR(value(r, "criteria.detection.margin"), 0.0, 1e-9);
}

TEST_F(MsxSbv, SignalAtTheSolutionIsPanEquation11) {
  const Report& r = *report_;
  const double s = pan_eq11_signal(5.0, value(r, "detector.dark_electrons"), value(r, "detector.read_noise"),
                                   value(r, "detector.quantisation_noise"));
  EXPECT_NEAR(value(r, "detector.signal_electrons"), s, s * 1e-9);
  // The noise terms from Table 1: N_d = 18 e-/s × 0.625 s, σ_o = 6 e-, n_q^2 = n_well/(2^N √12) as printed in §3.2.
  EXPECT_NEAR(value(r, "detector.dark_electrons"), 11.25, 1e-12);
  EXPECT_EQ(value(r, "detector.read_noise"), 6.0);
  const double nq2 = 1e5 / (4096.0 * std::sqrt(12.0));
  EXPECT_NEAR(std::pow(value(r, "detector.quantisation_noise"), 2), nq2, nq2 * 1e-12);
  // Noise budget of eq. (9), and S = 51.4 e- to the printed precision.
  const double n = std::sqrt(11.25 + 36.0 + nq2 + s);
  EXPECT_NEAR(value(r, "detector.noise_electrons"), n, n * 1e-12);
  EXPECT_NEAR(s, 51.406, 1e-3);
}

// The E-490 table read without the framework's CSV loader: (nm, W m^-2 nm^-1) rows.
std::vector<std::pair<double, double>> read_e490_nm() {
  std::ifstream in(std::string(RADCHAIN_SOURCE_DIR) + "/spectra/am0_astm_e490_00a.csv");
  std::vector<std::pair<double, double>> rows;
  std::string line;
  bool header = false;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      header = true;
      continue;
    }
    const auto comma = line.find(',');
    rows.emplace_back(std::stod(line.substr(0, comma)), std::stod(line.substr(comma + 1)));
  }
  return rows;
}

TEST_F(MsxSbv, SignalFromFirstPrinciples) {
  // S = t η τ (π D²/4) 10^{0.4 (m_sun - m)} ∫_{0.3 µm}^{0.9 µm} E_λ λ/(hc) dλ (Pan 2010 eqs. 1, 6-8) with
  // E_λ the E-490 table (linear between rows, trapezoid with the band edges as nodes).
  const auto rows = read_e490_nm();
  ASSERT_GT(rows.size(), 1000u);
  auto photons = [](double nm, double irradiance_per_nm) {
    return irradiance_per_nm * 1e9 * nm * 1e-9 / (constants::planck_J_s * constants::speed_of_light_m_s);
  };
  auto at = [&](double nm) {
    for (std::size_t i = 1; i < rows.size(); ++i)
      if (rows[i].first >= nm) {
        const double f = (nm - rows[i - 1].first) / (rows[i].first - rows[i - 1].first);
        return rows[i - 1].second + f * (rows[i].second - rows[i - 1].second);
      }
    return 0.0;
  };
  std::vector<std::pair<double, double>> nodes{{300.0, photons(300.0, at(300.0))}};
  for (const auto& [nm, e] : rows)
    if (nm > 300.0 && nm < 900.0) nodes.emplace_back(nm, photons(nm, e));
  nodes.emplace_back(900.0, photons(900.0, at(900.0)));
  double photon_irradiance = 0;  // photons s^-1 m^-2 at 1 AU in the band
  for (std::size_t i = 1; i < nodes.size(); ++i)
    photon_irradiance += 0.5 * (nodes[i].first - nodes[i - 1].first) * 1e-9 * (nodes[i].second + nodes[i - 1].second);

  const Report& r = *report_;
  const double m = value(r, "target.magnitude");
  const double area = std::numbers::pi * 0.15 * 0.15 / 4.0;
  const double expected = 0.625 * 0.27 * 0.56 * area * std::pow(10.0, 0.4 * (-26.73 - m)) * photon_irradiance;
  EXPECT_NEAR(value(r, "detector.signal_electrons"), expected, expected * 1e-9);
  EXPECT_NEAR(value(r, "optics.collecting_area"), area, area * 1e-15);
  EXPECT_NEAR(value(r, "source.total_irradiance"), 1366.09, 0.005);
}

TEST(Chain, SignalScalesWithMagnitude) {
  // Forward evaluation without the solve: 2.5 magnitudes fainter is 10 times less signal.
  Chain chain = load_sensor(sbv);
  chain.set("target.magnitude", 12.0);
  chain.evaluate();
  const double bright = chain.result("detector.signal_electrons");
  chain.set("target.magnitude", 14.5);
  chain.evaluate();
  const double faint = chain.result("detector.signal_electrons");
  EXPECT_NEAR(bright / faint, 10.0, 10.0 * 1e-12);
  EXPECT_THROW(chain.result("detector.no_such_result"), std::out_of_range);
  EXPECT_THROW(chain.parameter("optics.no_such_key"), std::logic_error);
  EXPECT_THROW(chain.parameter("detector.quantisation"), std::out_of_range);  // not numeric
}

TEST(Chain, SetOverrideOfTheAperture) {
  // --set optics.aperture="30 cm": the required signal (eq. 11) does not depend on D, the collected signal goes
  // as D², so the limiting magnitude rises by exactly 5 log10(30/15) = 1.50515; Pan 2010: "about 17".
  Chain base = load_sensor(sbv);
  Chain wide = load_sensor(sbv, {{"optics.aperture", "30 cm"}});
  const Report r15 = base.run(), r30 = wide.run();
  ASSERT_TRUE(r30.solves.at(0).converged);
  const double m15 = r15.solves.at(0).value_si, m30 = r30.solves.at(0).value_si;
  EXPECT_NEAR(m30 - m15, 5.0 * std::log10(2.0), 1e-9);
  EXPECT_NEAR(m30, 17.0, 0.1);
  EXPECT_NEAR(value(r30, "optics.aperture"), 0.30, 1e-15);
  EXPECT_FALSE(r30.all_passed());  // 17.06 is outside 15.55 ± 0.05
  EXPECT_NEAR(value(r30, "detector.snr"), 5.0, 1e-9);
}

TEST(Chain, ASystemGainReadsInDnPerElectronOrItsReciprocal) {
  // EMVA 1288 states K in DN/e-; astronomers quote 1/K in e-/ADU (SMTN-002: "1.5-1.7 e-/ADU"). 1/1.6 rounds to
  // 0.625 exactly, so the two spellings must give the same bits everywhere downstream.
  const std::string rubin = std::string(RADCHAIN_SOURCE_DIR) + "/sensors/rubin-lsst-r-m5.toml";
  const Report k = load_sensor(rubin, {{"detector.gain", "\"0.625 DN/e-\""}}).run();
  for (const char* reciprocal : {"\"1.6 e-/DN\"", "\"1.6 e-/ADU\""}) {
    const Report r = load_sensor(rubin, {{"detector.gain", reciprocal}}).run();
    EXPECT_EQ(value(r, "detector.system_gain"), 0.625) << reciprocal;
    EXPECT_EQ(r.solves.at(0).value_si, k.solves.at(0).value_si) << reciprocal;
  }
  EXPECT_EQ(value(load_sensor(rubin, {{"detector.gain", "\"2 ADU/e-\""}}).run(), "detector.system_gain"), 2.0);
  // No reciprocal of zero, and only a gain is read reciprocally.
  EXPECT_THROW(load_sensor(rubin, {{"detector.gain", "\"0 e-/DN\""}}), InputError);
  EXPECT_THROW(load_sensor(rubin, {{"detector.integration_time", "\"0.1 Hz\""}}), InputError);
}

TEST(Chain, SetOverridesAreValidated) {
  EXPECT_THROW(load_sensor(sbv, {{"optics.aperture", "30 kg"}}), InputError);
  EXPECT_THROW(load_sensor(sbv, {{"optics.aperture", "30"}}), InputError);
  EXPECT_THROW(load_sensor(sbv, {{"optics.apperture", "30 cm"}}), InputError);
  EXPECT_THROW(load_sensor(sbv, {{"optic.aperture", "30 cm"}}), InputError);
  EXPECT_THROW(load_sensor(sbv, {{"aperture", "30 cm"}}), InputError);
  // A TOML value on the command line works as in the file.
  Chain chain = load_sensor(sbv, {{"target.magnitude", "12"}, {"detector.quantisation", "\"emva\""}});
  EXPECT_TRUE(chain.slot("detector").params->given("quantisation"));
  EXPECT_EQ(chain.slot("detector").params->text("quantisation"), "emva");
}

TEST(Chain, EmvaQuantisationNoiseIsSmaller) {
  // EMVA 1288: n_q² = (n_well/2^N)²/12 = (1e5/4096)²/12 = 49.67 e-², against the printed 7.05 e-²: the limiting
  // magnitude drops.
  Chain paper = load_sensor(sbv);
  Chain emva = load_sensor(sbv, {{"detector.quantisation", "emva"}});
  const Report rp = paper.run(), re = emva.run();
  const double nq2 = std::pow(1e5 / 4096.0, 2) / 12.0;
  EXPECT_NEAR(std::pow(value(re, "detector.quantisation_noise"), 2), nq2, nq2 * 1e-12);
  EXPECT_LT(re.solves.at(0).value_si, rp.solves.at(0).value_si);
  const double s = pan_eq11_signal(5.0, 11.25, 6.0, std::sqrt(nq2));
  EXPECT_NEAR(value(re, "detector.signal_electrons"), s, s * 1e-9);
}

TEST(Chain, BadSensorFileIsAnInputError) {
  try {
    load_sensor(std::string(RADCHAIN_SOURCE_DIR) + "/sensors/no_such_sensor.toml");
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("no_such_sensor.toml: sensor file: cannot be read"), std::string::npos)
        << error.what();
  }
}

// Forward only is one option of loading: the [[solve]] entries are gone, the unknown keeps the file's value (and its
// result echoes it), the criterion is evaluated but not driven to zero, and a focused chain then leaves it out.
TEST(Chain, ForwardOnlyLoadingKeepsTheUnknownsValue) {
  Chain solved = load_sensor(sbv);
  Chain forward = load_sensor(sbv, {{"target.magnitude", "12"}}, Solving::forward_only);
  EXPECT_TRUE(forward.solves.empty());
  const Report report = forward.run();
  EXPECT_TRUE(report.solves.empty());
  EXPECT_DOUBLE_EQ(*report.value("target.magnitude"), 12.0);
  EXPECT_GT(*report.value("criteria.detection.margin"), 1.0);  // a 12th-magnitude star is far above the threshold
  EXPECT_NEAR(*solved.run().value("criteria.detection.margin"), 0.0, 1e-12);
  forward.focus({*forward.results().find("detector.snr")});
  EXPECT_TRUE(forward.skips(forward.stages.size() - 1));  // no solve needs criteria.detection any more
}

}  // namespace

namespace {

// A self-luminous point source (its own flat-f_ν SED) needs no [source]: the Rubin file without one gives the same
// limit to the last bit. A target lit by a source refuses without one (tests/config_errors, reflecting_target_...).
TEST(Chain, ASelfLuminousTargetNeedsNoSourceSection) {
  std::ifstream in(std::string(RADCHAIN_SOURCE_DIR) + "/sensors/rubin-lsst-r-m5.toml");
  std::string text, line;
  bool in_source = false;
  while (std::getline(in, line)) {
    if (line.starts_with("[")) in_source = line == "[source]";
    if (!in_source) text += line + "\n";
  }
  ASSERT_EQ(text.find("[source]"), std::string::npos);
  Chain with = load_sensor(std::string(RADCHAIN_SOURCE_DIR) + "/sensors/rubin-lsst-r-m5.toml");
  Chain without = radchain::load_sensor_text(text, "rubin-without-source.toml");
  const Report a = with.run(), b = without.run();
  ASSERT_TRUE(b.all_passed());
  EXPECT_EQ(a.value("target.magnitude"), b.value("target.magnitude"));
  EXPECT_EQ(a.value("detector.sky_electrons_per_pixel"), b.value("detector.sky_electrons_per_pixel"));
}

}  // namespace

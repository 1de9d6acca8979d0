// An airmass_lut atmosphere under an earth_orbit platform: the view airmass follows the platform's view zenith,
// which follows roll. Roll is spectral in such a chain (the atmosphere reads the view zenith in its spectral phase),
// so a sweep runs it point by point (never in lanes) and a budget's differences re-run the spectral phase: both
// against chains loaded fresh at each value, and the budget's ∂X_v/∂roll against the closed form.
#include "cli_helpers.hpp"
#include "radchain/batch/budget.hpp"
#include "radchain/batch/sweep.hpp"
#include "radchain/physics/solar_position.hpp"
#include "radchain/sensor_file.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace {
using namespace radchain;
using namespace radchain::test;

constexpr double deg = std::numbers::pi / 180;

std::string sensor_text(const std::string& roll) {
  return R"([sensor]
name = "view airmass test"
[platform]
plugin = "earth_orbit"
altitude = "700 km"
roll = ")" + roll + R"("
[source]
plugin = "sun"
[atmosphere]
plugin = "airmass_lut"
tables = ["lsst_atmos_aerosol_X10_throughputs1.9.csv", "lsst_atmos_aerosol_X15_throughputs1.9.csv", "lsst_atmos_aerosol_X20_throughputs1.9.csv", "lsst_atmos_aerosol_X25_throughputs1.9.csv"]
airmasses = [1.0, 1.5, 2.0, 2.5]
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

double fresh(const std::string& roll, const std::string& result) {
  Chain chain = load_sensor_text(sensor_text(roll), "view_airmass_test.toml");
  return chain.run().value(result).value();
}

// `radchain sweep FILE --set "platform.roll=0 deg:40 deg:5"`: every point equals a chain loaded at that roll, in
// the order given and out of order, and the worker does not use lanes (it would throw: roll is spectral here).
TEST(ViewAirmass, ASweepOverRollEqualsFreshChains) {
  Scratch scratch;
  const std::string file = (scratch / "view_airmass.toml").string();
  write_text(file, sensor_text("0 deg"));
  SweepOptions options;
  options.sensor_file = file;
  options.axes = {{"platform.roll", "0 deg:40 deg:5"}};
  options.results = {"platform.view_zenith_angle", "atmosphere.airmass", "atmosphere.transmittance", "detector.signal_electrons"};
  const Sweep sweep(options);
  SweepWorker worker(sweep);
  EXPECT_TRUE(worker.chain().parameter("platform.roll").spectral());
  const std::size_t n = sweep.columns();
  for (const std::vector<std::size_t>& group : {std::vector<std::size_t>{0, 1, 2, 3, 4}, std::vector<std::size_t>{4, 0, 3, 1}}) {
    std::vector<double> out(group.size() * n);
    std::vector<char> ok(group.size());
    worker.evaluate_group(group.data(), group.size(), out.data(), ok.data());
    for (std::size_t k = 0; k < group.size(); ++k) {
      ASSERT_TRUE(ok[k]) << worker.failure_of(k);
      const double roll_deg = sweep.axes()[0].value(group[k]);
      EXPECT_EQ(out[k * n], 10.0 * static_cast<double>(group[k]));
      const std::string roll = fmt::format("{:.17g} deg", roll_deg);
      // (view zenith in its display unit, degrees)
      EXPECT_NEAR(out[k * n + 1] * deg, fresh(roll, "platform.view_zenith_angle"), 1e-12) << roll;
      for (std::size_t r = 1; r < options.results.size(); ++r) {
        const double expected = fresh(roll, options.results[r]);
        EXPECT_NEAR(out[k * n + 1 + r], expected, 1e-12 * std::abs(expected)) << roll << " " << options.results[r];
      }
    }
  }
  // The airmass column moves with roll: 1 at nadir (Kasten & Young held at 1), 1.4254 at 40° (η = 45.51°).
  std::vector<double> out(n);
  ASSERT_TRUE(worker.evaluate(4, out.data())) << worker.failure();
  EXPECT_NEAR(out[2], 1.4254, 1e-4);
  ASSERT_TRUE(worker.evaluate(0, out.data())) << worker.failure();
  EXPECT_EQ(out[2], 1.0);
}

// The command line as a user types it: the airmass column of `radchain sweep` follows Kasten & Young at the view
// zenith of each roll (held at 1 at nadir), to the CSV's 10 significant digits.
TEST(ViewAirmass, TheSweepCommandOverRoll) {
  Scratch scratch;
  const std::string file = (scratch / "view_airmass.toml").string();
  write_text(file, sensor_text("0 deg"));
  const CliResult r =
      run_cli(scratch, "sweep '" + file + "' --set 'platform.roll=0 deg:40 deg:5' --results atmosphere.airmass");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream lines(r.out);
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line, "platform.roll_deg,atmosphere.airmass");
  const double k = (6371e3 + 700e3) / 6371e3;
  for (int i = 0; i < 5; ++i) {
    ASSERT_TRUE(std::getline(lines, line)) << r.out;
    const double roll = 10.0 * i * deg;
    const double x = std::max(1.0, physics::kasten_young_airmass(std::asin(k * std::sin(roll))));
    EXPECT_NEAR(std::stod(line.substr(line.find(',') + 1)), x, 1e-9 * x) << line;
  }
}

// `radchain budget` over roll at 30°: ∂X_v/∂roll by Ridders' differences (each point re-runs the spectral phase)
// against the closed form dX/dη · dη/dθ, with X = 1/D, D = cos η + a (b − η°)^−c (Kasten & Young 1989),
// dD/dη = −sin η + a c (b − η°)^(−c−1) · 180/π, and sin η = k sin θ, k = (R + h)/R, dη/dθ = k cos θ / cos η
// (θ = roll at pitch 0); the signal's derivative against a central difference of fresh chains (h = 1e-4 rad).
TEST(ViewAirmass, ABudgetOverRollRerunsTheSpectralPhase) {
  Chain chain = load_sensor_text(sensor_text("30 deg"), "view_airmass_test.toml");
  BudgetOptions options;
  options.results = {"atmosphere.airmass", "detector.signal_electrons"};
  const Budget budget = compute_budget(chain, options);
  const BudgetEntry* airmass = nullptr;
  const BudgetEntry* signal = nullptr;
  for (const BudgetEntry& e : budget.entries)
    if (e.parameter == "platform.roll") (e.result == "atmosphere.airmass" ? airmass : signal) = &e;
  ASSERT_TRUE(airmass && signal);
  ASSERT_TRUE(airmass->ok && signal->ok) << airmass->failure << signal->failure;

  const double r = 6371e3, h = 700e3, k = (r + h) / r, theta = 30 * deg;
  const double eta = std::asin(k * std::sin(theta));
  const double a = 0.50572, b = 96.07995, c = 1.6364, eta_deg = eta / deg;
  const double d = std::cos(eta) + a * std::pow(b - eta_deg, -c);
  const double d_prime = -std::sin(eta) + a * c * std::pow(b - eta_deg, -c - 1) / deg;
  const double dx_dtheta = -d_prime / (d * d) * k * std::cos(theta) / std::cos(eta);
  EXPECT_NEAR(airmass->derivative, dx_dtheta, 1e-6 * std::abs(dx_dtheta));
  EXPECT_LT(airmass->derivative, 0.93);  // 0.9237 per radian: the check above is not of a vanishing derivative
  EXPECT_GT(airmass->derivative, 0.92);

  const double step = 1e-4;
  const double central = (fresh(fmt::format("{:.17g} rad", theta + step), "detector.signal_electrons") -
                          fresh(fmt::format("{:.17g} rad", theta - step), "detector.signal_electrons")) /
                         (2 * step);
  EXPECT_NEAR(signal->derivative, central, 1e-5 * std::abs(central));
  EXPECT_LT(signal->derivative, 0.0);
}

// A value the sweep sets has no text as written: the refusal names it by its number (it said "airmass = :").
TEST(ViewAirmass, ARefusedSweptValueIsNamedByItsNumber) {
  Scratch scratch;
  const fs::path file = scratch / "view.toml";
  write_text(file, sensor_text("30 deg"));
  const CliResult r = run_cli(scratch, "sweep '" + file.string() + "' --set 'atmosphere.airmass=1:1.5:3' --out '" +
                                           (scratch / "out.csv").string() + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("at atmosphere.airmass = 1, atmosphere (plugin \"airmass_lut\"): airmass = 1: the platform gives "
                       "the line of sight's view zenith"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(scratch / "out.csv"));
}

}  // namespace

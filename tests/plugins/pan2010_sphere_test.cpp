// The lambertian_sphere target (a diffuse sphere in space) and sensors/sbv-smallest-sphere.toml: its
// magnitude against the closed form m = m_sun − 2.5 lg(p (D/2)²/r² Φ(α)), p = 2ρ/3, Φ the Lambert-sphere
// phase function (Russell 1916), and the smallest detectable sphere against the SBV's limiting magnitude.
#include "radchain/chain.hpp"
#include "radchain/error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace {
using namespace radchain;

const std::string sensors = std::string(RADCHAIN_SOURCE_DIR) + "/sensors/";
const std::string sphere = sensors + "sbv-smallest-sphere.toml";
constexpr double pi = std::numbers::pi;

// Lambert sphere, typed from the textbook form: I(α) ∝ p R² [sin α + (π − α) cos α]/π.
double closed_form_magnitude(double diameter_m, double bond_albedo, double range_m, double alpha_rad,
                             double sun_magnitude = -26.73) {
  const double p = 2.0 / 3.0 * bond_albedo;
  const double phase = (std::sin(alpha_rad) + (pi - alpha_rad) * std::cos(alpha_rad)) / pi;
  return sun_magnitude - 2.5 * std::log10(p * std::pow(diameter_m / 2, 2) / (range_m * range_m) * phase);
}

TEST(Pan2010Sphere, SmallestSphereHasTheSbvLimitingMagnitude) {
  Chain sbv = load_sensor(sensors + "msx-sbv.toml");
  const Report limit = sbv.run();
  Chain chain = load_sensor(sphere);
  const Report r = chain.run();
  ASSERT_TRUE(r.solves.at(0).converged) << r.solves.at(0).message;
  EXPECT_EQ(r.solves.at(0).spec.unknown, "target.diameter");
  EXPECT_TRUE(r.all_passed());
  // Grey albedo, same spectrum: the sphere at the detection limit is exactly as bright as the limiting star.
  const double m_lim = limit.solves.at(0).value_si;
  EXPECT_NEAR(r.value("target.magnitude").value(), m_lim, 1e-6);
  EXPECT_NEAR(r.value("detector.snr").value(), 5.0, 1e-9);
  // And its diameter is the closed form turned round: D = 2 r √(10^{0.4(m_sun − m)} / (p Φ(90°))), Φ(90°) = 1/π.
  const double ratio = std::pow(10.0, 0.4 * (-26.73 - m_lim));
  const double d = 2 * 1e6 * std::sqrt(ratio / (2.0 / 3.0 * 0.2 / pi));
  EXPECT_NEAR(r.solves.at(0).value_si, d, d * 1e-9);
  EXPECT_NEAR(d, 0.033872, 1e-6);  // 3.39 cm at 1000 km
}

TEST(Pan2010Sphere, MagnitudeAgainstTheClosedForm) {
  Chain chain = load_sensor(sphere);
  for (double alpha_deg : {0.0, 30.0, 90.0, 120.0, 170.0}) {
    for (double d : {0.1, 1.0, 3.0}) {
      chain.set("target.diameter", d);
      chain.set("target.phase_angle", alpha_deg * pi / 180);
      chain.evaluate();
      EXPECT_NEAR(chain.result("target.magnitude"), closed_form_magnitude(d, 0.2, 1e6, alpha_deg * pi / 180), 1e-12)
          << alpha_deg << " deg, " << d << " m";
    }
  }
  // Full phase: Φ = 1; quarter: 1/π; a 1 m sphere of p = 0.1333 at 1000 km, α = 0: m = 6.50.
  chain.set("target.diameter", 1.0);
  chain.set("target.phase_angle", 0.0);
  chain.evaluate();
  EXPECT_NEAR(chain.result("target.phase_function"), 1.0, 1e-15);
  EXPECT_NEAR(chain.result("target.geometric_albedo"), 0.2 * 2 / 3, 1e-15);
  EXPECT_NEAR(chain.result("target.magnitude"), -26.73 - 2.5 * std::log10(0.2 * 2 / 3 * 0.25 / 1e12), 1e-12);
  chain.set("target.phase_angle", pi / 2);
  chain.evaluate();
  EXPECT_NEAR(chain.result("target.phase_function"), 1.0 / pi, 1e-15);
  chain.set("target.phase_angle", pi);
  chain.evaluate();
  EXPECT_NEAR(chain.result("target.phase_function"), 0.0, 1e-15);
}

TEST(Pan2010Sphere, PhaseIntegralIsThreeHalves) {
  // q = 2 ∫0^π Φ(α) sin α dα = 3/2, so Bond albedo = p q = ρ: the plugin's phase function, Simpson on 200 steps.
  Chain chain = load_sensor(sphere);
  const int n = 200;
  double sum = 0;
  for (int i = 0; i <= n; ++i) {
    const double a = pi * i / n;
    chain.set("target.phase_angle", a);
    chain.evaluate();
    const double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    sum += w * chain.result("target.phase_function") * std::sin(a);
  }
  EXPECT_NEAR(2 * sum * (pi / n) / 3, 1.5, 1e-8);
}

TEST(Pan2010Sphere, GeometricAlbedoIsTwoThirdsOfBond) {
  Chain bond = load_sensor(sphere, {{"target.diameter", "1 m"}});
  Chain geometric = load_sensor(sphere, {{"target.diameter", "1 m"}, {"target.albedo", "0.1"}, {"target.albedo_kind", "geometric"}});
  bond.set("target.albedo", 0.15);
  bond.evaluate();
  geometric.evaluate();
  EXPECT_NEAR(geometric.result("target.bond_albedo"), 0.15, 1e-15);
  EXPECT_NEAR(geometric.result("target.magnitude"), bond.result("target.magnitude"), 1e-12);
  EXPECT_THROW(load_sensor(sphere, {{"target.albedo", "0.7"}, {"target.albedo_kind", "geometric"}}), InputError);
}

TEST(Pan2010Sphere, SunDistanceDimsTheSphereButNotAStar) {
  // At 2 AU from the Sun the sphere receives a quarter: 2.5 lg 4 = 1.50515 mag fainter. A star of given magnitude
  // (point_magnitude) keeps its signal.
  Chain near = load_sensor(sphere, {{"target.diameter", "1 m"}});
  Chain far = load_sensor(sphere, {{"target.diameter", "1 m"}, {"source.distance", "2 AU"}});
  near.evaluate();
  far.evaluate();
  EXPECT_NEAR(far.result("target.magnitude") - near.result("target.magnitude"), 2.5 * std::log10(4.0), 1e-12);
  EXPECT_NEAR(far.result("detector.signal_electrons") / near.result("detector.signal_electrons"), 0.25, 1e-12);
  Chain star = load_sensor(sensors + "msx-sbv.toml");
  Chain star_far = load_sensor(sensors + "msx-sbv.toml", {{"source.distance", "2 AU"}});
  star.evaluate();
  star_far.evaluate();
  EXPECT_NEAR(star_far.result("detector.signal_electrons"), star.result("detector.signal_electrons"), 1e-9);
  EXPECT_NEAR(star_far.result("target.illuminance"), star.result("target.illuminance"), 1e-24);
}

}  // namespace

// The Kolobrodov 1996 sensor files run through the whole chain; each design output is checked against the
// paper's closed forms evaluated here from the same inputs (not against numbers copied from a run).
#include "radchain/chain.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace {

const std::string paper_file = std::string(RADCHAIN_SOURCE_DIR) + "/sensors/kolobrodov-1996-ccd151.toml";
const std::string computed_file = std::string(RADCHAIN_SOURCE_DIR) + "/sensors/kolobrodov-1996-ccd151-computed.toml";

double value(const radchain::Report& report, const std::string& name) {
  const auto v = report.value(name);
  EXPECT_TRUE(v.has_value()) << name;
  return v.value_or(std::nan(""));
}

TEST(KolobrodovSensor, PaperModeFollowsTheClosedForms) {
  radchain::Chain chain = radchain::load_sensor(paper_file);
  const radchain::Report report = chain.run();
  ASSERT_TRUE(report.all_passed());

  // Inputs as printed (SI).
  const double e_s = 1400.0, z1 = 0.236, z2 = 0.58, tau_a = 0.5, tau_0 = 0.8, delta_rho = 0.3 * 0.01;
  const double h_nt = 0.0002e-6 / 1e-4, k_i = 0.187, k_c = 0.852, t_i = 5000 / 5e6, h = 400e3, dv = 5.0;
  // E's, E0, ΔM_n (eq. 4), H_nr, E_n (eq. 20).
  const double e0 = e_s * (z2 - z1) * tau_a;
  const double delta_m = e0 * delta_rho;
  const double e_n = h_nt * k_i / k_c / t_i;
  EXPECT_NEAR(value(report, "atmosphere.ground_irradiance"), e0, 1e-9 * e0);
  EXPECT_NEAR(value(report, "target.threshold_exitance"), delta_m, 1e-9 * delta_m);
  EXPECT_NEAR(value(report, "detector.threshold_irradiance"), e_n, 1e-9 * e_n);
  // Eq. (16) with the chain's V_s, and eq. (22) with the chain's f'.
  const double vs = value(report, "detector.system_element");
  const double f = vs * h / dv;
  EXPECT_NEAR(value(report, "optics.focal_length"), f, 1e-9 * f);
  const double d0 = f * std::sqrt(4 * e_n / (tau_a * tau_0 * delta_m));
  EXPECT_NEAR(value(report, "optics.aperture"), d0, 1e-6 * d0);
  EXPECT_NEAR(d0, 0.0650, 0.0002);  // the erratum: eq. (22) gives 65.0 mm, the paper prints 206 mm
  // Eq. (17)-(18).
  EXPECT_NEAR(value(report, "criteria.resolution.angular_field"), 2 * std::atan(0.035 / (2 * f)), 1e-12);
  EXPECT_NEAR(value(report, "criteria.resolution.swath"), 0.035 * h / f, 1e-6);
  // Eq. (23) with the printed 7.9 km/s: δy = 7.9 m for a 1 ms line, not the 5 m across track.
  EXPECT_NEAR(value(report, "criteria.resolution.along_track_sample"), 7.9, 1e-9);
}

TEST(KolobrodovSensor, ComputedModeBindsOnMatchingAndSatisfiesBoth) {
  radchain::Chain chain = radchain::load_sensor(computed_file);
  const radchain::Report report = chain.run();
  ASSERT_TRUE(report.all_passed());
  ASSERT_EQ(report.solves.size(), 2u);
  const auto& pupil = report.solves[1];
  EXPECT_EQ(pupil.binding, "matching");
  ASSERT_EQ(pupil.roots.size(), 2u);
  // The kept pupil is the larger root, and at it both margins hold.
  EXPECT_DOUBLE_EQ(pupil.value_si, std::max(pupil.roots[0].second, pupil.roots[1].second));
  EXPECT_GE(value(report, "criteria.energy.margin"), 0.0);
  EXPECT_NEAR(value(report, "criteria.matching.margin"), 0.0, 1e-9);
  // Eq. (12) at η = 0.8 with the exact coefficient 2·1.218·u½.
  const double u = 0.6033545644;
  const double f = value(report, "optics.focal_length");
  EXPECT_NEAR(pupil.value_si, 2 * 1.218 * u * f * 0.76e-6 / (0.8 * 7e-6), 1e-6);
  // The real ground-track speed of a 400 km circular orbit (WGS 84 GM, R = 6371 km).
  const double r = 6371e3, gm = 3.986004418e14, a = r + 400e3;
  EXPECT_NEAR(value(report, "platform.ground_speed"), std::sqrt(gm / a) * r / a, 1e-6);
}

TEST(KolobrodovSensor, EnergyPupilScalesWithTheSquareRootOfTheThreshold) {
  // Eq. (22): D0 ∝ sqrt(E_n) — doubling the noise-equivalent exposure multiplies the pupil by √2.
  radchain::Chain base = radchain::load_sensor(paper_file);
  radchain::Chain doubled = radchain::load_sensor(paper_file, {{"detector.nee", "0.0004 uJ/cm2"}});
  const double d1 = base.run().value("optics.aperture").value();
  const double d2 = doubled.run().value("optics.aperture").value();
  EXPECT_NEAR(d2 / d1, std::numbers::sqrt2, 1e-9);
}

}  // namespace

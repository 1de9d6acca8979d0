// The Earth-observation chain of issue 14 — earth_orbit, pixel_array, gsd_requirement, giqe — run from the
// bundled files (sensors/worldview-2-pan*.toml, sensors/sentinel-2a-msi-b4.toml, examples/eo-design-niirs5.toml)
// and checked against the closed forms of spherical-Earth geometry and the GIQE-5 computed here independently.
#include "radchain/chain.hpp"
#include "radchain/error.hpp"
#include "radchain/physics/earth_geometry.hpp"
#include "radchain/physics/giqe.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace {
using namespace radchain;

const std::string root = std::string(RADCHAIN_SOURCE_DIR) + "/";
constexpr double deg = std::numbers::pi / 180, R = 6371.0e3;

double value(const Report& r, const std::string& name) {
  const auto v = r.value(name);
  EXPECT_TRUE(v.has_value()) << name;
  return v.value_or(NAN);
}

TEST(EarthObservation, WorldView2At20DegreesMatchesTheClosedForm) {
  Chain chain = load_sensor(root + "sensors/worldview-2-pan-20deg.toml");
  const Report r = chain.run();
  const double h = 770e3, ifov = 8e-6 / 13.3, theta = 20 * deg;
  // law of cosines / sines by hand: ρ = (R+h) cos θ − √(R² − (R+h)² sin² θ), sin η = (R+h) sin θ / R
  const double s = R + h;
  const double rho = s * std::cos(theta) - std::sqrt(R * R - s * s * std::sin(theta) * std::sin(theta));
  const double eta = std::asin(s * std::sin(theta) / R);
  EXPECT_NEAR(value(r, "platform.slant_range"), rho, 1e-6);
  EXPECT_NEAR(value(r, "platform.view_zenith_angle"), eta, 1e-12);
  EXPECT_NEAR(value(r, "criteria.gsd.gsd_across_track"), rho * ifov / std::cos(eta), 1e-6);
  EXPECT_NEAR(value(r, "criteria.gsd.gsd_along_track"), rho * ifov, 1e-6);
  EXPECT_NEAR(value(r, "criteria.gsd.gsd_nadir"), h * ifov, 1e-12);
  // the published 0.52 m at 20° (eoPortal) — the flat-Earth geometric mean would be 0.508 m
  EXPECT_NEAR(value(r, "criteria.gsd.gsd_geometric_mean"), 0.52, 0.005);
  EXPECT_GT(std::abs(h * ifov / std::pow(std::cos(theta), 1.5) - 0.52), 0.01);
}

TEST(EarthObservation, LookPastTheHorizonIsAnInputError) {
  EXPECT_THROW(load_sensor(root + "sensors/worldview-2-pan.toml", {Override{"platform.roll", "\"70 deg\""}}),
               InputError);
}

TEST(EarthObservation, FocalLengthForAGsdAtALookAndApertureForNiirs5) {
  Chain chain = load_sensor(root + "examples/eo-design-niirs5.toml");
  const Report r = chain.run();
  ASSERT_EQ(r.solves.size(), 2u);
  for (const auto& s : r.solves) EXPECT_TRUE(s.converged) << s.message;
  // f' for a geometric-mean GSD g at θ: g = ρ (p/f') / √cos η  ⇒  f' = p ρ / (g √cos η)
  const double h = 500e3, theta = 25 * deg, s = R + h, p = 8e-6, g = 0.5;
  const double rho = s * std::cos(theta) - std::sqrt(R * R - s * s * std::sin(theta) * std::sin(theta));
  const double eta = std::asin(s * std::sin(theta) / R);
  EXPECT_NEAR(value(r, "optics.focal_length"), p * rho / (g * std::sqrt(std::cos(eta))), 1e-6);
  // at the solved aperture the GIQE-5 of the reported GSD, RER and SNR is 5 (independent evaluation)
  const double rer = value(r, "criteria.quality.rer");
  EXPECT_NEAR(physics::giqe5_niirs(value(r, "criteria.quality.gsd_geometric_mean"), rer, 50), 5.0, 1e-6);
  EXPECT_NEAR(value(r, "criteria.quality.niirs"), 5.0, 1e-6);
  EXPECT_GT(rer, 0.0);
  EXPECT_LT(rer, 1.0);
}

TEST(EarthObservation, Sentinel2DiffractionTimesPixelAtNyquist) {
  Chain chain = load_sensor(root + "sensors/sentinel-2a-msi-b4.toml");
  const Report r = chain.run();
  EXPECT_NEAR(value(r, "criteria.iq.mtf_nyquist_system"), 0.493636, 1e-6);
  EXPECT_NEAR(value(r, "criteria.iq.mtf_nyquist_pixel"), 2 / std::numbers::pi, 1e-12);
  EXPECT_NEAR(value(r, "criteria.gsd.gsd_nadir"), 9.825, 1e-9);
  // swath: 2 R λ(10.3°), λ = η − θ (closed form)
  const double h = 786e3, a = 10.3 * deg, s = R + h;
  EXPECT_NEAR(value(r, "criteria.gsd.swath"), 2 * R * (std::asin(s * std::sin(a) / R) - a), 1e-3);
}

}  // namespace

// The Earth-observation chain — earth_orbit, pixel_array, gsd_requirement, giqe — run from the
// bundled files (sensors/worldview-2-pan*.toml, sensors/sentinel-2a-msi-b4.toml, examples/eo-design-niirs5.toml)
// and checked against the closed forms of spherical-Earth geometry and the GIQE-5 computed here independently.
#include "radchain/chain.hpp"
#include "radchain/error.hpp"
#include "radchain/physics/earth_geometry.hpp"
#include "radchain/physics/giqe.hpp"

#include "radchain/sensor_file.hpp"
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>
#include <unistd.h>

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

// A pushbroom reads a line each time the ground moves one line spacing: the along-track GSD for square samples, or
// the published sampling of an oversampling camera (SPOT-5 HRS: 5 m lines for 10 m pixels). Line time = spacing /
// ground speed; the ground speed is that of the sub-satellite point over the Earth's surface, which turns under a
// retrograde sun-synchronous orbit: v² = v₀² − 2 v₀ ω R cos i + (ω R cos φ)², v₀ = √(GM/(R+h)) R/(R+h) (the
// closed form is checked against the Earth-fixed track in tests/core/physics/earth_geometry_test.cpp).
std::string without_lines(const std::string& file, std::initializer_list<const char*> keys) {
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* key : keys) {
    const auto at = text.find(std::string("\n") + key + " ");
    if (at != std::string::npos) text.erase(at + 1, text.find('\n', at + 1) - at);
  }
  return text;
}

TEST(EarthObservation, LineTimeFromTheAlongTrackSampling) {
  const std::string file = root + "sensors/spot-5-hrs-fore.toml";
  Chain chain = load_sensor(file);
  const Report r = chain.run();
  const double gm = 3.986004418e14, R = value(r, "platform.earth_radius"), h = value(r, "platform.altitude");
  const double v0 = std::sqrt(gm / (R + h)) * R / (R + h), u = 7.292115e-5 * R, cos_i = std::cos(98.7 * std::numbers::pi / 180);
  const double ground_speed = std::sqrt(v0 * v0 - 2 * v0 * u * cos_i + u * u);  // at the equator
  EXPECT_NEAR(value(r, "platform.inertial_ground_speed"), v0, 1e-6 * v0);
  EXPECT_NEAR(value(r, "platform.ground_speed"), ground_speed, 1e-6 * ground_speed);
  EXPECT_NEAR(ground_speed - v0, 86.1, 0.5);  // ω R |cos i| = 70 m/s plus (ω R)²/(2 v₀) = 16 m/s
  EXPECT_NEAR(value(r, "criteria.gsd.line_time"), 5.0 / ground_speed, 1e-9 * 5.0 / ground_speed);
  // Without inclination and latitude: a non-rotating Earth, v₀.
  Chain inertial = load_sensor_text(without_lines(file, {"inclination", "latitude"}), file);
  EXPECT_NEAR(value(inertial.run(), "platform.ground_speed"), v0, 1e-6 * v0);
  // Without the sampling key: square samples, the along-track GSD at the look.
  Chain square = load_sensor_text(without_lines(file, {"along_track_sampling"}), file);
  const Report s = square.run();
  EXPECT_NEAR(value(s, "criteria.gsd.line_time"), value(s, "criteria.gsd.gsd_along_track") / ground_speed, 1e-9);
}

TEST(EarthObservation, RotatingEarthNeedsBothKeysAndAReachableLatitude) {
  const std::string file = root + "sensors/spot-5-hrs-fore.toml";
  EXPECT_THROW(load_sensor_text(without_lines(file, {"latitude"}), file), InputError);
  EXPECT_THROW(load_sensor_text(without_lines(file, {"inclination"}), file), InputError);
  // 98.7° reaches ±81.3°: 85° is never under the track.
  try {
    load_sensor(file, {Override{"platform.latitude", "\"85 deg\""}});
    ADD_FAILURE() << "latitude 85 deg accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("never passes over latitude 85"), std::string::npos) << e.what();
  }
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
  // at the solved aperture the GIQE-5 is 5, evaluated independently: the weighted GSD of NGA eq. (5) from the
  // closed-form slant range and elevation, the weighted RER of eq. (7) from the two directions' RERs
  const double f = value(r, "optics.focal_length"), elevation = 90 * deg - eta;
  const double gsd_w = p * rho / f / std::pow(std::sin(elevation), 0.25);
  EXPECT_NEAR(value(r, "criteria.quality.gsd_normal_plane"), p * rho / f, 1e-9);
  EXPECT_NEAR(value(r, "criteria.quality.target_elevation"), elevation, 1e-12);
  EXPECT_NEAR(value(r, "criteria.quality.gsd_inches"), gsd_w / 0.0254, 1e-9);
  const double across = value(r, "criteria.quality.rer_across_track"), along = value(r, "criteria.quality.rer_along_track");
  EXPECT_LT(along, across);  // the example's smear and TDI act along track
  const double rer = value(r, "criteria.quality.rer");
  EXPECT_NEAR(rer, std::cbrt(across * along * along), 1e-15);
  EXPECT_NEAR(physics::giqe5_niirs(gsd_w, rer, 50), 5.0, 1e-6);
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

TEST(EarthObservation, AltitudeForAGsdAtALook) {
  // The WorldView-2 camera at 20° roll: the altitude at which the geometric-mean GSD is 0.5 m, found by the
  // chain's [[solve]] and, independently, by bisection on the closed form g(h) = ρ(h) IFOV / √cos η(h).
  std::ifstream in(root + "sensors/worldview-2-pan-20deg.toml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text = text.substr(0, text.find("[expected]"));
  text += "[[solve]]\nunknown = \"platform.altitude\"\ncriterion = \"gsd\"\nbracket = [\"300 km\", \"1500 km\"]\n";
  const auto path = std::filesystem::temp_directory_path() / ("eo_altitude_" + std::to_string(::getpid()) + ".toml");
  std::ofstream(path) << text;
  Chain chain = load_sensor(path.string());
  const Report r = chain.run();
  std::filesystem::remove(path);
  ASSERT_EQ(r.solves.size(), 1u);
  EXPECT_TRUE(r.solves[0].converged) << r.solves[0].message;
  const double ifov = 8e-6 / 13.3, theta = 20 * deg;
  auto gsd = [&](double h) {
    const double s = R + h;
    const double rho = s * std::cos(theta) - std::sqrt(R * R - s * s * std::sin(theta) * std::sin(theta));
    return rho * ifov / std::sqrt(std::cos(std::asin(s * std::sin(theta) / R)));
  };
  double lo = 300e3, hi = 1500e3;
  for (int i = 0; i < 200; ++i) (gsd(0.5 * (lo + hi)) < 0.5 ? lo : hi) = 0.5 * (lo + hi);
  EXPECT_NEAR(r.value("platform.altitude").value(), 0.5 * (lo + hi), 1e-3);
  EXPECT_NEAR(r.value("criteria.gsd.gsd_geometric_mean").value(), 0.5, 1e-9);
}

TEST(EarthObservation, Giqe4OptionUsesTheEdgeOvershoot) {
  Chain chain = load_sensor(root + "sensors/worldview-2-pan.toml", {Override{"criteria.iq.equation", "\"giqe4\""}});
  const Report r = chain.run();
  const double h = value(r, "criteria.iq.overshoot");
  EXPECT_GT(h, 0.5);  // diffraction × pixel rises monotonically: H = ER(1.25) < 1
  EXPECT_LT(h, 1.0);
  EXPECT_NEAR(value(r, "criteria.iq.niirs"),
              physics::giqe4_niirs(value(r, "criteria.iq.gsd_geometric_mean"), value(r, "criteria.iq.rer"), h, 1, 50),
              1e-12);
}

}  // namespace

// A dated scene: the sun's day_of_year sets its distance and declination, the ground's latitude
// and local solar time its zenith angle; against the closed forms computed here and the undated chain.
namespace dated {
std::string sentinel_with(const std::string& source_extra, const std::string& target_lines) {
  std::ifstream in(root + "sensors/sentinel-2a-msi-b4.toml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto source = text.find("plugin = \"sun\"");
  text.insert(text.find('\n', source) + 1, source_extra);
  const auto zenith = text.find("solar_zenith = \"30 deg\"");
  text.replace(zenith, text.find('\n', zenith) - zenith, target_lines);
  return text;
}

TEST(DatedScene, DayLatitudeAndTimeGiveTheSunsZenithAndDistance) {
  const std::string file = root + "sensors/sentinel-2a-msi-b4.toml";
  Chain chain = load_sensor_text(sentinel_with("day_of_year = 172\n", "latitude = \"43.6 deg\"\nlocal_solar_time = \"10.5 h\""), file);
  const Report r = chain.run();
  const double pi = std::numbers::pi, g = 2 * pi * 171 / 365;
  const double dec = 0.006918 - 0.399912 * std::cos(g) + 0.070257 * std::sin(g) - 0.006758 * std::cos(2 * g) +
                     0.000907 * std::sin(2 * g) - 0.002697 * std::cos(3 * g) + 0.00148 * std::sin(3 * g);
  const double lat = 43.6 * pi / 180, h = -1.5 * pi / 12;
  const double mu = std::sin(lat) * std::sin(dec) + std::cos(lat) * std::cos(dec) * std::cos(h);
  EXPECT_NEAR(value(r, "source.solar_declination"), dec, 1e-12);
  EXPECT_NEAR(value(r, "target.cos_solar_zenith"), mu, 1e-12);
  EXPECT_NEAR(std::cos(value(r, "target.solar_zenith")), mu, 1e-12);
  const double r_au = 1 / std::sqrt(1.000110 + 0.034221 * std::cos(g) + 0.001280 * std::sin(g) + 0.000719 * std::cos(2 * g) +
                                    0.000077 * std::sin(2 * g));
  EXPECT_NEAR(value(r, "source.distance"), r_au * 149597870700.0, 1.0);
  // The same scene undated, at that zenith and distance: the same signal.
  Chain undated = load_sensor(file, {Override{"target.solar_zenith", fmt::format("\"{:.17g} rad\"", std::acos(mu))},
                                     Override{"source.distance", fmt::format("\"{:.17g} m\"", r_au * 149597870700.0)}});
  EXPECT_NEAR(value(r, "detector.signal_electrons"), value(undated.run(), "detector.signal_electrons"),
              1e-9 * value(r, "detector.signal_electrons"));
}

TEST(DatedScene, NightMissingPiecesAndTwoZenithsAreRefused) {
  const std::string file = root + "sensors/sentinel-2a-msi-b4.toml";
  // Polar night: 80° N on 21 December at noon, the Sun 13.4° below the horizon.
  try {
    load_sensor_text(sentinel_with("day_of_year = 355\n", "latitude = \"80 deg\"\nlocal_solar_time = \"12 h\""), file).run();
    ADD_FAILURE() << "a scene at night was evaluated";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("below the horizon"), std::string::npos) << e.what();
  }
  EXPECT_THROW(load_sensor_text(sentinel_with("", "latitude = \"43.6 deg\"\nlocal_solar_time = \"10.5 h\""), file), InputError);
  EXPECT_THROW(load_sensor_text(sentinel_with("day_of_year = 172\n", "latitude = \"43.6 deg\""), file), InputError);
  EXPECT_THROW(load_sensor_text(sentinel_with("day_of_year = 172\n",
                                              "latitude = \"43.6 deg\"\nlocal_solar_time = \"10.5 h\"\nsolar_zenith = \"30 deg\""),
                                file),
               InputError);
  EXPECT_THROW(load_sensor_text(sentinel_with("day_of_year = 172\ndistance = \"1 AU\"\n", "solar_zenith = \"30 deg\""), file),
               InputError);
}
}  // namespace dated

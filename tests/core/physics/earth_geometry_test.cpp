// Spherical-Earth viewing geometry (physics/earth_geometry.hpp) against independent closed forms: the law of
// cosines and of sines in the triangle Earth centre – satellite – ground point, the flat-Earth limits, and the
// pixel-pitch GSD of a real imager computed by hand.
#include "radchain/physics/earth_geometry.hpp"
#include "radchain/physics/pushbroom.hpp"
#include "radchain/physics/solar_position.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

namespace {

using namespace radchain::physics;
constexpr double pi = std::numbers::pi;
constexpr double deg = pi / 180, km = 1e3, um = 1e-6;
constexpr double R = 6371.0 * km;

TEST(EarthGeometry, PixelPitchGsdIsAltitudeTimesIfov) {
  // Sentinel-2 MSI 10 m bands: h = 786 km, p = 7.5 µm, f' = 600 mm → 786e3 · 7.5e-6 / 0.6 = 9.825 m (by hand).
  EXPECT_NEAR(pixel_pitch_gsd_m(786 * km, 7.5 * um, 0.6), 9.825, 1e-12);
}

TEST(EarthGeometry, SlantRangeObeysTheLawOfCosines) {
  const double h = 700 * km, s = R + h;
  for (double theta_deg : {0.0, 5.0, 20.0, 45.0, 60.0}) {
    const double theta = theta_deg * deg;
    const double rho = slant_range_m(h, theta, R);
    // R² = ρ² + s² − 2ρ s cos θ (independent of the quadratic's root formula)
    EXPECT_NEAR(rho * rho + s * s - 2 * rho * s * std::cos(theta), R * R, 1e-9 * R * R) << theta_deg;
    // law of sines: ρ = R sin λ / sin θ with λ = η − θ (θ > 0)
    if (theta_deg > 0) {
      const double lambda = earth_central_angle_rad(h, theta, R);
      EXPECT_NEAR(rho, R * std::sin(lambda) / std::sin(theta), 1e-6) << theta_deg;
    }
  }
  EXPECT_DOUBLE_EQ(slant_range_m(h, 0, R), h);
}

TEST(EarthGeometry, HorizonAndBeyond) {
  const double h = 500 * km;
  const double horizon = horizon_off_nadir_angle_rad(h, R);
  EXPECT_NEAR(horizon, std::asin(R / (R + h)), 1e-15);
  EXPECT_NEAR(horizon / deg, 68.0, 0.1);  // 500 km: horizon ~68° off nadir (SMAD Table 5-3 style estimate)
  // At the horizon the slant range is the tangent length √(s² − R²).
  // (ρ has an infinite slope there: 1e-12 of θ moves it by ~6 m, so 1e-5 relative)
  const double tangent = std::sqrt((R + h) * (R + h) - R * R);
  EXPECT_NEAR(slant_range_m(h, horizon * (1 - 1e-12), R), tangent, 1e-5 * tangent);
  EXPECT_THROW(slant_range_m(h, horizon + 0.01, R), LookPastHorizon);
  EXPECT_THROW(gsd_across_track_m(h, 80 * deg, 0, 1e-5, R), LookPastHorizon);
}

TEST(EarthGeometry, GsdAtARollEqualsTheClosedFormInAndAcrossTheLookPlane) {
  const double h = 617 * km, ifov = 0.31 / 617e3;  // a 31 cm GSD camera
  for (double roll_deg : {0.0, 10.0, 30.0, 45.0}) {
    const double roll = roll_deg * deg;
    const double eta = view_zenith_angle_rad(h, roll, R);
    const double rho = slant_range_m(h, roll, R);
    EXPECT_NEAR(gsd_across_track_m(h, roll, 0, ifov, R), rho * ifov / std::cos(eta), 1e-6 * rho * ifov) << roll_deg;
    EXPECT_NEAR(gsd_along_track_m(h, roll, 0, ifov, R), rho * ifov, 1e-6 * rho * ifov) << roll_deg;
    // a pure pitch swaps the two
    EXPECT_NEAR(gsd_along_track_m(h, 0, roll, ifov, R), rho * ifov / std::cos(eta), 1e-6 * rho * ifov) << roll_deg;
    EXPECT_NEAR(gsd_across_track_m(h, 0, roll, ifov, R), rho * ifov, 1e-6 * rho * ifov) << roll_deg;
    EXPECT_NEAR(gsd_in_look_plane_m(h, roll, ifov, R), rho * ifov / std::cos(eta), 1e-9);
  }
  // WorldView-3-like at 30° off nadir: in-plane GSD grows by ρ/(h cos η) = 1.42 over nadir on a sphere
  // (flat Earth: 1/cos² 30° = 1.333) — the curvature term a flat-Earth design misses.
  const double growth = gsd_across_track_m(h, 30 * deg, 0, ifov, R) / gsd_across_track_m(h, 0, 0, ifov, R);
  EXPECT_GT(growth, 1.0 / std::pow(std::cos(30 * deg), 2));
  EXPECT_NEAR(growth, slant_range_m(h, 30 * deg, R) / (h * std::cos(view_zenith_angle_rad(h, 30 * deg, R))), 1e-5);
}

TEST(EarthGeometry, FlatEarthLimit) {
  const double big = 1e13, h = 500 * km, ifov = 1e-6, theta = 40 * deg;  // R → ∞
  EXPECT_NEAR(gsd_in_look_plane_m(h, theta, ifov, big), h * ifov / std::pow(std::cos(theta), 2), 1e-6);
  EXPECT_NEAR(gsd_across_look_plane_m(h, theta, ifov, big), h * ifov / std::cos(theta), 1e-6);
}

TEST(EarthGeometry, CombinedRollAndPitchKeepTheCameraFrame) {
  // Pixels along the line stay Δθ apart in angle at any (roll, pitch): across-track GSD ≈ ρ Δθ / cos(angle
  // between the across direction and the ground) — checked here against the pure cases' symmetry: pitch then
  // roll of equal size give the same off-nadir angle and slant range, and the along-track GSD at pure pitch ψ
  // equals the across-track GSD at pure roll ψ.
  const double h = 600 * km, ifov = 1e-6;
  EXPECT_NEAR(gsd_along_track_m(h, 0, 25 * deg, ifov, R), gsd_across_track_m(h, 25 * deg, 0, ifov, R), 1e-9);
  EXPECT_NEAR(gsd_across_track_m(h, 0, 25 * deg, ifov, R), gsd_along_track_m(h, 25 * deg, 0, ifov, R), 1e-9);
  const double theta = off_nadir_angle_rad(20 * deg, 15 * deg);
  // both GSDs lie between the perpendicular ρΔθ and the in-plane ρΔθ/cos η at the combined angle
  const double lo = gsd_across_look_plane_m(h, theta, ifov, R), hi = gsd_in_look_plane_m(h, theta, ifov, R);
  for (double g : {gsd_across_track_m(h, 20 * deg, 15 * deg, ifov, R), gsd_along_track_m(h, 20 * deg, 15 * deg, ifov, R)}) {
    EXPECT_GE(g, lo * (1 - 1e-6));
    EXPECT_LE(g, hi * (1 + 1e-6));
  }
}

TEST(EarthGeometry, SwathIsTheArcBetweenTheEdgeLooks) {
  // Nadir-centred: swath = 2 R λ(α), λ the Earth central angle of the edge look (closed form).
  const double h = 786 * km, alpha = 10.3 * deg;
  EXPECT_NEAR(swath_m(h, 0, 0, alpha, R), 2 * R * earth_central_angle_rad(h, alpha, R), 1e-3);
  // longer than the flat-Earth 2 h tan α
  EXPECT_GT(swath_m(h, 0, 0, alpha, R), 2 * h * std::tan(alpha));
  EXPECT_NEAR(half_field_angle_rad(0.1, 0.5), std::atan(0.1), 1e-15);
}

TEST(EarthGeometry, OffNadirAngleAndLineTime) {
  EXPECT_NEAR(off_nadir_angle_rad(30 * deg, 0), 30 * deg, 1e-15);
  // Near nadir the angle keeps its relative precision (acos of cos φ cos ψ lost it: 3e-5 at 2e-6 rad); with roll
  // alone it is |φ|, with both √(φ² + ψ²) to second order.
  for (double roll : {1.9164066912343387e-06, -3e-9, 1e-4}) EXPECT_NEAR(off_nadir_angle_rad(roll, 0) / std::abs(roll), 1, 1e-15);
  EXPECT_NEAR(off_nadir_angle_rad(3e-7, 4e-7) / 5e-7, 1, 1e-14);
  EXPECT_EQ(off_nadir_angle_rad(0, 0), 0);
  EXPECT_NEAR(std::cos(off_nadir_angle_rad(20 * deg, 15 * deg)), std::cos(20 * deg) * std::cos(15 * deg), 1e-15);
  EXPECT_DOUBLE_EQ(line_time_s(10.0, 6.7e3), 10.0 / 6.7e3);
  EXPECT_THROW(line_time_s(10.0, 0), std::invalid_argument);
}

}  // namespace

// The ground speed over the rotating Earth (Clairaut's closed form) against a direct computation: the sub-satellite
// point moved along its inclined great circle on the inertial sphere, turned into Earth-fixed axes, differentiated.
TEST(EarthGeometry, GroundSpeedOverTheRotatingEarthMatchesTheEarthFixedTrack) {
  constexpr double radius = 6371e3, h = 822e3, w = 7.292115e-5;
  const double v0 = radchain::physics::ground_track_speed_m_s(h, 3.986004418e14, radius);
  for (double i_deg : {0.0, 28.5, 51.6, 90.0, 98.7, 150.0})
    for (double u_deg : {0.0, 20.0, 45.0, 80.0, 135.0, 250.0}) {
      const double i = i_deg * pi / 180, u0 = u_deg * pi / 180, rate = v0 / radius;
      auto earth_fixed = [&](double t) {  // R_z(−ω t) · R · (cos u, sin u cos i, sin u sin i)
        const double u = u0 + rate * t, x = std::cos(u), y = std::sin(u) * std::cos(i), z = std::sin(u) * std::sin(i);
        const double c = std::cos(w * t), s = std::sin(w * t);
        return std::array{radius * (c * x + s * y), radius * (-s * x + c * y), radius * z};
      };
      const double dt = 1e-2;
      const auto a = earth_fixed(-dt), b = earth_fixed(dt);
      const double direct = std::hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]) / (2 * dt);
      const double latitude = std::asin(std::sin(u0) * std::sin(i));
      EXPECT_NEAR(radchain::physics::rotating_earth_ground_speed_m_s(v0, i, latitude, radius, w), direct, 1e-6 * direct)
          << "i = " << i_deg << " deg, u = " << u_deg << " deg";
    }
  // An equatorial prograde orbit loses ω R exactly; a retrograde one gains it.
  EXPECT_NEAR(radchain::physics::rotating_earth_ground_speed_m_s(v0, 0, 0, radius, w), v0 - w * radius, 1e-9);
  EXPECT_NEAR(radchain::physics::rotating_earth_ground_speed_m_s(v0, pi, 0, radius, w), v0 + w * radius, 1e-9);
  // A latitude the track never reaches is refused.
  EXPECT_THROW(radchain::physics::rotating_earth_ground_speed_m_s(v0, 10 * pi / 180, 30 * pi / 180, radius, w), std::invalid_argument);
}

// The Sun's position for a dated scene (Spencer 1971; physics/solar_position.hpp) against independent values: the
// Astronomical Almanac's declinations at the 2023 solstices and equinox (+23.44°, −23.44°, ≈0° within Spencer's
// stated 0.0006 rad = 0.034° plus the day's own motion, ≤ 0.4° near the equinox), the perihelion/aphelion
// distances 0.98329 / 1.01671 AU (the series meets them to 4e-4 AU, 0.08 % in irradiance: measured here, not
// Spencer's own claim), and the zenith angle by spherical trigonometry.
TEST(SolarPosition, DeclinationDistanceAndZenith) {
  using radchain::physics::earth_sun_distance_au;
  using radchain::physics::solar_declination_rad;
  using radchain::physics::solar_zenith_rad;
  EXPECT_NEAR(solar_declination_rad(172) / deg, 23.44, 0.05);   // 21 June
  EXPECT_NEAR(solar_declination_rad(355) / deg, -23.44, 0.05);  // 21 December
  EXPECT_NEAR(solar_declination_rad(80) / deg, 0.0, 0.5);       // 21 March (the equinox falls on day 79-80)
  EXPECT_NEAR(earth_sun_distance_au(3), 0.98329, 5e-4);         // perihelion, ~3 January
  EXPECT_NEAR(earth_sun_distance_au(185), 1.01671, 5e-4);       // aphelion, ~4 July
  // At local noon the zenith angle is |φ − δ|; six hours from noon on an equinox (δ = 0) the Sun is on the horizon.
  for (double lat : {-60.0, -10.0, 0.0, 23.44, 45.0, 70.0})
    for (double dec : {-23.44, 0.0, 10.0, 23.44})
      EXPECT_NEAR(solar_zenith_rad(lat * deg, dec * deg, 12 * 3600.0), std::abs(lat - dec) * deg, 1e-12) << lat << " " << dec;
  EXPECT_NEAR(solar_zenith_rad(45 * deg, 0, 6 * 3600.0), pi / 2, 1e-12);
  // Against the direction cosines: the Sun's unit vector (cos δ cos h, cos δ sin h, sin δ) dotted with the zenith
  // (cos φ, 0, sin φ), at 10:30 local solar time.
  const double lat = 38.5 * deg, dec = -12.0 * deg, h = -1.5 / 12 * pi;
  EXPECT_NEAR(std::cos(solar_zenith_rad(lat, dec, 10.5 * 3600)),
              std::cos(dec) * std::cos(h) * std::cos(lat) + std::sin(dec) * std::sin(lat), 1e-14);
}

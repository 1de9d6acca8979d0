// A satellite on a circular orbit over a spherical Earth, looking at the ground along a line of sight rotated by
// roll (across track) and pitch (along track). Publishes what circular_orbit publishes (altitude, ground speed,
// off-nadir angle as platform.tilt) and the viewing geometry a modern EO design review needs: slant range and
// view zenith angle at the ground point (closed-form spherical trigonometry, physics/earth_geometry.hpp). The view
// zenith is set in the spectral phase as well, for an atmosphere that reads its tables at the view airmass.
// A look past the horizon is a located error here (for the file's values) and an error during a solve.
#include "radchain/physics/earth_geometry.hpp"
#include "radchain/physics/pushbroom.hpp"
#include "radchain/plugin.hpp"

#include <cmath>
#include <fmt/format.h>
#include <numbers>

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      quantity("altitude", "m", "786 km").needed().above(0).at_most(1e9).described("orbit altitude h above the surface"),
      quantity("roll", "rad", "10 deg").fallback("0 deg").above(-1.5707963267948966).below(1.5707963267948966)
          .described("look angle across track (rotation about the along-track axis)"),
      quantity("pitch", "rad", "0 deg").fallback("0 deg").above(-1.5707963267948966).below(1.5707963267948966)
          .described("look angle along track (rotation about the across-track axis, after the roll)"),
      quantity("ground_speed", "m/s", "6.6 km/s").above(0)
          .described("pin the ground-track speed; default: circular orbit over a non-rotating Earth"),
      quantity("earth_radius", "m", "6371 km").fallback("6371 km").above(0)
          .described("spherical Earth radius R (default: IUGG mean radius; 6378.137 km = WGS 84 equatorial)"),
      quantity("earth_gm", "m3 s-2", "3.986004418e14 m3/s2").fallback("3.986004418e14 m3/s2").above(0)
          .described("geocentric gravitational constant GM (WGS 84)"),
      quantity("inclination", "rad", "98.7 deg").at_least(0).at_most(std::numbers::pi)
          .described("orbit inclination i: given, the ground speed is over the rotating Earth at `latitude`"),
      quantity("latitude", "rad", "45 deg").at_least(-std::numbers::pi / 2).at_most(std::numbers::pi / 2)
          .described("latitude φ of the sub-satellite point (needs inclination; within ±i of the equator)"),
  };
  return s;
}

class EarthOrbit final : public Stage {
 public:
  explicit EarthOrbit(const Params& p)
      : altitude_(p.handle("altitude")), roll_(p.handle("roll")), pitch_(p.handle("pitch")),
        radius_(p.handle("earth_radius")), gm_(p.handle("earth_gm")), pinned_speed_(p.handle("ground_speed")),
        inclination_(p.handle("inclination")), latitude_(p.handle("latitude")), speed_pinned_(p.has("ground_speed")),
        rotating_(p.has("inclination")) {
    if (p.has("latitude") && !rotating_) p.reject("latitude", "needs the orbit's inclination (the Earth's rotation at that latitude)");
    if (rotating_ && !p.has("latitude"))
      p.reject("inclination", "needs the latitude of the sub-satellite point, where the Earth's rotation is taken");
    if (rotating_ && speed_pinned_) p.reject("ground_speed", "is pinned: give it or the orbit's inclination and latitude, not both");
    if (rotating_ && std::cos(*latitude_) < std::abs(std::cos(*inclination_)) * (1 - 1e-12))
      p.reject("latitude", fmt::format("an orbit inclined {:.4g} deg never passes over latitude {:.4g} deg",
                                       *inclination_ * 180 / std::numbers::pi, *latitude_ * 180 / std::numbers::pi));
    // Located error for the file's own values (SMAD §5.2: sin θ_h = R/(R + h)).
    const double theta = physics::off_nadir_angle_rad(*roll_, *pitch_);
    const double horizon = physics::horizon_off_nadir_angle_rad(*altitude_, *radius_);
    if (theta >= horizon) {
      constexpr double deg = 180 / std::numbers::pi;
      p.reject(p.given("roll") ? "roll" : "pitch",
               fmt::format("the line of sight ({:.4g} deg off nadir) misses the Earth: from {:.4g} km the horizon is "
                           "{:.4g} deg off nadir",
                           theta * deg, *altitude_ / 1e3, horizon * deg));
    }
  }

  void prepare(Context& c) override {
    id_altitude_ = c.declare(vocabulary::platform_altitude, "input h", "km");
    id_tilt_ = c.declare(vocabulary::platform_tilt, "off-nadir angle θ: cos θ = cos(roll) cos(pitch)", "deg");
    id_roll_ = c.declare(vocabulary::platform_roll, "input", "deg");
    id_pitch_ = c.declare(vocabulary::platform_pitch, "input", "deg");
    id_radius_ = c.declare(vocabulary::platform_earth_radius, "input R", "km");
    id_range_ = c.declare(vocabulary::platform_slant_range,
                          "ρ = (R+h) cos θ − √(R² − (R+h)² sin² θ) (SMAD 3rd ed. §5.2)", "km");
    id_zenith_ = c.declare(vocabulary::platform_view_zenith_angle, "sin η = (R+h) sin θ / R (SMAD §5.2)", "deg");
    // Now too, for an atmosphere's spectral phase (an RT table read at the view airmass): where one reads it,
    // altitude, roll, pitch and the Earth's radius re-run the spectral phase (Chain::set); elsewhere they stay scalar.
    c.set_in_spectral_phase(id_zenith_,
                            physics::view_zenith_angle_rad(*altitude_, physics::off_nadir_angle_rad(*roll_, *pitch_), *radius_),
                            {altitude_, roll_, pitch_, radius_});
    id_central_ = c.declare("earth_central_angle", "rad", "λ = η − θ (SMAD §5.2)", "deg");
    id_horizon_ = c.declare("horizon_off_nadir_angle", "rad", "sin θ_h = R/(R+h)", "deg");
    id_orbit_speed_ = c.declare("orbital_speed", "m/s", "√(GM/(R+h)), circular orbit", "km/s");
    id_speed_ = c.declare(vocabulary::platform_ground_speed,
                          speed_pinned_ ? "pinned"
                          : rotating_   ? "√(v₀² − 2 v₀ ω R cos i + (ω R cos φ)²) over the rotating Earth (Clairaut), "
                                          "v₀ = √(GM/(R+h))·R/(R+h)"
                                        : "√(GM/(R+h))·R/(R+h), sub-satellite point, non-rotating Earth",
                          "km/s");
    if (rotating_)
      id_inertial_speed_ = c.declare("inertial_ground_speed", "m/s", "v₀ = √(GM/(R+h))·R/(R+h) (non-rotating Earth)", "km/s");
  }

  void evaluate(Context& c) override {
    const double h = *altitude_, r = *radius_;
    const double theta = physics::off_nadir_angle_rad(*roll_, *pitch_);
    c.results.set(id_altitude_, h);
    c.results.set(id_tilt_, theta);
    c.results.set(id_roll_, *roll_);
    c.results.set(id_pitch_, *pitch_);
    c.results.set(id_radius_, r);
    c.results.set(id_range_, physics::slant_range_m(h, theta, r));  // throws past the horizon (during a solve)
    c.results.set(id_zenith_, physics::view_zenith_angle_rad(h, theta, r));
    c.results.set(id_central_, physics::earth_central_angle_rad(h, theta, r));
    c.results.set(id_horizon_, physics::horizon_off_nadir_angle_rad(h, r));
    c.results.set(id_orbit_speed_, physics::circular_orbit_speed_m_s(h, *gm_, r));
    const double v0 = physics::ground_track_speed_m_s(h, *gm_, r);
    c.results.set(id_speed_, speed_pinned_ ? *pinned_speed_
                             : rotating_   ? physics::rotating_earth_ground_speed_m_s(v0, *inclination_, *latitude_, r)
                                           : v0);
    if (rotating_) c.results.set(id_inertial_speed_, v0);
  }

 private:
  const double *altitude_, *roll_, *pitch_, *radius_, *gm_, *pinned_speed_, *inclination_, *latitude_;
  bool speed_pinned_, rotating_;
  ResultId id_inertial_speed_{};
  ResultId id_altitude_{}, id_tilt_{}, id_roll_{}, id_pitch_{}, id_radius_{}, id_range_{}, id_zenith_{}, id_central_{},
      id_horizon_{}, id_orbit_speed_{}, id_speed_{};
};

}  // namespace

RADCHAIN_PLUGIN(EarthOrbit, {
    .summary = "satellite on a circular orbit over a spherical Earth, looking at (roll, pitch): slant range, view zenith",
    .reference = "Wertz & Larson, Space Mission Analysis and Design 3rd ed. (1999) §5.2; WGS 84 GM and ω_E; Clairaut's relation",
    .schema = schema,
    .publishes = {vocabulary::platform_altitude, vocabulary::platform_tilt, vocabulary::platform_ground_speed,
                  vocabulary::platform_roll, vocabulary::platform_pitch, vocabulary::platform_earth_radius,
                  vocabulary::platform_slant_range, vocabulary::platform_view_zenith_angle},
})

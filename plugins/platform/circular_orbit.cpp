// A satellite on a circular orbit around a spherical, non-rotating Earth. Altitude, line-of-sight tilt and the
// ground-track speed — given (the paper's v_f = 7.9 km/s) or derived: v = √(GM/(R+h)), ground track v·R/(R+h).
#include "radchain/physics/pushbroom.hpp"
#include "radchain/plugin.hpp"

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      quantity("altitude", "m", "400 km").needed().above(0).at_most(1e9).described("orbit altitude h above the surface"),
      quantity("ground_speed", "m/s", "7.9 km/s").above(0)
          .described("pin the ground-track speed (Kolobrodov 1996 uses 7.9 km/s); default: circular orbit"),
      quantity("tilt", "rad", "0 deg").fallback("0 deg").at_least(0).below(1.5707963267948966)
          .described("off-nadir tilt of the line of sight ω (eq. 19)"),
      quantity("earth_radius", "m", "6371 km").fallback("6371 km").above(0).described("mean Earth radius R (IUGG)"),
      quantity("earth_gm", "m3 s-2", "3.986004418e14 m3/s2").fallback("3.986004418e14 m3/s2").above(0)
          .described("geocentric gravitational constant GM (WGS 84)"),
  };
  return s;
}

class CircularOrbit final : public Stage {
 public:
  explicit CircularOrbit(const Params& p)
      : params_(p), altitude_(p.handle("altitude")), tilt_(p.handle("tilt")), radius_(p.handle("earth_radius")),
        gm_(p.handle("earth_gm")), pinned_speed_(p.handle("ground_speed")) {}

  void prepare(Context& c) override {
    speed_pinned_ = params_.has("ground_speed");
    id_altitude_ = c.declare(vocabulary::platform_altitude, "input h", "km");
    id_tilt_ = c.declare(vocabulary::platform_tilt, "input ω", "deg");
    id_orbit_speed_ = c.declare("orbital_speed", "m/s", "√(GM/(R+h)), circular orbit", "km/s");
    id_track_speed_ = c.declare("ground_track_speed", "m/s", "√(GM/(R+h))·R/(R+h), non-rotating Earth", "km/s");
    id_speed_ = c.declare(vocabulary::platform_ground_speed, params_.has("ground_speed") ? "pinned (Kolobrodov 1996 eq. 23: v_f = 7.9 km/s)"
                                                      : "= ground_track_speed",
                          "km/s");
  }

  void evaluate(Context& c) override {
    const double track = physics::ground_track_speed_m_s(*altitude_, *gm_, *radius_);
    c.results.set(id_altitude_, *altitude_);
    c.results.set(id_tilt_, *tilt_);
    c.results.set(id_orbit_speed_, physics::circular_orbit_speed_m_s(*altitude_, *gm_, *radius_));
    c.results.set(id_track_speed_, track);
    c.results.set(id_speed_, speed_pinned_ ? *pinned_speed_ : track);
  }

 private:
  const Params& params_;
  const double *altitude_, *tilt_, *radius_, *gm_, *pinned_speed_;
  bool speed_pinned_ = false;
  ResultId id_altitude_{}, id_tilt_{}, id_orbit_speed_{}, id_track_speed_{}, id_speed_{};
};

}  // namespace

RADCHAIN_PLUGIN(CircularOrbit, {
    .summary = "satellite on a circular orbit: altitude, line-of-sight tilt, ground-track speed",
    .reference = "Kepler circular orbit; WGS 84 GM; Kolobrodov 1996 eq. (23)",
    .schema = schema,
    .publishes = {vocabulary::platform_altitude, vocabulary::platform_tilt, vocabulary::platform_ground_speed},
})

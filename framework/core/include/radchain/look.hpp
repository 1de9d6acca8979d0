#pragma once
// The platform's look as the ground-sampling criteria read it (gsd_requirement, giqe): the altitude, the off-nadir
// roll and pitch (a platform that publishes only a tilt has it taken as a roll), the Earth's radius (default: the
// mean radius), the focal length, and the pixel pitch — the criterion's own `pixel_pitch` key, else the detector's
// detector.pixel_pitch. One reading of the vocabulary for both, so they always see the same geometry.
#include "radchain/physics/pushbroom.hpp"
#include "radchain/plugin.hpp"

#include <optional>
#include <string>

namespace radchain {

struct Look {
  double altitude_m = 0, roll_rad = 0, pitch_rad = 0, earth_radius_m = 0, focal_length_m = 0, pixel_pitch_m = 0;
};

class LookTerms {
 public:
  // In prepare(): the terms this criterion needs (declared in its PluginInfo.needs); without a pixel pitch of its
  // own or the detector's, `params` refuses at `pitch_key_for_error`. A stage that reads the look only in some
  // configurations lists the platform's terms as if_present() and passes `platform_optional`: a missing platform is
  // then refused at `pitch_key_for_error` too.
  void find(Context& c, const Params& params, const std::string& pitch_key_for_error, bool platform_optional = false) {
    if (platform_optional) {
      const auto altitude = c.find(vocabulary::platform_altitude), tilt = c.find(vocabulary::platform_tilt);
      if (!altitude || !tilt) params.reject(pitch_key_for_error, "needs an orbiting platform (its altitude and look)");
      altitude_ = *altitude, tilt_ = *tilt;
    } else {
      altitude_ = c.require(vocabulary::platform_altitude);
      tilt_ = c.require(vocabulary::platform_tilt);
    }
    roll_ = c.find(vocabulary::platform_roll);
    pitch_angle_ = c.find(vocabulary::platform_pitch);
    radius_ = c.find(vocabulary::platform_earth_radius);
    if (platform_optional) {
      const auto focal = c.find(vocabulary::optics_focal_length);
      if (!focal) params.reject(pitch_key_for_error, "needs the optics' focal length");
      focal_ = *focal;
    } else {
      focal_ = c.require(vocabulary::optics_focal_length);
    }
    own_pitch_ = params.has("pixel_pitch") ? params.handle("pixel_pitch") : nullptr;
    detector_pitch_ = own_pitch_ ? std::nullopt : c.find(vocabulary::detector_pixel_pitch);
    if (!own_pitch_ && !detector_pitch_)
      params.reject(pitch_key_for_error,
                    "no pixel pitch: give pixel_pitch here, or use a detector that publishes detector.pixel_pitch");
  }

  // In evaluate(): the look's values (SI).
  Look read(const Results& results) const {
    Look look;
    look.altitude_m = results.value(altitude_);
    look.roll_rad = roll_ ? results.value(*roll_) : results.value(tilt_);
    look.pitch_rad = pitch_angle_ ? results.value(*pitch_angle_) : 0.0;
    look.earth_radius_m = radius_ ? results.value(*radius_) : physics::earth_mean_radius_m;
    look.focal_length_m = results.value(focal_);
    look.pixel_pitch_m = own_pitch_ ? *own_pitch_ : results.value(*detector_pitch_);
    return look;
  }

 private:
  ResultId altitude_{}, tilt_{}, focal_{};
  std::optional<ResultId> roll_, pitch_angle_, radius_, detector_pitch_;
  const double* own_pitch_ = nullptr;
};

}  // namespace radchain

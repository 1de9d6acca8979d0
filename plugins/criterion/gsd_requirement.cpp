// Ground sample distance requirement of an Earth-observation camera, the practitioner's pixel-pitch GSD (not
// Kolobrodov's 1.49-pitch resolution element, which ground_resolution keeps): at nadir GSD = h p / f', and at the
// platform's look (roll, pitch) over a spherical Earth the across- and along-track GSDs (physics/earth_geometry.hpp).
//   margin = GSD_required / GSD − 1   (≥ 0: fine enough; the GSD compared is chosen by `direction`)
// A [[solve]] on optics.focal_length or platform.altitude with this criterion sizes either for the GSD at the look.
// Also reported: swath of the line (pixel_count or the detector's line length), line time for square samples.
#include "radchain/physics/earth_geometry.hpp"
#include "radchain/physics/pushbroom.hpp"
#include "radchain/look.hpp"
#include "radchain/plugin.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      quantity("gsd", "m", "10 m").needed().above(0).described("required ground sample distance"),
      quantity("pixel_pitch", "m", "7.5 um").above(0)
          .described("pixel pitch p (default: the detector's detector.pixel_pitch)"),
      quantity("field_of_view", "rad", "20.6 deg").above(0).below(3.141592653589793)
          .described("full across-track field of view, for the swath (instead of pixel_count or the line length)"),
      number("pixel_count", "2592").above(0)
          .described("pixels across the line, for the swath (default: the detector's line length, if published)"),
      choice("direction", {"geometric_mean", "across_track", "along_track", "worst", "nadir"}).fallback("geometric_mean")
          .described("which GSD must meet the requirement: √(across·along) (GIQE convention), one of them, the larger, or the nadir GSD"),
      quantity("along_track_sampling", "m", "5 m").above(0)
          .described("ground distance between lines when it is not the along-track GSD (an oversampling pushbroom, e.g. SPOT-5 HRS: 5 m lines for 10 m pixels): sets the line time"),
  };
  return s;
}

class GsdRequirement final : public Stage {
 public:
  explicit GsdRequirement(const Params& p)
      : params_(p), required_(p.handle("gsd")), count_(p.handle("pixel_count")), fov_(p.handle("field_of_view")),
        direction_(p.text("direction")) {}

  void prepare(Context& c) override {
    look_.find(c, params_, "gsd");
    speed_ = c.require(vocabulary::platform_ground_speed);
    if (params_.has("pixel_count") && params_.has("field_of_view"))
      params_.reject("field_of_view", "give pixel_count or field_of_view, not both");
    fov_given_ = params_.has("field_of_view");
    line_ = params_.has("pixel_count") || fov_given_ ? std::nullopt : c.find(vocabulary::detector_line_length);
    id_nadir_ = c.declare(vocabulary::criterion_gsd_nadir, "h p / f' (Schowengerdt 2007 §3.3)", "m");
    id_ifov_ = c.declare("ifov", "rad", "p / f'", "urad");
    id_across_ = c.declare(vocabulary::criterion_gsd_across_track, "spherical Earth, neighbouring pixels at roll ± IFOV/2", "m");
    id_along_ = c.declare(vocabulary::criterion_gsd_along_track, "spherical Earth, neighbouring lines at pitch ± IFOV/2", "m");
    id_mean_ = c.declare("gsd_geometric_mean", "m", "√(GSD_across · GSD_along)", "m");
    id_required_ = c.declare("required_gsd", "m", "input", "m");
    id_margin_ = c.declare(vocabulary::criterion_margin, "GSD_required / GSD(" + direction_ + ") − 1");
    id_line_time_ = c.declare("line_time", "s",
                              params_.has("along_track_sampling") ? "along_track_sampling / ground speed"
                                                                  : "GSD_along / ground speed (square samples)",
                              "ms");
    if (params_.has("pixel_count") || fov_given_ || line_) {
      id_field_ = c.declare("angular_field", "rad", fov_given_ ? "input" : "2 atan(N p / 2f')", "deg");
      id_swath_ = c.declare("swath", "m", "great-circle distance between the line's edge pixels at the look", "km");
      id_swath_flat_ = c.declare("swath_flat_nadir", "m", "flat Earth at nadir: N p h / f' (Kolobrodov eq. 18)", "km");
      has_swath_ = true;
    }
  }

  void evaluate(Context& c) override {
    const Look look = look_.read(c.results);  // circular_orbit publishes a tilt only: taken as an across-track roll
    const double h = look.altitude_m, f = look.focal_length_m, p = look.pixel_pitch_m, r = look.earth_radius_m;
    const double roll = look.roll_rad, pitch = look.pitch_rad;
    const double ifov = p / f;
    const double nadir = physics::pixel_pitch_gsd_m(h, p, f);
    const double across = physics::gsd_across_track_m(h, roll, pitch, ifov, r);
    const double along = physics::gsd_along_track_m(h, roll, pitch, ifov, r);
    const double mean = std::sqrt(across * along);
    double compared = mean;
    if (direction_ == "across_track") compared = across;
    else if (direction_ == "along_track") compared = along;
    else if (direction_ == "worst") compared = std::max(across, along);
    else if (direction_ == "nadir") compared = nadir;
    c.results.set(id_nadir_, nadir);
    c.results.set(id_ifov_, ifov);
    c.results.set(id_across_, across);
    c.results.set(id_along_, along);
    c.results.set(id_mean_, mean);
    c.results.set(id_required_, *required_);
    c.results.set(id_margin_, *required_ / compared - 1.0);
    // A pushbroom reads a line each time the ground moves one line spacing: the along-track GSD for square samples,
    // or the given sampling distance for an oversampling camera.
    const double spacing = params_.has("along_track_sampling") ? params_.get("along_track_sampling") : along;
    // Lines farther apart than a pixel's footprint leave gaps along track: the image is undersampled there.
    if (spacing > along * 1.01)
      c.warn(params_.problem("along_track_sampling",
                             fmt::format("lines {:.4g} m apart are coarser than the {:.4g} m along-track GSD: the ground "
                                         "between them is not imaged",
                                         spacing, along)));
    c.results.set(id_line_time_, physics::line_time_s(spacing, c.results.value(speed_)));
    if (has_swath_) {
      const double length = line_ ? c.results.value(*line_) : fov_given_ ? 2 * f * std::tan(*fov_ / 2) : *count_ * p;
      const double half = fov_given_ ? *fov_ / 2 : physics::half_field_angle_rad(length, f);
      c.results.set(id_field_, 2 * half);
      c.results.set(id_swath_, physics::swath_m(h, roll, pitch, half, r));
      c.results.set(id_swath_flat_, physics::ground_extent_m(length, h, f));
    }
  }

 private:
  const Params& params_;
  const double *required_, *count_, *fov_;
  bool fov_given_ = false;
  std::string direction_;
  bool has_swath_ = false;
  LookTerms look_;
  ResultId speed_{};
  std::optional<ResultId> line_;
  ResultId id_nadir_{}, id_ifov_{}, id_across_{}, id_along_{}, id_mean_{}, id_required_{}, id_margin_{},
      id_line_time_{}, id_field_{}, id_swath_{}, id_swath_flat_{};
};

}  // namespace

RADCHAIN_PLUGIN(GsdRequirement, {
    .summary = "pixel-pitch GSD at nadir and at the look (spherical Earth), swath, line time; margin on a required GSD",
    .reference = "Schowengerdt, Remote Sensing 3rd ed. (2007) §3.3; Wertz & Larson, SMAD 3rd ed. (1999) §5.2",
    .schema = schema,
    .publishes = {vocabulary::criterion_gsd_nadir, vocabulary::criterion_gsd_across_track,
                  vocabulary::criterion_gsd_along_track, vocabulary::criterion_margin},
    .needs = {vocabulary::platform_altitude, vocabulary::platform_ground_speed, vocabulary::platform_tilt,
              if_present(vocabulary::platform_roll), if_present(vocabulary::platform_pitch),
              if_present(vocabulary::platform_earth_radius), vocabulary::optics_focal_length,
              if_present(vocabulary::detector_line_length), if_present(vocabulary::detector_pixel_pitch)},
    .inverse = InverseForm::power_law,
})

// The ground resolution requirement of a pushbroom camera (Kolobrodov 1996 eqs. 16-19, 23). The system's
// resolution element V_s (detector, eq. 15) projected from altitude h through f' must not exceed δV:
//   δV = V_s h / f'  (eq. 16),   margin = δV_required / δV − 1   (≥ 0: fine enough)
// A [[solve]] on optics.focal_length with this criterion is eq. (16) solved for f'. Also reported: the field of
// view (17), swath and along-field element (18), growth at the field edge and for the tilted line of sight (19),
// and the along-track sample δy = v t_p of one line period (23) against δV. Beside Kolobrodov's element, the
// pixel-pitch GSD h p / f' (the distance between samples, Schowengerdt 2007 §3.3) when the detector gives its pitch.
#include "radchain/physics/earth_geometry.hpp"
#include "radchain/physics/pushbroom.hpp"
#include "radchain/plugin.hpp"

#include <cmath>

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      quantity("ground_element", "m", "5 m").needed().above(0).described("required ground resolution element δV at nadir"),
  };
  return s;
}

class GroundResolution final : public Stage {
 public:
  explicit GroundResolution(const Params& p) : required_(p.handle("ground_element")) {}

  void prepare(Context& c) override {
    altitude_ = c.require(vocabulary::platform_altitude);
    speed_ = c.require(vocabulary::platform_ground_speed);
    tilt_ = c.require(vocabulary::platform_tilt);
    focal_ = c.require(vocabulary::optics_focal_length);
    element_ = c.require(vocabulary::detector_system_element);
    line_ = c.require(vocabulary::detector_line_length);
    period_ = c.require(vocabulary::detector_integration_time);
    pitch_ = c.find(vocabulary::detector_pixel_pitch);
    id_ground_ = c.declare(vocabulary::criterion_ground_element, "Kolobrodov 1996 eq. (16): δV = V_s h / f'", "m");
    id_required_ = c.declare("required_ground_element", "m", "input δV", "m");
    id_margin_ = c.declare(vocabulary::criterion_margin, "δV_required / δV − 1");
    if (pitch_)
      id_gsd_ = c.declare(vocabulary::criterion_gsd_nadir, "pixel-pitch GSD h p / f' (Schowengerdt 2007 §3.3; not eq. 16's V_s)", "m");
    id_field_ = c.declare("angular_field", "rad", "eq. (17): 2ω = 2 atan(l_D / 2f')", "deg");
    id_field_across_ = c.declare("angular_field_across", "rad", "eq. (17): 2ω_y = 2 atan(V_s / 2f')", "deg");
    id_swath_ = c.declare("swath", "m", "eq. (18): V = l_D h / f'", "km");
    id_width_ = c.declare("along_field_element", "m", "eq. (18): W = V_s h / f'", "m");
    id_edge_in_ = c.declare("edge_element_along_line", "m", "eq. (19) at ω = half field: V_s h / (f' cos²ω)", "m");
    id_edge_cross_ = c.declare("edge_element_across_line", "m", "eq. (19) at ω = half field: V_s h / (f' cos ω)", "m");
    id_tilt_in_ = c.declare("tilted_element_in_plane", "m", "eq. (19) at the platform tilt: V_s h / (f' cos²ω)", "m");
    id_tilt_cross_ = c.declare("tilted_element_cross_plane", "m", "eq. (19) at the platform tilt: V_s h / (f' cos ω)", "m");
    id_along_ = c.declare("along_track_sample", "m", "eq. (23): δy = v t_p (line period = integration time)", "m");
    id_match_ = c.declare("along_to_cross_ratio", "1", "δy / δV (1 = square ground samples)");
    id_period_match_ = c.declare("matching_line_period", "s", "eq. (23) turned round: t_p = δV / v", "ms");
  }

  void evaluate(Context& c) override {
    const double h = c.results.value(altitude_), f = c.results.value(focal_), vs = c.results.value(element_);
    const double ground = physics::ground_extent_m(vs, h, f);
    const double field = physics::full_angular_field_rad(c.results.value(line_), f);
    const double tilt = c.results.value(tilt_);
    const double along = physics::along_track_sample_m(c.results.value(speed_), c.results.value(period_));
    c.results.set(id_ground_, ground);
    c.results.set(id_required_, *required_);
    c.results.set(id_margin_, *required_ / ground - 1.0);
    if (id_gsd_) c.results.set(*id_gsd_, physics::pixel_pitch_gsd_m(h, c.results.value(*pitch_), f));
    c.results.set(id_field_, field);
    c.results.set(id_field_across_, physics::full_angular_field_rad(vs, f));
    c.results.set(id_swath_, physics::ground_extent_m(c.results.value(line_), h, f));
    c.results.set(id_width_, ground);
    c.results.set(id_edge_in_, physics::off_nadir_element_in_plane_m(vs, h, f, field / 2));
    c.results.set(id_edge_cross_, physics::off_nadir_element_cross_plane_m(vs, h, f, field / 2));
    c.results.set(id_tilt_in_, physics::off_nadir_element_in_plane_m(vs, h, f, tilt));
    c.results.set(id_tilt_cross_, physics::off_nadir_element_cross_plane_m(vs, h, f, tilt));
    c.results.set(id_along_, along);
    c.results.set(id_match_, along / ground);
    c.results.set(id_period_match_, physics::line_period_for_along_track_sample_s(ground, c.results.value(speed_)));
  }

 private:
  const double* required_;
  ResultId altitude_{}, speed_{}, tilt_{}, focal_{}, element_{}, line_{}, period_{};
  std::optional<ResultId> pitch_, id_gsd_;
  ResultId id_ground_{}, id_required_{}, id_margin_{}, id_field_{}, id_field_across_{}, id_swath_{}, id_width_{},
      id_edge_in_{}, id_edge_cross_{}, id_tilt_in_{}, id_tilt_cross_{}, id_along_{}, id_match_{}, id_period_match_{};
};

}  // namespace

RADCHAIN_PLUGIN(GroundResolution, {
    .summary = "ground resolution element from altitude, focal length and the system element; field, swath",
    .reference = "Kolobrodov 1996 eqs. (16)-(19), (23)",
    .schema = schema,
    .publishes = {vocabulary::criterion_ground_element, vocabulary::criterion_margin, vocabulary::criterion_gsd_nadir},
    .needs = {vocabulary::platform_altitude, vocabulary::platform_ground_speed, vocabulary::platform_tilt,
              vocabulary::optics_focal_length, vocabulary::detector_system_element, vocabulary::detector_line_length,
              vocabulary::detector_integration_time, if_present(vocabulary::detector_pixel_pitch)},
    .inverse = InverseForm::power_law,
})

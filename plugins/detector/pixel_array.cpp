// The geometry of a detector array with no radiometric model: pixel pitch, pixels across the line (or the
// frame's width), the line or frame time. For geometry-only design files (GSD, swath, MTF budget, NIIRS with a
// given SNR) where a datasheet detector's noise model is not wanted: it publishes the pitch and the line length
// and leaves the radiation alone. An SNR comes from a datasheet detector (emva1288) instead.
#include "radchain/plugin.hpp"

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      quantity("pixel_pitch", "m", "7.5 um").needed().above(0).described("centre-to-centre distance of the pixels"),
      number("pixel_count", "2592").needed().at_least(1).described("pixels across the line (or across the frame)"),
      quantity("integration_time", "s", "1.5 ms").above(0).described("line (or frame) integration time, if known"),
  };
  return s;
}

class PixelArray final : public Stage {
 public:
  bool power_law() const override { return true; }  // pitch, count, time: inputs passed on

  explicit PixelArray(const Params& p)
      : params_(p), pitch_(p.handle("pixel_pitch")), count_(p.handle("pixel_count")), time_(p.handle("integration_time")) {}

  void prepare(Context& c) override {
    // Geometry only: light through optics, or none at all (a file without [source], [atmosphere], [target]).
    const RadiationForm form = c.light.signal.form;
    if (form != RadiationForm::focal_irradiance && form != RadiationForm::focal_power && form != RadiationForm::none)
      c.refuse_form("light through optics (a focal-plane irradiance or a point image)", form);
    id_pitch_ = c.declare(vocabulary::detector_pixel_pitch, "input p", "um");
    id_count_ = c.declare("pixel_count", "1", "input N");
    id_line_ = c.declare(vocabulary::detector_line_length, "l = N p", "mm");
    if (params_.has("integration_time")) id_time_ = c.declare(vocabulary::detector_integration_time, "input", "ms");
  }

  void evaluate(Context& c) override {
    c.results.set(id_pitch_, *pitch_);
    c.results.set(id_count_, *count_);
    c.results.set(id_line_, *pitch_ * *count_);
    if (id_time_) c.results.set(*id_time_, *time_);
  }

 private:
  const Params& params_;
  const double *pitch_, *count_, *time_;
  ResultId id_pitch_{}, id_count_{}, id_line_{};
  std::optional<ResultId> id_time_;
};

}  // namespace

RADCHAIN_PLUGIN(PixelArray, {
    .summary = "geometry of a detector array without radiometry: pixel pitch, pixel count, line length",
    .reference = "(geometry only)",
    .schema = schema,
    .publishes = {vocabulary::detector_pixel_pitch, vocabulary::detector_line_length, vocabulary::detector_integration_time},
})

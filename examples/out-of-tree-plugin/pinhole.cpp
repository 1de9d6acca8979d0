// A minimal optics plugin written outside the radchain tree: a bare circular aperture with no losses.
// It shows the whole contract: a schema, a Stage with prepare/evaluate, and RADCHAIN_PLUGIN at the bottom,
// which lists the shared results it publishes (radchain/vocabulary.hpp). Its name and kind come from the build
// (radchain_add_plugin in CMakeLists.txt).
#include <radchain/plugin.hpp>

#include <numbers>

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      quantity("aperture", "m", "1 mm").needed().above(0).described("hole diameter D"),
  };
  return s;
}

class Pinhole final : public Stage {
 public:
  explicit Pinhole(const Params& p) : aperture_(p.handle("aperture")) {}
  void prepare(Context& c) override {
    if (c.light.signal.form != RadiationForm::pupil_irradiance)
      c.refuse_form("a point irradiance at the pupil", c.light.signal.form);
    c.light.signal.form = RadiationForm::focal_power;
    area_ = c.declare(vocabulary::optics_collecting_area, "π D²/4", "mm2");
  }
  void evaluate(Context& c) override {
    const double area = std::numbers::pi * *aperture_ * *aperture_ / 4.0;
    c.light.signal.scale *= area;
    c.results.set(area_, area);
  }

 private:
  const double* aperture_;
  ResultId area_{};
};

}  // namespace

RADCHAIN_PLUGIN(Pinhole, {
    .summary = "a bare circular hole (out-of-tree example)",
    .reference = "geometry",
    .schema = schema,
    .publishes = {vocabulary::optics_collecting_area},
})

// The brightest pixel must not saturate: a point image whose peak pixel holds more charge than the pixel's
// saturation capacity (EMVA 1288 R4.0 §2.3) is clipped, its photometry and SNR are meaningless and it is not
// "detected at SNR 3539". The margin 1/fill − 1 (the criteria's convention: achieved/required − 1, here
// capacity/charge − 1) is < 0 when saturated; `max_fill` (default 1) may demand head-room, e.g. 0.8 to stay in
// the linear range EMVA 1288 fits (§6.5: up to 70 % of saturation). A [[solve]] on the target's magnitude with
// this criterion gives the brightest unsaturated magnitude.
#include "radchain/plugin.hpp"

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      number("max_fill", "0.8").fallback("1").above(0).at_most(1)
          .described("largest allowed fill of the brightest pixel (charge / saturation capacity)"),
  };
  return s;
}

class Unsaturated final : public LaneStage<Unsaturated> {
  friend class LaneStage<Unsaturated>;  // calls compute()

 public:
  explicit Unsaturated(const Params& p) : max_fill_(p.handle("max_fill")) {}

  void prepare(Context& c) override {
    fill_ = c.require(vocabulary::detector_peak_pixel_fill);
    id_margin_ = c.declare(vocabulary::criterion_margin, "max_fill / fill − 1 (< 0: the brightest pixel saturates)");
    id_fill_ = c.declare("peak_pixel_fill", "1", "the detector's brightest-pixel fill", "%");
    id_saturated_ = c.declare("saturated", "1", "1 if the brightest pixel exceeds max_fill of its saturation capacity");
  }

 private:
  template <class Access>
  void compute(Access& a) {
    using V = typename Access::Value;
    const V fill = a.value(fill_);
    const V margin = a.param(max_fill_) / fill - 1.0;
    a.set(id_margin_, margin);
    if (!a.full_detail()) return;
    a.set(id_fill_, fill);
    a.set(id_saturated_, indicator(margin < -1e-9));
  }

  const double* max_fill_;
  ResultId fill_{}, id_margin_{}, id_fill_{}, id_saturated_{};
};

}  // namespace

RADCHAIN_PLUGIN(Unsaturated, {
    .summary = "the brightest pixel stays below its saturation capacity (margin max_fill/fill − 1)",
    .reference = "EMVA Standard 1288 Release 4.0 §2.3 (saturation capacity)",
    .schema = schema,
    .publishes = {vocabulary::criterion_margin},
    .needs = {vocabulary::detector_peak_pixel_fill},
    .inverse = InverseForm::power_law,
})

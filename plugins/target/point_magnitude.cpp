// A point object of given visual magnitude with the Sun's spectral shape (Pan 2010 eq. 1): its irradiance at
// the pupil is E_t(λ) = 10^{0.4 (m_sun - m)} E_sun(λ), so its illuminance is 10^{0.4 (m_sun - m)} E_s.
// E_sun is the Sun at 1 AU (m_sun = -26.73 is its magnitude there): the source's spectrum per unit
// illumination_scale. The scale itself (the Sun-target distance, a down-path atmosphere) lights objects that
// reflect, not a star of given magnitude, so it is not applied here.
#include "radchain/constants.hpp"
#include "radchain/physics/photometry.hpp"
#include "radchain/plugin.hpp"

#include <cmath>

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      number("magnitude", "15.5").at_least(-30).at_most(40).fallback("15").scales(Scaling::magnitude)
          .described("apparent visual magnitude m (a [[solve]] unknown for the limiting magnitude)"),
  };
  return s;
}

class PointMagnitude final : public LaneStage<PointMagnitude> {
  friend class LaneStage<PointMagnitude>;  // calls compute()

 public:
  explicit PointMagnitude(const Params& p) : magnitude_(p.handle("magnitude")) {}

  void prepare(Context& c) override {
    if (c.light.illumination.empty()) c.refuse_form("a source spectrum", RadiationForm::none);
    c.light.signal.form = RadiationForm::pupil_irradiance;
    c.light.signal.spectrum = c.light.illumination;
    if (!c.light.up_path_transmittance.empty())  // seen through an atmosphere (ground-based viewing)
      c.light.signal.spectrum = c.light.signal.spectrum.product(c.light.up_path_transmittance, c.light.signal.spectrum.unit());
    sun_magnitude_ = c.require(vocabulary::source_visual_magnitude);
    sun_illuminance_ = c.require(vocabulary::source_illuminance);
    sun_distance_ = c.find(vocabulary::source_distance);
    id_illuminance_ = c.declare(vocabulary::target_illuminance, "Pan 2010 eq. (1): E_t = 10^{0.4(m_sun - m)} E_s", "lx");
    id_ratio_ = c.declare("irradiance_ratio", "1", "Pan 2010 eq. (1): E_t / E_s");
  }

  private:
  template <class Access>
  void compute(Access& a) {
    using V = typename Access::Value;
    const V ratio = physics::magnitude_ratio(a.param(magnitude_), a.value(sun_magnitude_));
    a.signal_scale() = ratio * a.up_path_scale();
    a.set(id_ratio_, ratio);
    if (!a.full_detail()) return;  // target.illuminance feeds only the telescope's reported luminous flux
    // source.illuminance is at the source's distance: back to 1 AU.
    V to_1au = broadcast<V>(1.0);
    if (sun_distance_) {
      const V au = a.value(*sun_distance_) / constants::astronomical_unit_m;
      to_1au = au * au;
    }
    a.set(id_illuminance_, ratio * a.value(sun_illuminance_) * to_1au);
  }

  const double* magnitude_;
  ResultId sun_magnitude_{}, sun_illuminance_{}, id_illuminance_{}, id_ratio_{};
  std::optional<ResultId> sun_distance_;
};

}  // namespace

RADCHAIN_PLUGIN(PointMagnitude, {
    .summary = "point object of given visual magnitude with the source's spectral shape",
    .reference = "Pan et al. 2010, Acta Optica Sinica 30(10), eq. (1)",
    .schema = schema,
    .publishes = {vocabulary::target_illuminance},
    .needs = {vocabulary::source_visual_magnitude, vocabulary::source_illuminance,
              if_present(vocabulary::source_distance)},
})

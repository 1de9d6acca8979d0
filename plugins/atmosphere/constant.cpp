// An atmosphere of constant (spectrally flat) transmittance τ_A, crossed by the illumination on its way down
// (ground scenes) and by the target's light on its way up: E_0 = E's τ_A (Kolobrodov 1996, text before eq. 5),
// then E' ∝ τ_A M (eq. 5). Optional path radiance (in-band, spectrally flat over the reporting band).
#include "radchain/plugin.hpp"

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      number("transmittance", "0.5").needed().above(0).at_most(1).described("integral transmittance τ_A of one pass"),
      flag("down_path").fallback("true")
          .described("the source's light crosses the atmosphere before reaching the target (false for objects in space)"),
      quantity("path_radiance", "W m-2 sr-1", "0 W/(m2 sr)").fallback("0 W/(m2 sr)").at_least(0).affects_spectrum()
          .described("in-band path radiance at the sensor, spread flat over the source's reporting band (band_min/band_max); an extended scene's detector adds it to the scene"),
  };
  return s;
}

class ConstantAtmosphere final : public Stage {
 public:
  explicit ConstantAtmosphere(const Params& p) : params_(p), tau_(p.handle("transmittance")) {}

  void prepare(Context& c) override {
    down_ = params_.flag("down_path");
    const double path_radiance = params_.get("path_radiance");
    if (path_radiance > 0) {
      if (!c.light.has_report_band()) params_.reject("path_radiance", "needs the source's band_min/band_max to spread it over");
      const double width = c.light.report_band_max_m - c.light.report_band_min_m;
      Eigen::ArrayXd grid(2), value(2);
      grid << c.light.report_band_min_m, c.light.report_band_max_m;
      value << path_radiance / width, path_radiance / width;
      c.light.path_radiance = Spectrum(grid, value, "W m-2 sr-1 m-1");
    }
    id_tau_ = c.declare("transmittance", "1", "input τ_A (one pass)");
    if (c.light.has_report_band() && down_) {
      band_irradiance_ = c.find(vocabulary::source_band_irradiance);
      if (band_irradiance_) id_ground_ = c.declare(vocabulary::atmosphere_ground_irradiance, "Kolobrodov 1996: E_0 = E's τ_A", "W/cm2");
    }
  }

  void evaluate(Context& c) override {
    if (down_) c.light.illumination_scale *= *tau_;
    c.light.up_path_scale *= *tau_;
    c.results.set(id_tau_, *tau_);
    if (band_irradiance_) c.results.set(id_ground_, c.results.value(*band_irradiance_) * *tau_);
  }

 private:
  const Params& params_;
  const double* tau_;
  bool down_ = true;
  std::optional<ResultId> band_irradiance_;
  ResultId id_tau_{}, id_ground_{};
};

}  // namespace

RADCHAIN_PLUGIN(ConstantAtmosphere, {
    .summary = "spectrally flat atmospheric transmittance τ_A, down and up paths, optional path radiance",
    .reference = "Kolobrodov 1996, text before eq. (5) and eq. (5)",
    .schema = schema,
    .publishes = {vocabulary::atmosphere_ground_irradiance},
    .needs = {if_present(vocabulary::source_band_irradiance)},
})

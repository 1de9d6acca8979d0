// The Sun outside the atmosphere: a tabulated AM0 spectrum (ASTM E-490 by default, Wehrli 1985 selectable)
// or a Planck model, at a given distance. Publishes its total irradiance and its illuminance (computed from
// the spectrum with V(λ), never typed in unless pinned as a paper value).
#include "radchain/constants.hpp"
#include "radchain/physics/photometry.hpp"
#include "radchain/physics/planck.hpp"
#include "radchain/plugin.hpp"

#include <cmath>

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      choice("model", {"table", "planck"}).fallback("table").affects_spectrum()
          .described("tabulated AM0 spectrum, or a blackbody of `temperature` scaled to `total_irradiance`"),
      spectrum_file("table", "W m-2 m-1", "am0_wehrli_1985.csv").fallback("am0_astm_e490_00a.csv")
          .described("AM0 spectral irradiance at 1 AU (ASTM E-490-00a by default)"),
      quantity("temperature", "K", "5778 K").fallback("5778 K").above(0).affects_spectrum()
          .described("blackbody temperature (model = planck)"),
      quantity("total_irradiance", "W m-2", "1361 W/m2").above(0).affects_spectrum()
          .described("rescale the spectrum to this total at 1 AU (required for model = planck)"),
      quantity("distance", "m", "1 AU").fallback("1 AU").above(0).described("Sun-target distance (inverse-square)"),
      spectrum_file("v_lambda", "1", "cie_1924_photopic_V_1nm.csv").fallback("cie_1924_photopic_V_1nm.csv")
          .described("photopic luminous efficiency V(λ) for the illuminance"),
      number("visual_magnitude", "-26.73").fallback("-26.73").at_least(-30).at_most(-20)
          .described("the Sun's apparent visual magnitude at 1 AU (Pan 2010 uses -26.73)"),
      quantity("illuminance", "lx", "1.3e5 lx").above(0).affects_spectrum()
          .described("paper value: pin the solar illuminance at 1 AU (the spectrum is scaled to it)"),
  };
  return s;
}

class Sun final : public Stage {
 public:
  explicit Sun(const Params& p)
      : params_(p), distance_(p.handle("distance")), magnitude_(p.handle("visual_magnitude")) {
    if (p.text("model") == "planck" && !p.has("total_irradiance"))
      p.reject("model", "model = \"planck\" needs total_irradiance, e.g. \"1361 W/m2\"");
  }

  void prepare(Context& c) override {
    Spectrum spectrum;
    if (params_.text("model") == "planck") {
      const double t = params_.get("temperature");
      const int n = 4000;  // log grid 100 nm .. 100 µm
      Eigen::ArrayXd grid = Eigen::ArrayXd::LinSpaced(n, std::log(1e-7), std::log(1e-4)).exp();
      const double scale = params_.get("total_irradiance") / physics::blackbody_exitance(t);
      spectrum = Spectrum::sampled(grid, [&](double l) { return scale * physics::planck_spectral_exitance(l, t); },
                                   "W m-2 m-1");
    } else {
      spectrum = params_.spectrum("table");
      if (params_.has("total_irradiance")) spectrum = spectrum.scaled(params_.get("total_irradiance") / spectrum.integral());
    }
    const Spectrum& v = params_.spectrum("v_lambda");
    const double computed_illuminance = physics::luminous(spectrum, v);
    if (params_.has("illuminance")) spectrum = spectrum.scaled(params_.get("illuminance") / computed_illuminance);
    c.light.illumination = spectrum;

    total_ = spectrum.integral();
    illuminance_ = physics::luminous(spectrum, v);
    id_total_ = c.declare("total_irradiance", "W m-2", "∫ E_λ dλ over the spectrum (solar constant at 1 AU)", "W m-2");
    id_illuminance_ = c.declare("illuminance", "lx", "CIE: E_v = 683 lm/W ∫ V(λ) E_λ dλ, at 1 AU" +
                                std::string(params_.has("illuminance") ? " (pinned paper value)" : ""), "lx");
    if (params_.has("illuminance"))
      id_illuminance_computed_ = c.declare("illuminance_computed", "lx", "683 ∫ V E_λ dλ of the unscaled spectrum", "lx");
    computed_illuminance_ = computed_illuminance;
    id_efficacy_ = c.declare("luminous_efficacy", "lm W-1", "E_v / E_e", "lm W-1");
    id_magnitude_ = c.declare("visual_magnitude", "1", "Pan 2010 eq. (1) reference m_sun");
    id_distance_ = c.declare("distance", "m", "input", "AU");
  }

  void evaluate(Context& c) override {
    const double inverse_square = std::pow(constants::astronomical_unit_m / *distance_, 2);
    c.light.illumination_scale = inverse_square;
    c.results.set(id_total_, total_ * inverse_square);
    c.results.set(id_illuminance_, illuminance_ * inverse_square);
    if (params_.has("illuminance")) c.results.set(id_illuminance_computed_, computed_illuminance_ * inverse_square);
    c.results.set(id_efficacy_, illuminance_ / total_);
    c.results.set(id_magnitude_, *magnitude_);
    c.results.set(id_distance_, *distance_);
  }

 private:
  const Params& params_;
  const double* distance_;
  const double* magnitude_;
  double total_ = 0, illuminance_ = 0, computed_illuminance_ = 0;
  ResultId id_total_{}, id_illuminance_{}, id_illuminance_computed_{}, id_efficacy_{}, id_magnitude_{}, id_distance_{};
};

const PluginInfo& info() {
  static const PluginInfo i{plugin_abi_version, framework_version, Kind::source, "sun",
                            "the Sun outside the atmosphere: AM0 table or Planck model, at a distance",
                            "ASTM E-490-00a; Wehrli 1985; CIE 015 photometry; Planck", &schema,
                            [](const Params& p) -> std::unique_ptr<Stage> { return std::make_unique<Sun>(p); }};
  return i;
}
}  // namespace

RADCHAIN_PLUGIN(info)

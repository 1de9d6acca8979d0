// Any tabulated source spectrum in absolute units (spectral irradiance, W m^-2 m^-1, e.g. a CSV with header
// wavelength_nm,spectral_irradiance_W_m-2_nm-1), optionally rescaled to a total and moved to another
// distance by the inverse-square law. Publishes its total irradiance and illuminance like `sun`.
#include "radchain/physics/photometry.hpp"
#include "radchain/plugin.hpp"

#include <cmath>

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      spectrum_file("table", "W m-2 m-1", "am0_wehrli_1985.csv").needed()
          .described("spectral irradiance at reference_distance, absolute units in the CSV header"),
      quantity("total_irradiance", "W m-2", "1361 W/m2").above(0).affects_spectrum()
          .described("rescale the table to this total ∫ E_λ dλ (at reference_distance)"),
      quantity("reference_distance", "m", "1 AU").above(0)
          .described("distance from the emitter at which the table holds (with distance)"),
      quantity("distance", "m", "1.5 AU").above(0)
          .described("emitter-target distance: the table is scaled by (reference_distance / distance)²"),
      spectrum_file("v_lambda", "1", "cie_1924_photopic_V_1nm.csv").fallback("cie_1924_photopic_V_1nm.csv")
          .described("photopic luminous efficiency V(λ) for the illuminance"),
      number("visual_magnitude", "-26.73").at_least(-30).at_most(40).scales(Scaling::magnitude)
          .described("the source's apparent visual magnitude at reference_distance (for point_magnitude targets)"),
  };
  return s;
}

class Tabulated final : public Stage {
 public:
  explicit Tabulated(const Params& p)
      : params_(p), reference_distance_(p.handle("reference_distance")), distance_(p.handle("distance")),
        magnitude_(p.handle("visual_magnitude")), scaled_by_distance_(p.has("distance")) {
    if (p.has("distance") != p.has("reference_distance"))
      p.reject(p.has("distance") ? "distance" : "reference_distance",
               "distance and reference_distance go together: the table holds at reference_distance");
  }

  void prepare(Context& c) override {
    Spectrum spectrum = params_.spectrum("table");
    if (params_.has("total_irradiance")) spectrum = spectrum.scaled(params_.get("total_irradiance") / spectrum.integral());
    c.light.illumination = spectrum;
    note_table(c.light, params_, "table");
    total_ = spectrum.integral();
    illuminance_ = physics::luminous(spectrum, params_.spectrum("v_lambda"));
    id_total_ = c.declare("total_irradiance", "W m-2", "∫ E_λ dλ over the table", "W m-2");
    id_illuminance_ = c.declare(vocabulary::source_illuminance, "CIE: E_v = 683 lm/W ∫ V(λ) E_λ dλ", "lx");
    id_efficacy_ = c.declare("luminous_efficacy", "lm W-1", "E_v / E_e", "lm W-1");
    if (params_.has("visual_magnitude"))
      id_magnitude_ = c.declare(vocabulary::source_visual_magnitude, "input: reference magnitude for Pan 2010 eq. (1)");
    if (scaled_by_distance_) id_distance_ = c.declare(vocabulary::source_distance, "input", "m");
  }

  void evaluate(Context& c) override {
    const double inverse_square = scaled_by_distance_ ? std::pow(*reference_distance_ / *distance_, 2) : 1.0;
    c.light.illumination_scale = inverse_square;
    c.results.set(id_total_, total_ * inverse_square);
    c.results.set(id_illuminance_, illuminance_ * inverse_square);
    c.results.set(id_efficacy_, illuminance_ / total_);
    if (params_.has("visual_magnitude")) c.results.set(id_magnitude_, *magnitude_);
    if (scaled_by_distance_) c.results.set(id_distance_, *distance_);
  }

 private:
  const Params& params_;
  const double* reference_distance_;
  const double* distance_;
  const double* magnitude_;
  bool scaled_by_distance_;
  double total_ = 0, illuminance_ = 0;
  ResultId id_total_{}, id_illuminance_{}, id_efficacy_{}, id_magnitude_{}, id_distance_{};
};

}  // namespace

RADCHAIN_PLUGIN(Tabulated, {
    .summary = "any tabulated spectral irradiance (absolute units), optionally moved to another distance",
    .reference = "CIE 015 photometry; inverse-square law",
    .schema = schema,
    .publishes = {vocabulary::source_illuminance, vocabulary::source_visual_magnitude, vocabulary::source_distance},
})

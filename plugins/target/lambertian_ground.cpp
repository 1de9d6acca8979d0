// A Lambertian ground background of albedo ρ_b with an object differing by Δρ (Kolobrodov 1996 eqs. 1-4).
// The file says which contrast it means: `contrast_kind = "absolute"` gives Δρ = ρ_t − ρ_b directly (eq. 4 and
// the worked example); "relative" gives Δρ = contrast · ρ_b (eq. 1, (ρ_t − ρ_b)/ρ_b). The paper's "1 % on an
// albedo of 0.3" is relative 0.01, i.e. absolute 3e-3.
// Signal: the radiance difference ΔL_λ = Δρ E_0λ / π (Lambertian, eqs. 2-3), times the up-path transmittance.
// Background: L_bλ = ρ_b E_0λ / π plus any path radiance.
#include "radchain/plugin.hpp"

#include <numbers>

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      number("albedo", "0.3").needed().above(0).at_most(1).described("background reflectance ρ_b (Lambertian)"),
      number("contrast", "0.01").needed().above(0).at_most(1).described("reflectance difference to detect, see contrast_kind"),
      choice("contrast_kind", {"relative", "absolute"}).needed()
          .described("relative: Δρ = contrast·ρ_b (eq. 1); absolute: Δρ = contrast (eq. 4)"),
  };
  return s;
}

class LambertianGround final : public Stage {
 public:
  explicit LambertianGround(const Params& p)
      : albedo_(p.handle("albedo")), contrast_(p.handle("contrast")),
        relative_(p.text("contrast_kind") == "relative") {}

  void prepare(Context& c) override {
    if (c.light.illumination.empty()) c.refuse_form("a source spectrum", RadiationForm::none);
    // Radiance per unit reflectance: E_0λ / π (Lambertian), seen through the up path.
    Spectrum per_reflectance = c.light.illumination.scaled(1.0 / std::numbers::pi, "W m-2 sr-1 m-1");
    if (!c.light.up_path_transmittance.empty())
      per_reflectance = per_reflectance.product(c.light.up_path_transmittance, "W m-2 sr-1 m-1");
    c.light.signal = Radiation{RadiationForm::scene_radiance, per_reflectance, 1.0};
    Spectrum background = per_reflectance;
    c.light.background = Radiation{RadiationForm::scene_radiance, background, 1.0};
    id_delta_rho_ = c.declare(vocabulary::target_reflectance_difference, "Δρ, absolute (Kolobrodov 1996 eq. 4)");
    id_relative_ = c.declare("relative_contrast", "1", "Δρ/ρ_b (Kolobrodov 1996 eq. 1)");
    id_albedo_ = c.declare(vocabulary::target_background_reflectance, "input ρ_b");
    if (c.light.has_report_band()) {
      ground_irradiance_per_scale_ =
          c.light.illumination.integral(c.light.report_band_min_m, c.light.report_band_max_m);
      id_exitance_ = c.declare(vocabulary::target_background_exitance, "M_b = E_0 ρ_b (Kolobrodov 1996 eq. 2)", "W/cm2");
      id_threshold_ = c.declare("threshold_exitance", "W m-2", "ΔM_n = E_0 Δρ (Kolobrodov 1996 eq. 4)", "W/cm2");
    }
  }

  void evaluate(Context& c) override {
    const double delta_rho = relative_ ? *contrast_ * *albedo_ : *contrast_;
    c.light.signal.scale = c.light.illumination_scale * c.light.up_path_scale * delta_rho;
    c.light.background.scale = c.light.illumination_scale * c.light.up_path_scale * *albedo_;
    c.results.set(id_delta_rho_, delta_rho);
    c.results.set(id_relative_, delta_rho / *albedo_);
    c.results.set(id_albedo_, *albedo_);
    if (id_exitance_) {
      // Exitances at the ground (before the up path): M = E_0 ρ.
      const double e0 = ground_irradiance_per_scale_ * c.light.illumination_scale;
      c.results.set(*id_exitance_, e0 * *albedo_);
      c.results.set(*id_threshold_, e0 * delta_rho);
    }
  }

 private:
  const double *albedo_, *contrast_;
  bool relative_;
  double ground_irradiance_per_scale_ = 0;
  ResultId id_delta_rho_{}, id_relative_{}, id_albedo_{};
  std::optional<ResultId> id_exitance_, id_threshold_;
};

}  // namespace

RADCHAIN_PLUGIN(LambertianGround, {
    .summary = "Lambertian ground of albedo ρ_b with an object of reflectance difference Δρ",
    .reference = "Kolobrodov 1996 eqs. (1)-(4)",
    .schema = schema,
    .publishes = {vocabulary::target_reflectance_difference, vocabulary::target_background_exitance,
                  vocabulary::target_background_reflectance},
})

// A Lambertian ground of reflectance ρ lit by the Sun at solar zenith angle θ_s: the radiance that
// reaches the aperture is
//   L_λ = τ↑_λ ρ E_λ cos θ_s τ↓_λ / π  (+ L_path,λ, which the atmosphere adds to the scene background)
// (Schott, Remote Sensing: The Image Chain Approach, 2nd ed. (2007), §4.1 "the big equation", Lambertian
// surface, no adjacency or sky-light term; Schowengerdt 2007 §2.4). E_λ is the source's irradiance at normal
// incidence (τ↓ applied by the atmosphere's down path), so θ_s enters only through cos θ_s here. The signal is
// the whole target radiance (as an SNR at L_ref counts it), the background a ground of `background_reflectance`.
// The path radiance stays in light.path_radiance (it is not ∝ ρ or the sun's scale): reported in
// at_aperture_radiance here, and added to the scene's pixel by the detector (emva1288) through the same étendue.
// Kolobrodov's contrast target stays lambertian_ground.
#include "radchain/physics/solar_position.hpp"
#include "radchain/plugin.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      number("reflectance", "0.3").needed().above(0).at_most(1).described("Lambertian reflectance ρ of the target"),
      quantity("solar_zenith", "rad", "30 deg").fallback("0 deg").at_least(0).below(1.5707963267948966)
          .described("solar zenith angle θ_s at the target (the Sun above the horizon)"),
      quantity("latitude", "rad", "45 deg").at_least(-std::numbers::pi / 2).at_most(std::numbers::pi / 2)
          .described("the target's latitude φ: with local_solar_time and the sun's day_of_year, θ_s from the date"),
      quantity("local_solar_time", "s", "10.5 h").at_least(0).at_most(86400)
          .described("local solar time t of the scene (e.g. a sun-synchronous orbit's 10:30 node: \"10.5 h\")"),
      number("background_reflectance", "0.1").above(0).at_most(1)
          .described("reflectance of the surrounding ground (default: ρ, a uniform scene)"),
  };
  return s;
}

class ReflectanceGround final : public Stage {
 public:
  explicit ReflectanceGround(const Params& p)
      : params_(p), rho_(p.handle("reflectance")), zenith_(p.handle("solar_zenith")),
        background_rho_(p.handle("background_reflectance")), latitude_(p.handle("latitude")),
        solar_time_(p.handle("local_solar_time")), dated_(p.has("latitude") || p.has("local_solar_time")) {
    if (dated_ && !(p.has("latitude") && p.has("local_solar_time")))
      p.reject(p.has("latitude") ? "latitude" : "local_solar_time",
               "the Sun's position needs both latitude and local_solar_time (and the sun's day_of_year)");
    if (dated_ && p.given("solar_zenith"))
      p.reject("solar_zenith", "is computed from latitude, local_solar_time and the day: give one or the other");
  }

  void prepare(Context& c) override {
    if (c.light.illumination.empty()) c.refuse_form("a source spectrum", RadiationForm::none);
    Spectrum per_reflectance = c.light.illumination.scaled(1.0 / std::numbers::pi, "W m-2 sr-1 m-1");
    if (!c.light.up_path_transmittance.empty())
      per_reflectance = per_reflectance.product(c.light.up_path_transmittance, "W m-2 sr-1 m-1");
    c.light.signal = Radiation{RadiationForm::scene_radiance, per_reflectance, 1.0};
    c.light.background = Radiation{RadiationForm::scene_radiance, per_reflectance, 1.0};
    // The Sun's zenith given to the source (once for the chain: the atmosphere's down path uses it too).
    source_zenith_ = c.find(vocabulary::source_solar_zenith);
    if (source_zenith_ && (dated_ || params_.given("solar_zenith")))
      params_.reject(dated_ ? "latitude" : "solar_zenith",
                     "the source gives solar_zenith, which sets the Sun for the whole chain: give the Sun's position once");
    if (dated_) {
      declination_ = c.find(vocabulary::source_solar_declination);
      if (!declination_)
        params_.reject("latitude", "the Sun's position needs the day: give the source (plugin \"sun\") a day_of_year");
      id_zenith_ = c.declare("solar_zenith", "rad",
                             "cos θ_s = sin φ sin δ + cos φ cos δ cos h, h = π (t − 12 h)/12 h (Iqbal 1983 §1.5)", "deg");
    }
    id_cos_ = c.declare("cos_solar_zenith", "1", "cos θ_s");
    id_rho_ = c.declare(vocabulary::target_reflectance, "input ρ (the signal is ∝ ρ: dL/dρ = L/ρ, for NEΔρ)");
    if (c.light.has_report_band()) {
      const double lo = c.light.report_band_min_m, hi = c.light.report_band_max_m;
      per_reflectance_in_band_ = per_reflectance.integral(lo, hi);
      path_in_band_ = c.light.path_radiance.empty() ? 0.0 : c.light.path_radiance.integral(lo, hi);
      id_radiance_ = c.declare("at_aperture_radiance", "W m-2 sr-1",
                               "in the reporting band: τ↑ ρ E cos θ_s τ↓ / π + L_path (Schott 2007 §4.1)", "W/(m2 sr)");
      id_surface_ = c.declare("surface_radiance_at_aperture", "W m-2 sr-1", "τ↑ ρ E cos θ_s τ↓ / π, in band",
                              "W/(m2 sr)");
      id_path_ = c.declare("path_radiance", "W m-2 sr-1", "L_path in band (from the atmosphere)", "W/(m2 sr)");
    }
  }

  void evaluate(Context& c) override {
    double zenith = source_zenith_ ? c.results.value(*source_zenith_) : *zenith_;
    if (dated_) {
      zenith = physics::solar_zenith_rad(*latitude_, c.results.value(*declination_), *solar_time_);
      if (!(zenith < std::numbers::pi / 2))
        throw std::domain_error(fmt::format("the Sun is {:.4g} deg below the horizon at latitude {:.4g} deg, {:.4g} h local solar time",
                                            (zenith - std::numbers::pi / 2) * 180 / std::numbers::pi,
                                            *latitude_ * 180 / std::numbers::pi, *solar_time_ / 3600));
      c.results.set(*id_zenith_, zenith);
    }
    const double mu = std::cos(zenith);
    const double rho_b = params_.has("background_reflectance") ? *background_rho_ : *rho_;
    const double common = c.light.illumination_scale * c.light.up_path_scale * mu;
    c.light.signal.scale = common * *rho_;
    c.light.background.scale = common * rho_b;
    c.results.set(id_cos_, mu);
    c.results.set(id_rho_, *rho_);
    if (id_radiance_) {
      const double surface = per_reflectance_in_band_ * common * *rho_;
      const double path = path_in_band_;  // already at the sensor: the atmosphere states it so
      c.results.set(*id_surface_, surface);
      c.results.set(*id_path_, path);
      c.results.set(*id_radiance_, surface + path);
    }
  }

 private:
  const Params& params_;
  const double *rho_, *zenith_, *background_rho_, *latitude_, *solar_time_;
  bool dated_;
  std::optional<ResultId> declination_, id_zenith_, source_zenith_;
  double per_reflectance_in_band_ = 0, path_in_band_ = 0;
  ResultId id_cos_{}, id_rho_{};
  std::optional<ResultId> id_radiance_, id_surface_, id_path_;
};

}  // namespace

RADCHAIN_PLUGIN(ReflectanceGround, {
    .summary = "Lambertian ground of reflectance ρ under the Sun at zenith angle θ_s: at-aperture radiance",
    .reference = "Schott, Remote Sensing: The Image Chain Approach 2nd ed. (2007) §4.1; Iqbal 1983 §1.5 (sun position)",
    .schema = schema,
    .publishes = {vocabulary::target_reflectance},
    .needs = {if_present(vocabulary::source_solar_declination), if_present(vocabulary::source_solar_zenith)},
})

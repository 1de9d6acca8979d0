// A sensor in space (near the Earth, 1 AU from the Sun): no atmosphere on the line of sight — no extinction, no
// seeing — and a background of zodiacal light plus optional stray light (earthshine, scattered sunlight).
//   zodiacal light   Leinert et al. 1998 (A&AS 127, 1) Table 17: radiance at 500 nm versus helioecliptic longitude
//                    λ − λ⊙ and ecliptic latitude β, bilinear between the nodes (physics/zodiacal.hpp)
//   stray light      a radiance at 500 nm given by the user (e.g. a baffle's earthshine requirement), and/or a
//                    spectral radiance table with its own spectrum (an earthshine or straylight model's output)
//   spectrum         the zodiacal and the 500 nm stray light are scattered sunlight: L_λ = L_500 · E_⊙(λ)/E_⊙(500 nm)
//                    with the solar spectrum (ASTM E-490 by default). Leinert's reddening of the zodiacal light (§8.1:
//                    a few % per 100 nm across the visible) is not applied. The table is added as given.
// All of it is built in the spectral phase (the coordinates and the stray light change the background's spectrum
// once a table with another spectrum is added), so these keys affect the spectrum.
// The background is handed on as a scene radiance (light.background): the optics image it as an extended scene
// and the detector counts it by étendue per pixel, like the site's sky.
#include "radchain/physics/zodiacal.hpp"
#include "radchain/plugin.hpp"
#include "radchain/spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

namespace {
using namespace radchain;

constexpr double deg = std::numbers::pi / 180.0;
constexpr double reference_wavelength_m = 500e-9;  // Leinert's Table 17 wavelength

const Schema& schema() {
  static const Schema s = {
      quantity("zodiacal_longitude", "rad", "90 deg").at_least(0).at_most(2 * std::numbers::pi).affects_spectrum()
          .described("helioecliptic longitude λ − λ⊙ of the line of sight (0-360°; the table is symmetric about 180°)"),
      quantity("zodiacal_latitude", "rad", "30 deg").at_least(-std::numbers::pi / 2).at_most(std::numbers::pi / 2)
          .affects_spectrum().described("ecliptic latitude β of the line of sight"),
      quantity("stray_light", "W m-2 sr-1 m-1", "1e-7 W m-2 sr-1 um-1").at_least(0).affects_spectrum()
          .described("stray light (earthshine, scattered sunlight) as a radiance at 500 nm, solar spectrum; default: none"),
      spectrum_file("stray_light_table", "W m-2 sr-1 m-1", "earthshine_radiance.csv")
          .described("stray light as a spectral radiance table with its own spectrum (e.g. an earthshine model's "
                     "output), added as given within its range (0 beyond it, as a site's sky_table); default: none"),
      spectrum_file("solar_spectrum", "W m-2 m-1", "am0_astm_e490_00a.csv").fallback("am0_astm_e490_00a.csv")
          .described("the Sun's spectral irradiance: the spectrum of the zodiacal light and of `stray_light` (not of a table)"),
  };
  return s;
}

class Space final : public Stage {
 public:
  explicit Space(const Params& p)
      : params_(p), zodiacal_(p.has("zodiacal_longitude")),
        background_(zodiacal_ || p.has("stray_light") || p.has("stray_light_table")) {
    if (p.has("zodiacal_longitude") != p.has("zodiacal_latitude"))
      p.reject(p.has("zodiacal_longitude") ? "zodiacal_longitude" : "zodiacal_latitude",
               "the zodiacal light needs both zodiacal_longitude and zodiacal_latitude");
  }

  void prepare(Context& c) override {
    id_transmittance_ = c.declare("transmittance", "1", "1: no atmosphere on the line of sight");
    if (!background_) return;
    zodiacal_500_ = 0;
    if (zodiacal_) {
      const auto found = physics::leinert_zodiacal_radiance_500nm(params_.get("zodiacal_longitude") / deg,
                                                                 params_.get("zodiacal_latitude") / deg);
      if (!found)
        params_.reject("zodiacal_longitude", "Leinert et al. 1998 Table 17 has no value this close to the Sun "
                                             "(|λ − λ⊙| < 15-30° near the ecliptic)");
      zodiacal_500_ = *found;
    }
    // The solar spectrum's shape at the zodiacal and 500 nm stray radiance (when either is given), plus the table.
    std::optional<Spectrum> sunlit;
    if (zodiacal_ || params_.has("stray_light")) {
      const Spectrum& sun = params_.spectrum("solar_spectrum");
      if (reference_wavelength_m < sun.min_wavelength_m() || reference_wavelength_m > sun.max_wavelength_m())
        params_.reject("solar_spectrum", "the table must cover 500 nm (the zodiacal and stray light are given there)");
      const double at_500 = zodiacal_500_ + (params_.has("stray_light") ? params_.get("stray_light") : 0.0);
      sunlit = sun.scaled(at_500 / sun(reference_wavelength_m), "W m-2 sr-1 m-1");
    }
    table_500_ = 0;
    std::optional<Spectrum> table;
    if (params_.has("stray_light_table")) {
      table = params_.spectrum("stray_light_table").scaled(1.0, "W m-2 sr-1 m-1");
      if (table->value().minCoeff() < 0) params_.reject("stray_light_table", "a stray-light radiance cannot be negative");
      table_500_ = (*table)(reference_wavelength_m);
    }
    Spectrum background = sunlit ? *sunlit : *table;
    if (sunlit && table) {  // on both grids: the sunlit part everywhere, the table within its range (0 beyond, as a sky_table)
      const double lo = std::min(sunlit->min_wavelength_m(), table->min_wavelength_m());
      const double hi = std::max(sunlit->max_wavelength_m(), table->max_wavelength_m());
      const Eigen::ArrayXd grid = union_grid({&*sunlit, &*table}, lo, hi);
      background = Spectrum(grid, (*sunlit)(grid) + (*table)(grid), "W m-2 sr-1 m-1");
    }
    c.light.background = Radiation{RadiationForm::scene_radiance, std::move(background), 1.0};
    id_total_ = c.declare("background_radiance_500nm", "W m-2 sr-1 m-1", "zodiacal + stray light (both forms) at 500 nm",
                          "W m-2 sr-1 um-1");
    if (params_.has("stray_light_table"))
      id_table_ = c.declare("stray_light_table_radiance_500nm", "W m-2 sr-1 m-1", "the stray_light_table at 500 nm",
                            "W m-2 sr-1 um-1");
    if (zodiacal_) {
      id_zodiacal_ = c.declare("zodiacal_radiance_500nm", "W m-2 sr-1 m-1",
                               "Leinert et al. 1998 Table 17 at (λ − λ⊙, β), bilinear", "W m-2 sr-1 um-1");
      id_s10_ = c.declare("zodiacal_s10", "1", "zodiacal radiance / 1.28e-8 W m-2 sr-1 um-1 (S10 units)");
      id_mag_ = c.declare("zodiacal_surface_brightness", "1",
                          "V mag/arcsec² of a solar-type surface: 10 + 2.5 lg(3600²) − 2.5 lg S10");
    }
  }

  void evaluate(Context& c) override {
    c.results.set(id_transmittance_, 1.0);
    if (!background_) return;
    c.light.background.scale = 1.0;
    const double stray = params_.has("stray_light") ? params_.get("stray_light") : 0.0;
    c.results.set(*id_total_, zodiacal_500_ + stray + table_500_);
    if (id_table_) c.results.set(*id_table_, table_500_);
    if (zodiacal_) {
      c.results.set(*id_zodiacal_, zodiacal_500_);
      c.results.set(*id_s10_, zodiacal_500_ / physics::s10_W_m2_sr_m);
      c.results.set(*id_mag_, physics::s10_to_mag_per_arcsec2(zodiacal_500_ / physics::s10_W_m2_sr_m));
    }
  }

 private:
  const Params& params_;
  bool zodiacal_, background_;
  double zodiacal_500_ = 0, table_500_ = 0;  // W m-2 sr-1 m-1 at 500 nm (spectral phase)
  ResultId id_transmittance_{};
  std::optional<ResultId> id_total_, id_table_, id_zodiacal_, id_s10_, id_mag_;
};

}  // namespace

RADCHAIN_PLUGIN(Space, {
    .summary = "space: no extinction, no seeing; zodiacal light (Leinert et al. 1998 Table 17) and stray light "
               "(solar spectrum at a 500 nm radiance, or a spectral radiance table) as the background",
    .reference = "Leinert et al. 1998, A&AS 127, 1, Table 17; ASTM E-490 solar spectrum",
    .schema = schema,
})

// The Sun outside the atmosphere: a tabulated AM0 spectrum (ASTM E-490 by default, Wehrli 1985 selectable)
// or a Planck model, at a given distance. Publishes its total irradiance and its illuminance (computed from
// the spectrum with V(λ), never typed in unless pinned as a paper value). Given a working band λ1..λ2 it also
// publishes z(λ1), z(λ2) (the fraction of the spectrum's total below λ) and the in-band irradiance
// E'_s = E_s [z(λ2) - z(λ1)] (Kolobrodov 1996, after Pavlov 1974), with the printed z as optional overrides.
#include "radchain/constants.hpp"
#include "radchain/physics/band.hpp"
#include "radchain/physics/photometry.hpp"
#include "radchain/physics/planck.hpp"
#include "radchain/physics/pushbroom.hpp"
#include "radchain/physics/solar_position.hpp"
#include "radchain/plugin.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

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
      quantity("solar_zenith", "rad", "40 deg").at_least(0).below(1.5707963267948966).affects_spectrum()
          .described("the Sun's zenith angle θ_s at the scene, given once for the chain: a ground target's cos θ_s "
                     "and an atmosphere table's down-path airmass (Kasten & Young 1989) follow from it"),
      integer("day_of_year", "172").at_least(1).at_most(366)
          .described("the scene's day: sets the distance and publishes the declination (Spencer 1971)"),
      spectrum_file("v_lambda", "1", "cie_1924_photopic_V_1nm.csv").fallback("cie_1924_photopic_V_1nm.csv")
          .described("photopic luminous efficiency V(λ) for the illuminance"),
      number("visual_magnitude", "-26.73").fallback("-26.73").at_least(-30).at_most(-20).scales(Scaling::magnitude)
          .described("the Sun's apparent visual magnitude at 1 AU (Pan 2010 uses -26.73)"),
      quantity("illuminance", "lx", "1.3e5 lx").above(0).affects_spectrum()
          .described("paper value: pin the solar illuminance at 1 AU (the spectrum is scaled to it)"),
      quantity("band_min", "m", "0.5 um").above(0).affects_spectrum()
          .described("working band lower limit λ1: publish z(λ1) and the in-band irradiance (with band_max)"),
      quantity("band_max", "m", "0.76 um").above(0).affects_spectrum()
          .described("working band upper limit λ2 (with band_min)"),
      number("z_band_min", "0.236").at_least(0).at_most(1).affects_spectrum()
          .described("paper value: pin z(λ1), the fraction of the Sun's radiation below λ1 (Kolobrodov 1996: 0.236)"),
      number("z_band_max", "0.58").at_least(0).at_most(1).affects_spectrum()
          .described("paper value: pin z(λ2) (Kolobrodov 1996: 0.58)"),
  };
  return s;
}

class Sun final : public Stage {
 public:
  explicit Sun(const Params& p)
      : params_(p), distance_(p.handle("distance")), magnitude_(p.handle("visual_magnitude")),
        total_irradiance_(p.entry("total_irradiance")), illuminance_pin_(p.entry("illuminance")),
        day_of_year_(p.entry("day_of_year")), band_min_(p.entry("band_min")), solar_zenith_(p.entry("solar_zenith")),
        planck_(p.text("model") == "planck") {
    if (planck_ && !total_irradiance_.present)
      p.reject("model", "model = \"planck\" needs total_irradiance, e.g. \"1361 W/m2\"");
    if (p.has("band_min") != p.has("band_max"))
      p.reject(p.has("band_min") ? "band_min" : "band_max", "band_min and band_max go together (the working band λ1..λ2)");
    if (p.has("band_min") && !(p.get("band_max") > p.get("band_min"))) p.reject("band_max", "must be larger than band_min");
    if (p.has("day_of_year") && p.given("distance"))
      p.reject("day_of_year", "sets the Earth-Sun distance: give it or distance, not both");
    if ((p.has("z_band_min") || p.has("z_band_max")) && !p.has("band_min"))
      p.reject(p.has("z_band_min") ? "z_band_min" : "z_band_max", "a pinned z needs the working band (band_min, band_max)");
  }

  // (Presence is read at each spectral phase, from entries kept at construction: a sweep may give a key the file
  // left out.)
  void prepare(Context& c) override {
    Spectrum spectrum;
    if (planck_) {
      const double t = params_.get("temperature");
      spectrum = physics::blackbody_exitance_spectrum(t).scaled(total_irradiance_.number / physics::blackbody_exitance(t));
    } else {
      spectrum = params_.spectrum("table");
      if (total_irradiance_.present) spectrum = spectrum.scaled(total_irradiance_.number / spectrum.integral());
    }
    const Spectrum& v = params_.spectrum("v_lambda");
    const double computed_illuminance = physics::luminous(spectrum, v);
    const bool pinned = illuminance_pin_.present;
    illuminance_ = computed_illuminance;
    if (pinned) {
      spectrum = spectrum.scaled(illuminance_pin_.number / computed_illuminance);
      illuminance_ = physics::luminous(spectrum, v);  // the pinned value, up to rounding
    }
    c.light.illumination = spectrum;
    if (planck_) note_table(c.light, spectrum, "model = \"planck\" of " + params_.context() + " (its sampled grid)");
    else note_table(c.light, params_, "table");
    total_ = spectrum.integral();
    id_total_ = c.declare("total_irradiance", "W m-2", "∫ E_λ dλ over the spectrum (solar constant at 1 AU)", "W m-2");
    id_illuminance_ = c.declare(vocabulary::source_illuminance,
                                pinned ? "CIE: E_v = 683 lm/W ∫ V(λ) E_λ dλ, at 1 AU (pinned paper value)"
                                       : "CIE: E_v = 683 lm/W ∫ V(λ) E_λ dλ, at 1 AU",
                                "lx");
    if (pinned)
      id_illuminance_computed_ = c.declare("illuminance_computed", "lx", "683 ∫ V E_λ dλ of the unscaled spectrum", "lx");
    computed_illuminance_ = computed_illuminance;
    id_efficacy_ = c.declare("luminous_efficacy", "lm W-1", "E_v / E_e", "lm W-1");
    id_magnitude_ = c.declare(vocabulary::source_visual_magnitude, "Pan 2010 eq. (1) reference m_sun");
    dated_ = day_of_year_.present;
    id_distance_ = c.declare(vocabulary::source_distance,
                             dated_ ? "r = 1 AU ((r₀/r)²)^(−½) on day d (Spencer 1971)" : "input", "AU");
    if (dated_)
      id_declination_ = c.declare(vocabulary::source_solar_declination,
                                  "δ(d) = 0.006918 − 0.399912 cos Γ + … (Spencer 1971, Γ = 2π(d−1)/365)", "deg");
    has_band_ = band_min_.present;
    if (has_band_) prepare_band(c, spectrum);
    if (solar_zenith_.present) {
      id_zenith_ = c.declare(vocabulary::source_solar_zenith, "input θ_s", "deg");
      c.set_in_spectral_phase(*id_zenith_, solar_zenith_.number);  // an atmosphere's spectral phase reads it next
    }
  }

  // With pinned z values the spectrum is rescaled inside the band so that every later stage integrating over
  // it sees E'_s = E_s [z(λ2) - z(λ1)] (the paper's number), while its shape is kept.
  static Spectrum with_band_total(const Spectrum& spectrum, double lo, double hi, double band_total) {
    // The band limits become grid nodes first (this leaves the piecewise-linear function unchanged), so scaling
    // every node in [lo, hi] scales the in-band integral exactly.
    const Eigen::ArrayXd grid = union_grid({&spectrum}, spectrum.min_wavelength_m(), spectrum.max_wavelength_m());
    std::vector<double> nodes(grid.data(), grid.data() + grid.size());
    for (double limit : {lo, hi})
      if (std::find(nodes.begin(), nodes.end(), limit) == nodes.end()) nodes.push_back(limit);
    std::sort(nodes.begin(), nodes.end());
    const Eigen::ArrayXd refined = Eigen::Map<Eigen::ArrayXd>(nodes.data(), static_cast<Eigen::Index>(nodes.size()));
    const double factor = band_total / spectrum.integral(lo, hi);
    return Spectrum::sampled(refined, [&](double l) { return spectrum(l) * (l >= lo && l <= hi ? factor : 1.0); },
                             spectrum.unit(), spectrum.extrapolation());
  }

  // Kolobrodov 1996 (after Pavlov 1974): E'_s = E_s [z(λ2) - z(λ1)], z(λ) the fraction of the Sun's total
  // radiation below λ, computed from the spectrum unless pinned to a printed value.
  void prepare_band(Context& c, const Spectrum& spectrum) {
    const double lo = params_.get("band_min"), hi = params_.get("band_max");
    z_computed_[0] = physics::fraction_below(spectrum, lo);
    z_computed_[1] = physics::fraction_below(spectrum, hi);
    const char* keys[2] = {"z_band_min", "z_band_max"};
    for (int i = 0; i < 2; ++i) {
      const bool pinned = pinned_z_[i] = params_.has(keys[i]);
      z_[i] = pinned ? params_.get(keys[i]) : z_computed_[i];
      id_z_[i] = c.declare(keys[i], "1", std::string(i == 0 ? "z(λ1)" : "z(λ2)") +
                                             (pinned ? " (pinned paper value)" : " = ∫_0^λ E_λ dλ / ∫ E_λ dλ"));
      if (pinned)
        id_z_computed_[i] = c.declare(std::string(keys[i]) + "_computed", "1", "∫_0^λ E_λ dλ / ∫ E_λ dλ of the spectrum");
    }
    id_band_ = c.declare(vocabulary::source_band_irradiance, "Kolobrodov 1996: E'_s = E_s [z(λ2) - z(λ1)]", "W/cm2");
    c.light.report_band_min_m = lo;
    c.light.report_band_max_m = hi;
    if (pinned_z_[0] || pinned_z_[1])
      c.light.illumination =
          with_band_total(c.light.illumination, lo, hi, physics::band_solar_irradiance_W_m2(total_, z_[0], z_[1]));
  }

  void evaluate(Context& c) override {
    const double day = dated_ ? day_of_year_.number : 0.0;
    const double distance = dated_ ? physics::earth_sun_distance_au(day) * constants::astronomical_unit_m : *distance_;
    const double au_over_d = constants::astronomical_unit_m / distance;
    const double inverse_square = au_over_d * au_over_d;
    c.light.illumination_scale = inverse_square;
    c.results.set(id_total_, total_ * inverse_square);
    c.results.set(id_illuminance_, illuminance_ * inverse_square);
    if (id_illuminance_computed_) c.results.set(*id_illuminance_computed_, computed_illuminance_ * inverse_square);
    c.results.set(id_efficacy_, illuminance_ / total_);
    c.results.set(id_magnitude_, *magnitude_);
    c.results.set(id_distance_, distance);
    if (id_declination_) c.results.set(*id_declination_, physics::solar_declination_rad(day));
    if (id_zenith_) c.results.set(*id_zenith_, solar_zenith_.number);
    if (has_band_) {
      for (int i = 0; i < 2; ++i) {
        c.results.set(id_z_[i], z_[i]);
        if (pinned_z_[i]) c.results.set(id_z_computed_[i], z_computed_[i]);
      }
      c.results.set(id_band_, physics::band_solar_irradiance_W_m2(total_ * inverse_square, z_[0], z_[1]));
    }
  }

 private:
  const Params& params_;
  const double* distance_;
  const double* magnitude_;
  const Params::Entry &total_irradiance_, &illuminance_pin_, &day_of_year_, &band_min_, &solar_zenith_;
  const bool planck_;
  std::optional<ResultId> id_illuminance_computed_;  // only when the illuminance is pinned
  double total_ = 0, illuminance_ = 0, computed_illuminance_ = 0;
  ResultId id_total_{}, id_illuminance_{}, id_efficacy_{}, id_magnitude_{}, id_distance_{};
  std::optional<ResultId> id_declination_, id_zenith_;
  bool dated_ = false;
  bool has_band_ = false, pinned_z_[2] = {false, false};
  double z_[2] = {0, 0}, z_computed_[2] = {0, 0};
  ResultId id_z_[2]{}, id_z_computed_[2]{}, id_band_{};
};

}  // namespace

RADCHAIN_PLUGIN(Sun, {
    .summary = "the Sun outside the atmosphere: AM0 table or Planck model, at a distance",
    .reference = "ASTM E-490-00a; Wehrli 1985; CIE 015 photometry; Planck; Spencer 1971 (day of year)",
    .schema = schema,
    .publishes = {vocabulary::source_illuminance, vocabulary::source_visual_magnitude, vocabulary::source_distance,
                  vocabulary::source_band_irradiance, vocabulary::source_solar_declination, vocabulary::source_solar_zenith},
})

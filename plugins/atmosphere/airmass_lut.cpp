// An atmosphere given as a look-up table over airmass: τ(λ) from a radiative-transfer code at several airmasses
// X₁ < X₂ < … (one table per node, e.g. the MODTRAN runs of lsst/throughputs atmos/atmos_XX_aerosol.dat), and
// optionally the path radiance L_path,λ at the same nodes. Between two nodes the transmittance is interpolated
// geometrically, τ = τ_i^(1−w) τ_{i+1}^w with w = (X − X_i)/(X_{i+1} − X_i), i.e. ln τ linear in X: exact where
// the Bouguer-Lambert-Beer law holds (ln τ = −X κ), and closer than Beer's τ₁^X where it does not (saturated
// molecular bands, multiple scattering: the reason RT codes are run per airmass). The path radiance is
// interpolated linearly. No extrapolation: an airmass outside the nodes is refused.
// Two paths, two airmasses: the line of sight (`airmass`: the up path, and the path radiance seen along it), or
// derived from an earth_orbit platform's view zenith η at the ground point, and, optionally, the Sun's path to the
// ground (`sun_airmass`, the down path), or derived from the source's `solar_zenith` θ_s; both derivations by
// Kasten & Young 1989 held at 1 near the zenith (physics/solar_position.hpp: relative_airmass). The platform and
// the source set those angles in their spectral phases (Context::set_in_spectral_phase), so in such a chain a
// change of roll or pitch re-runs the spectral phase from the platform (chain.hpp). An Earth scene under a low
// Sun seen at nadir crosses the atmosphere at X_s ≠ X_v
// (L = τ(X_v) ρ E cos θ_s τ(X_s)/π + L_path(X_v); Schott 2007 §4.1). The path radiance tables are then runs at the
// scene's sun angle, one per view airmass.
#include "radchain/curve_components.hpp"
#include "radchain/error.hpp"
#include "radchain/physics/solar_position.hpp"
#include "radchain/plugin.hpp"
#include "radchain/spectrum_csv.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <utility>

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      spectrum_file("tables", "1", "lsst_atmos_aerosol_X10_throughputs1.9.csv").as_list().needed()
          .described("transmittance τ(λ) at each node airmass (one table per entry of `airmasses`, same order)"),
      number("airmasses", "1.0").as_list().needed().at_least(1)
          .described("the node airmasses of the tables, increasing (e.g. [1.0, 1.5, 2.0, 2.5])"),
      number("airmass", "1.3").at_least(1).affects_spectrum()
          .described("the line of sight's airmass X, within the nodes (interpolated, never extrapolated); needed unless "
                     "the platform has a view (earth_orbit), which sets it from its view zenith (Kasten & Young 1989)"),
      number("sun_airmass", "2.0").at_least(1).affects_spectrum()
          .described("the Sun's path to the ground (down path), within the nodes; default: from the source's solar_zenith "
                     "(Kasten & Young 1989) when it has one, else the line of sight's"),
      spectrum_file("path_radiance_tables", "W m-2 sr-1 m-1", "path_radiance_X10.csv").as_list()
          .described("path radiance at the sensor at each node (optional; same count and order as the tables)"),
      flag("down_path").fallback("true")
          .described("the source's light crosses the atmosphere before reaching the target (false for objects in space)"),
  };
  return s;
}

class AirmassLut final : public Stage {
 public:
  explicit AirmassLut(const Params& p) : params_(p) {
    const std::vector<std::string>& tables = p.entry("tables").texts;
    const std::vector<double>& nodes = p.entry("airmasses").numbers;
    if (tables.size() < 2) p.reject("tables", "a look-up table needs at least two nodes");
    if (nodes.size() != tables.size())
      p.reject("airmasses", fmt::format("{} airmasses for {} tables: give one per table", nodes.size(), tables.size()));
    for (std::size_t i = 1; i < nodes.size(); ++i)
      if (!(nodes[i] > nodes[i - 1])) p.reject("airmasses", "the node airmasses must increase");
    if (p.has("path_radiance_tables") && p.entry("path_radiance_tables").texts.size() != tables.size())
      p.reject("path_radiance_tables", "give one path radiance table per transmittance table");
    for (const char* key : {"airmass", "sun_airmass"}) {
      if (!p.has(key)) continue;
      const double x = p.get(key);
      if (x < nodes.front() || x > nodes.back())
        p.reject(key, fmt::format("{:g} is outside the table's nodes [{:g}, {:g}] (no extrapolation)", x, nodes.front(), nodes.back()));
    }
    if (p.has("sun_airmass") && !p.flag("down_path"))
      p.reject("sun_airmass", "down_path = false: the source's light does not cross this atmosphere");
  }

  // The node interval [X_i, X_(i+1)] of an airmass and the weight w in it.
  std::pair<std::size_t, double> bracket(double x) const {
    const std::vector<double>& nodes = params_.entry("airmasses").numbers;
    std::size_t i = 0;
    while (i + 2 < nodes.size() && x > nodes[i + 1]) ++i;
    return {i, (x - nodes[i]) / (nodes[i + 1] - nodes[i])};
  }

  // τ(λ) at airmass x: τ_i^(1−w) τ_(i+1)^w on the lower node's grid (the tables of one RT run share theirs).
  Spectrum transmittance_at(double x) const {
    const std::vector<std::string>& tables = params_.entry("tables").texts;
    const auto [i, w] = bracket(x);
    const Spectrum& below = cached_spectrum_csv(tables[i], "1").spectrum;
    const Spectrum& above = cached_spectrum_csv(tables[i + 1], "1").spectrum;
    const Eigen::ArrayXd& grid = below.wavelength_m();
    const Eigen::ArrayXd tau_below = below.value().max(0.0), tau_above = above(grid).max(0.0);
    const Eigen::ArrayXd tau = (tau_below > 0 && tau_above > 0).select(tau_below.pow(1 - w) * tau_above.pow(w), 0.0);
    return Spectrum(grid, tau, "1", Extrapolation::zero);
  }

  // An airmass derived from an angle (the platform's view zenith, the source's solar zenith): within the nodes.
  void check_derived(double x, double angle_rad, const char* what, const char* result) const {
    const std::vector<double>& nodes = params_.entry("airmasses").numbers;
    if (x < nodes.front() || x > nodes.back())
      params_.reject("airmasses", fmt::format("{} at {:.4g}° ({}) crosses {:.4g} airmasses (Kasten & Young 1989), "
                                              "outside the tables' nodes [{:g}, {:g}]: add a table at that airmass (no "
                                              "extrapolation)",
                                              what, angle_rad * 180 / std::numbers::pi, result, x, nodes.front(), nodes.back()));
  }

  void prepare(Context& c) override {
    const std::vector<double>& nodes = params_.entry("airmasses").numbers;
    // The line of sight's airmass: given, or from the platform's view zenith η (set in its spectral phase).
    const std::optional<ResultId> view = c.find(vocabulary::platform_view_zenith_angle);
    std::string view_equation = "input X (between the LUT's nodes)";
    if (view) {
      if (params_.has("airmass"))
        params_.reject("airmass", "the platform gives the line of sight's view zenith (platform.view_zenith_angle), "
                                  "which sets its airmass: give one of them (a platform without a view, circular_orbit, "
                                  "takes the airmass by hand)");
      const double eta = c.read_in_spectral_phase(*view);
      view_airmass_ = physics::relative_airmass(eta);
      view_equation = "X = max(1, 1/(cos η + 0.50572 (96.07995° − η)^−1.6364)), η the platform's view zenith "
                      "(Kasten & Young 1989)";
      check_derived(view_airmass_, eta, "the line of sight", "platform.view_zenith_angle");
    } else if (params_.has("airmass")) {
      view_airmass_ = params_.get("airmass");
    } else {
      throw InputError({}, params_.context(), "airmass",
                       "missing required key: the line of sight's airmass, e.g. 1.3 (a platform with a view, "
                       "earth_orbit, sets it from its view zenith instead)");
    }
    const double x = view_airmass_;
    const auto [i, w] = bracket(x);
    const Spectrum path = transmittance_at(x);
    note_table(c.light, path, "tables of " + params_.context());
    const double lo = c.light.has_report_band() ? c.light.report_band_min_m : 400e-9;
    const double hi = c.light.has_report_band() ? c.light.report_band_max_m : 700e-9;
    if (params_.flag("down_path")) {
      // The down path's airmass: given, or from the source's θ_s (set in its spectral phase), or the line of sight's.
      const std::optional<ResultId> zenith = c.find(vocabulary::source_solar_zenith);
      std::string equation = "input X_s";
      sun_airmass_ = x;
      if (params_.has("sun_airmass")) {
        if (zenith)
          params_.reject("sun_airmass", "the source gives solar_zenith, which sets the Sun's airmass: give one of them");
        sun_airmass_ = params_.get("sun_airmass");
      } else if (zenith) {
        const double theta = c.read_in_spectral_phase(*zenith);
        sun_airmass_ = physics::relative_airmass(theta);
        equation = "X_s = max(1, 1/(cos θ_s + 0.50572 (96.07995° − θ_s)^−1.6364)), θ_s the source's (Kasten & Young 1989)";
        check_derived(sun_airmass_, theta, "the Sun", "source.solar_zenith");
      } else {
        equation = "X_s = X (no sun_airmass given)";
      }
      const Spectrum sun_path = sun_airmass_ == x ? path : transmittance_at(sun_airmass_);
      c.light.illumination = c.light.illumination.product(sun_path, c.light.illumination.unit());
      sun_tau_ = sun_path.integral(lo, hi) / (hi - lo);
      id_sun_tau_ = c.declare("sun_transmittance", "1", "band mean of τ at the Sun's airmass (the down path)");
      id_sun_airmass_ = c.declare("sun_airmass", "1", equation);
    }
    c.light.up_path_transmittance =
        c.light.up_path_transmittance.empty() ? path : c.light.up_path_transmittance.product(path, "1");
    mean_tau_ = path.integral(lo, hi) / (hi - lo);
    id_tau_ = c.declare("transmittance", "1", "band mean of τ_i^(1−w) τ_{i+1}^w along the line of sight over the reporting band (or 400-700 nm)");
    id_airmass_ = c.declare(vocabulary::atmosphere_airmass, view_equation);
    id_weight_ = c.declare("lut_weight", "1", fmt::format("w = (X − X_i)/(X_(i+1) − X_i) between the nodes {:g} and {:g}",
                                                          nodes[i], nodes[i + 1]));
    if (params_.has("path_radiance_tables")) {
      // Along the line of sight: the tables' node airmasses are view airmasses.
      const std::vector<std::string>& paths = params_.entry("path_radiance_tables").texts;
      const Spectrum& l_below = cached_spectrum_csv(paths[i], "W m-2 sr-1 m-1").spectrum;
      const Spectrum& l_above = cached_spectrum_csv(paths[i + 1], "W m-2 sr-1 m-1").spectrum;
      const Eigen::ArrayXd& l_grid = l_below.wavelength_m();
      c.light.path_radiance = Spectrum(l_grid, (1 - w) * l_below.value() + w * l_above(l_grid), "W m-2 sr-1 m-1");
      path_in_band_ = c.light.path_radiance.integral(lo, hi);
      id_path_ = c.declare("path_radiance", "W m-2 sr-1", "∫ L_path,λ dλ over the reporting band (or 400-700 nm)", "W/(m2 sr)");
    }
    weight_ = w;
  }

  void evaluate(Context& c) override {
    c.results.set(id_tau_, mean_tau_);
    c.results.set(id_airmass_, view_airmass_);
    c.results.set(id_weight_, weight_);
    if (id_path_) c.results.set(*id_path_, path_in_band_);
    if (id_sun_tau_) {
      c.results.set(*id_sun_tau_, sun_tau_);
      c.results.set(*id_sun_airmass_, sun_airmass_);
    }
  }

 private:
  const Params& params_;
  double mean_tau_ = 1, path_in_band_ = 0, weight_ = 0, sun_tau_ = 1, sun_airmass_ = 1, view_airmass_ = 1;
  ResultId id_tau_{}, id_airmass_{}, id_weight_{};
  std::optional<ResultId> id_path_, id_sun_tau_, id_sun_airmass_;
};

}  // namespace

RADCHAIN_PLUGIN(AirmassLut, {
    .summary = "atmosphere as an RT look-up table over airmass: τ(λ) (and path radiance) per node, interpolated",
    .reference = "Bouguer-Lambert-Beer law (ln τ linear in X between nodes); tables e.g. MODTRAN (lsst/throughputs atmos/); "
                 "Kasten & Young 1989 (the Sun's and the line of sight's airmass from their zenith angles)",
    .schema = schema,
    .publishes = {vocabulary::atmosphere_airmass},
    .needs = {if_present(vocabulary::source_solar_zenith), if_present(vocabulary::platform_view_zenith_angle)},
})

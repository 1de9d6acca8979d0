// An atmosphere given as a spectral transmittance table τ(λ) for one vertical pass (e.g. MODTRAN), scaled to an
// airmass X by Bouguer-Lambert-Beer: τ_X(λ) = τ(λ)^X. Crossed on the way down (unless down_path = false) and up.
// Optionally the path radiance L_path,λ at the sensor as a table (as an RT code — libRadtran, 6S, MODTRAN — writes
// it for one geometry): it joins the scene's radiance, L = τ↑ ρ E cos θ_s τ↓/π + L_path (Schott 2007 §4.1), and is
// used as given — it is the RT run's, for its own sun, view and atmosphere, and is not rescaled with `airmass`.
// (Named tabulated_transmittance, not tabulated: plugin names are global — CMake targets and .so files.)
#include "radchain/plugin.hpp"

#include <cmath>

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      spectrum_file("table", "1", "atmosphere_modtran_cerro_pachon_airmass1.0.csv")
          .fallback("atmosphere_modtran_cerro_pachon_airmass1.0.csv").described("transmittance τ(λ) of one vertical pass"),
      number("airmass", "1").fallback("1").at_least(1).at_most(40).affects_spectrum()
          .described("relative air mass X of each pass (τ^X, Bouguer-Lambert-Beer)"),
      flag("down_path").fallback("true")
          .described("the source's light crosses the atmosphere before reaching the target (false for objects in space)"),
      spectrum_file("path_radiance", "W m-2 sr-1 m-1", "path_radiance_libradtran.csv")
          .described("path radiance at the sensor, a table from an RT code for this geometry (W m-2 sr-1 nm-1 or per m)"),
  };
  return s;
}

class TabulatedTransmittance final : public Stage {
 public:
  explicit TabulatedTransmittance(const Params& p) : params_(p) {}

  void prepare(Context& c) override {
    const Spectrum& table = params_.spectrum("table");
    const double x = params_.get("airmass");
    Eigen::ArrayXd tau = table.value().max(0.0).pow(x);
    const Spectrum path(table.wavelength_m(), tau, "1", Extrapolation::zero);
    if (params_.flag("down_path")) c.light.illumination = c.light.illumination.product(path, c.light.illumination.unit());
    note_table(c.light, params_, "table");
    c.light.up_path_transmittance =
        c.light.up_path_transmittance.empty() ? path : c.light.up_path_transmittance.product(path, "1");
    id_tau_ = c.declare("transmittance", "1", "band mean of τ(λ)^X over the reporting band (or 400-700 nm)");
    const double lo = c.light.has_report_band() ? c.light.report_band_min_m : 400e-9;
    const double hi = c.light.has_report_band() ? c.light.report_band_max_m : 700e-9;
    mean_tau_ = path.integral(lo, hi) / (hi - lo);
    if (params_.has("path_radiance")) {
      c.light.path_radiance = params_.spectrum("path_radiance");
      id_path_ = c.declare("path_radiance", "W m-2 sr-1", "∫ L_path,λ dλ over the reporting band (or 400-700 nm)", "W/(m2 sr)");
      path_in_band_ = c.light.path_radiance.integral(lo, hi);
    }
  }

  void evaluate(Context& c) override {
    c.results.set(id_tau_, mean_tau_);
    if (id_path_) c.results.set(*id_path_, path_in_band_);
  }

 private:
  const Params& params_;
  double mean_tau_ = 1, path_in_band_ = 0;
  ResultId id_tau_{};
  std::optional<ResultId> id_path_;
};

}  // namespace

RADCHAIN_PLUGIN(TabulatedTransmittance, {
    .summary = "spectral atmospheric transmittance table, airmass-scaled, down and up paths; optional path radiance table",
    .reference = "Bouguer-Lambert-Beer law; table provenance in spectra/",
    .schema = schema,
})

// A point source (star, unresolved satellite) of given magnitude in a named bandpass and magnitude system
// (Vega, AB or ST), with a spectral energy distribution independent of the band that normalises it.
//   SED   `sed` (a spectral irradiance table, any normalisation), or `sed_shape`: the source's spectrum (the Sun
//         for a sunlit object or a solar-type star), flat in f_ν (survey depths m5 are quoted for it), flat in f_λ
//   m     = −2.5 lg(∫ f_λ T λ dλ / ∫ f_λ,ref T λ dλ) + m_ref   (photon counting; Bessell & Murphy 2012 eq. A1;
//         physics/magnitudes.hpp), so f_λ = 10^{-0.4 (m − m_ref)} N₀ · SED / ∫ SED T λ/(hc) dλ
//   N₀    = ∫ f_λ,ref T λ/(hc) dλ, photons s⁻¹ m⁻² of magnitude 0 (published: target.zero_point_photon_rate)
// The magnitude is above the atmosphere: an atmosphere before this stage dims it by its up path (τ(λ)^X and
// its scalar, e.g. the extinction k·X of the `site` atmosphere).
#include "radchain/physics/magnitudes.hpp"
#include "radchain/physics/photometry.hpp"
#include "radchain/plugin.hpp"

#include <cmath>

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      number("magnitude", "18").needed().at_least(-30).at_most(40).scales(Scaling::magnitude)
          .described("apparent magnitude in `band` and `system` (a [[solve]] unknown for a limiting magnitude)"),
      choice("system", {"vega", "ab", "st"}).needed().affects_spectrum()
          .described("magnitude system: vega (α Lyr = reference_magnitude), ab (3631 Jy), st (3.63e-9 erg/s/cm²/Å)"),
      spectrum_file("band", "1", "johnson_cousins_V_bessell1990.csv").needed()
          .described("bandpass T(λ) that defines the magnitude (table in spectra/)"),
      spectrum_file("sed", "W m-2 m-1", "vega_alpha_lyr_stis_002.csv")
          .described("spectral energy distribution of the source (shape only); default: sed_shape"),
      choice("sed_shape", {"source", "flat_f_nu", "flat_f_lambda"}).fallback("source").affects_spectrum()
          .described("SED without a table: the source's spectrum, flat in f_ν (the survey depth convention), or flat in f_λ"),
      spectrum_file("vega_spectrum", "W m-2 m-1", "vega_alpha_lyr_stis_002.csv")
          .fallback("vega_alpha_lyr_stis_002.csv").described("the Vega spectrum of the vega system"),
      number("reference_magnitude", "0.03").fallback("0").at_least(-1).at_most(1).affects_spectrum()
          .described("Vega's own magnitude in the band (vega system; 0 defines the pure Vega system)"),
  };
  return s;
}

class PointSource final : public LaneStage<PointSource> {
  friend class LaneStage<PointSource>;  // calls compute()

 public:
  explicit PointSource(const Params& p) : params_(p), magnitude_(p.handle("magnitude")) {
    if (p.text("system") != "vega" && p.given("reference_magnitude"))
      p.reject("reference_magnitude", "is used only with system = \"vega\"");
  }

  void prepare(Context& c) override {
    const Spectrum& band = params_.spectrum("band");
    const double lo = band.min_wavelength_m(), hi = band.max_wavelength_m();
    const bool own_sed = params_.has("sed");
    const std::string& shape = params_.text("sed_shape");
    if (own_sed && params_.given("sed_shape")) params_.reject("sed_shape", "give sed (a table) or sed_shape, not both");
    if (!own_sed && shape == "source" && c.light.illumination.empty())
      c.refuse_form("a source spectrum (or give sed)", RadiationForm::none);
    // A flat SED spans every band the chain may integrate, not only the normalising band's table: the source is
    // the same whatever band its magnitude is quoted in.
    const Spectrum& flat = shape == "flat_f_nu" ? physics::flat_f_nu_sed() : physics::flat_f_lambda_sed();
    const Spectrum& sed = own_sed ? params_.spectrum("sed") : shape == "source" ? c.light.illumination : flat;
    auto covers = [&](const Spectrum& s) { return s.min_wavelength_m() <= lo && s.max_wavelength_m() >= hi; };
    if (!covers(sed))
      params_.reject(own_sed ? "sed" : "band", "the band (" + nm_range(band) + ") reaches outside the SED's table (" +
                                                   nm_range(sed) + "): its magnitude there would be counted as 0");
    const std::string& system = params_.text("system");
    if (system == "vega") {
      const Spectrum& vega = params_.spectrum("vega_spectrum");
      if (!covers(vega)) params_.reject("vega_spectrum", "does not cover the band (" + nm_range(band) + ")");
      zero_point_ = physics::band_photon_rate(vega, band) * std::pow(10.0, 0.4 * params_.get("reference_magnitude"));
    } else if (system == "ab") {  // the reference spectra are the flat SEDs themselves: a flat SED in its own system
      zero_point_ = physics::band_photon_rate(physics::flat_f_nu_sed(), band);  // is scaled by exactly 1
    } else {
      zero_point_ = physics::band_photon_rate(physics::flat_f_lambda_sed(), band);
    }
    const double sed_rate = physics::band_photon_rate(sed, band);
    if (!(sed_rate > 0)) params_.reject(own_sed ? "sed" : "band", "the SED gives no photons in the band");
    // The signal per unit scale: the SED normalised to N₀ photons s⁻¹ m⁻² in the band (magnitude 0).
    if (own_sed) note_table(c.light, params_, "sed");
    else if (shape != "source") note_table(c.light, sed, "sed_shape = \"" + shape + "\" of " + params_.context());
    c.light.signal.form = RadiationForm::pupil_irradiance;
    c.light.signal.spectrum = sed.scaled(zero_point_ / sed_rate, "W m-2 m-1");
    if (!c.light.up_path_transmittance.empty())  // seen through an atmosphere
      c.light.signal.spectrum = c.light.signal.spectrum.product(c.light.up_path_transmittance, "W m-2 m-1");
    id_zero_point_ = c.declare(vocabulary::target_zero_point_photon_rate,
                               "N₀ = ∫ f_λ,ref T λ/(hc) dλ (" + system + ", Bessell & Murphy 2012 eq. A1)", "cm-2 s-1");
    id_magnitude_ = c.declare(vocabulary::target_band_magnitude, "input m (" + system + ")");
    id_photon_rate_ = c.declare("band_photon_rate", "m-2 s-1", "10^{-0.4 m} N₀ above the atmosphere", "cm-2 s-1");
  }

 private:
  template <class Access>
  void compute(Access& a) {
    using V = typename Access::Value;
    const V ratio = physics::magnitude_ratio(a.param(magnitude_), broadcast<V>(0.0));
    a.signal_scale() = ratio * a.up_path_scale();
    a.set(id_magnitude_, a.param(magnitude_));
    a.set(id_zero_point_, broadcast<V>(zero_point_));
    if (!a.full_detail()) return;
    a.set(id_photon_rate_, ratio * zero_point_);
  }

  const Params& params_;
  const double* magnitude_;
  double zero_point_ = 0;
  ResultId id_zero_point_{}, id_magnitude_{}, id_photon_rate_{};
};

}  // namespace

RADCHAIN_PLUGIN(PointSource, {
    .summary = "point source of given Vega/AB/ST magnitude in a bandpass, with its own SED (or the source's)",
    .reference = "Bessell & Murphy 2012 PASP 124, 140 (eq. A1); Oke & Gunn 1983 (AB); Bohlin & Gilliland 2004 (Vega)",
    .schema = schema,
    .publishes = {vocabulary::target_zero_point_photon_rate, vocabulary::target_band_magnitude},
})

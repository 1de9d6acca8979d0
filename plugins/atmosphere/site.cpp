// Observing conditions at a ground site, for objects above the atmosphere (stars, satellites): only the up path.
//   extinction   the object's light is dimmed by 10^{-0.4 k X}, or by a table τ(λ)^{X/X_table} (Bouguer-Lambert-Beer): k in mag per airmass in the band the target's
//                magnitude is given in (Bouguer's law in magnitudes; e.g. Ivezić et al. 2019 eq. 6's −k_m (X − 1)
//                term relative to the zenith). Neither given: the site curve practice uses when it has none of its
//                own, Rubin's fiducial Cerro Pachón atmosphere at X = 1 (lsst/throughputs 1.9 baseline/atmos_10.dat,
//                300-1150 nm: Rayleigh, ozone, water, aerosols), as a table τ(λ)^X; the report's transmittance row says so
//   seeing       FWHM θ(X) = θ_zenith X^0.6 (Kolmogorov turbulence, r0 ∝ X^{-3/5}: Roddier 1981, Prog. Optics 19,
//                281; Ivezić et al. 2019 §3.2), published for the detector's PSF; `seeing_at` says whether the value
//                given is θ_zenith or θ(X), and both are published
//   sky          the sky's own radiation, as measured at the site: it is already the light that reaches the
//                telescope, so it is never extinguished again and never takes the target's spectrum. Given as
//                  sky_brightness  m AB mag/arcsec², flat in f_ν: L_λ = 10^{-0.4 m} f_ν,AB c/λ² / Ω_arcsec²
//                                  (Oke & Gunn 1983; Ω_arcsec² = (π/648000)² sr), or
//                  sky_table       a spectral radiance table (a dark-sky SED), optionally scaled so that its AB
//                                  magnitude per arcsec² in sky_band is sky_brightness (photon-counting AB
//                                  magnitude, physics/magnitudes.hpp: m = −2.5 lg(∫ L T λ dλ / ∫ L_AB T λ dλ)).
//                It is handed on as the background radiance (light.background): the optics image it as an
//                extended scene (transmittance curve included) and the detector counts it by étendue per pixel.
//                atmosphere.sky_brightness is the input m, or the table's AB magnitude in sky_band when given.
// The airmass is required; extinction defaults to the site curve above; seeing and sky are optional (absent: none).
#include "radchain/physics/emva1288.hpp"
#include "radchain/physics/magnitudes.hpp"
#include "radchain/plugin.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <string_view>

namespace {
using namespace radchain;

// The default extinction: lsst/throughputs 1.9 baseline/atmos_10.dat (MODTRAN, Cerro Pachón, X = 1, aerosols), the
// curve SMTN-002 computes Rubin's depths with, over its whole 300-1150 nm.
constexpr std::string_view default_site_curve = "lsst_atmos_10_300-1150nm_throughputs1.9.csv";

const Schema& schema() {
  static const Schema s = {
      number("airmass", "1.2").needed().at_least(1).at_most(40).affects_spectrum().described("airmass X of the line of sight"),
      number("extinction", "0.10").at_least(0).at_most(5)
          .described("extinction coefficient k in mag per airmass, in the target's band (or give transmittance_table; "
                     "neither: the default site curve)"),
      spectrum_file("transmittance_table", "1", "lsst_atmos_10_throughputs1.9.csv").fallback(std::string(default_site_curve))
          .described("spectral transmittance τ(λ) of the atmosphere at table_airmass (instead of extinction); default: "
                     "Rubin's fiducial Cerro Pachón atmosphere at X = 1, 300-1150 nm"),
      number("table_airmass", "1").fallback("1").at_least(1).at_most(40).affects_spectrum()
          .described("airmass at which transmittance_table was computed: τ(λ)^{X/X_table} at airmass X"),
      quantity("seeing", "rad", "0.7 arcsec").above(0)
          .described("seeing FWHM, at the zenith (scaled by X^0.6) or along the line of sight as seeing_at says; default: no seeing"),
      choice("seeing_at", {"zenith", "line_of_sight"}).fallback("zenith")
          .described("where `seeing` is measured: at the zenith (a site's quoted seeing) or along the line of sight (already at X)"),
      number("sky_brightness", "21.2").at_least(10).at_most(30).scales(Scaling::magnitude)
          .described("sky surface brightness at the site in AB mag/arcsec² (flat in f_ν; in sky_band when sky_table is given); default: no sky"),
      spectrum_file("sky_table", "W m-2 sr-1 m-1", "lsst_darksky_throughputs1.9.csv")
          .described("sky spectral radiance at the site (a dark-sky SED; W m-2 nm-1 arcsec-2 or per sr)"),
      spectrum_file("sky_band", "1", "lsst_hardware_r_throughputs1.9.csv")
          .described("bandpass in which sky_table's AB mag/arcsec² is computed, or normalised to sky_brightness"),
  };
  return s;
}

// Ω of one arcsec², sr.
constexpr double arcsec2_sr = (std::numbers::pi / 648000.0) * (std::numbers::pi / 648000.0);

// The AB zero point (f_ν = 3630.8 Jy) as a radiance per arcsec², W m-2 sr-1 m-1, over 0.1-30 µm: a flat-f_ν sky
// of magnitude 0 per arcsec². Log-spaced, 20,001 points: linear interpolation of 1/λ² errs < 1e-7.
// A constant of nature, built once per process (20,001 exponentials and slopes: it cost more than the rest of a
// site's spectral phase, which an airmass sweep re-runs at every airmass). Spectra share their immutable data.
const Spectrum& ab_radiance_per_arcsec2() {
  static const Spectrum ab = physics::ab_reference_spectrum(1e-7, 3e-5, 20001).scaled(1.0 / arcsec2_sr, "W m-2 sr-1 m-1");
  return ab;
}

class Site final : public Stage {
 public:
  explicit Site(const Params& p)
      : params_(p), airmass_(p.handle("airmass")), extinction_(p.handle("extinction")), seeing_(p.handle("seeing")),
        sky_(p.handle("sky_brightness")) {
    if (p.given("extinction") && p.given("transmittance_table"))
      p.reject("extinction", "give either extinction (mag per airmass) or transmittance_table (τ(λ) at table_airmass), not both");
    if (p.given("table_airmass") && !p.given("transmittance_table"))
      p.reject("table_airmass", "is the airmass of a transmittance_table given in the file (the default site curve is at X = 1)");
    if (p.has("sky_band") && !p.has("sky_table"))
      p.reject("sky_band", "is the band of a sky_table (a sky_brightness alone is flat in f_ν, the same in every band)");
    if (p.has("sky_table") && p.has("sky_brightness") && !p.has("sky_band"))
      p.reject("sky_brightness", "the sky is given twice (sky_table and sky_brightness): give sky_band to normalise "
                                 "the table to sky_brightness in that band, or drop one");
  }

  void prepare(Context& c) override {
    if (!params_.has("extinction")) {
      // The airmass is spectral here: it changes the table's shape τ^{X/X_table}.
      const Spectrum& table = params_.spectrum("transmittance_table");
      const double power = params_.get("airmass") / params_.get("table_airmass");
      // τ^p = exp(p ln τ) with ln τ kept per table (an airmass sweep re-runs this at every airmass: Eigen's
      // vectorised exp instead of a scalar pow per node); 0 where τ = 0 (ln τ = −∞).
      if (log_table_source_ != table.value().data()) {
        log_table_source_ = table.value().data();
        log_table_ = table.value().max(0.0).log();
      }
      const Eigen::ArrayXd tau = (log_table_ == -std::numeric_limits<double>::infinity()).select(0.0, (power * log_table_).exp());
      const Spectrum path(table.wavelength_m(), tau, "1", Extrapolation::zero);
      c.light.up_path_transmittance =
          c.light.up_path_transmittance.empty() ? path : c.light.up_path_transmittance.product(path, "1");
      note_table(c.light, params_, "transmittance_table");
    }
    id_airmass_ = c.declare(vocabulary::atmosphere_airmass, "input X");
    id_transmittance_ = c.declare("transmittance", "1",
                                  params_.has("extinction")                ? "10^{-0.4 k X} (Bouguer, in magnitudes)"
                                  : params_.given("transmittance_table") ? "1 (the table's τ(λ)^{X/X_table} is spectral)"
                                                                          : "1 (spectral: τ(λ)^X of the default site curve, Rubin's "
                                                                            "Cerro Pachón atmosphere at X = 1; give extinction or "
                                                                            "transmittance_table for another site)");
    // Both are reported, whichever was given: a seeing quoted at the zenith is 2.23" along a line of sight at X = 1.2
    // when 2" was written, and a reader of the report sees which is which.
    if (params_.has("seeing")) {
      const bool zenith = params_.text("seeing_at") == "zenith";
      id_seeing_ = c.declare(vocabulary::atmosphere_seeing_fwhm, zenith ? "θ_zenith X^0.6 (Roddier 1981)" : "input θ (seeing_at = line_of_sight)", "arcsec");
      id_seeing_zenith_ = c.declare("seeing_zenith_fwhm", "rad", zenith ? "input θ_zenith" : "θ X^-0.6 (Roddier 1981)", "arcsec");
    }
    prepare_sky(c);
  }

  void evaluate(Context& c) override {
    const double x = *airmass_;
    const double tau = params_.has("extinction") ? std::pow(10.0, -0.4 * *extinction_ * x) : 1.0;
    c.light.up_path_scale *= tau;
    c.results.set(id_airmass_, x);
    c.results.set(id_transmittance_, tau);
    if (id_seeing_) {
      const bool zenith = params_.text("seeing_at") == "zenith";
      c.results.set(*id_seeing_, zenith ? physics::seeing_at_airmass(*seeing_, x) : *seeing_);
      c.results.set(*id_seeing_zenith_, zenith ? *seeing_ : *seeing_ / std::pow(x, 0.6));
    }
    if (table_ && params_.has("sky_brightness")) {  // the table scaled to sky_brightness in sky_band
      c.light.background.scale = std::pow(10.0, -0.4 * *sky_) * ab_in_band_ / table_in_band_;
      c.results.set(*id_sky_, *sky_);
    } else if (table_) {
      c.light.background.scale = 1.0;
      if (id_sky_) c.results.set(*id_sky_, physics::band_magnitude(table_in_band_, ab_in_band_));
    } else if (params_.has("sky_brightness")) {
      c.light.background.scale = std::pow(10.0, -0.4 * *sky_);
      c.results.set(*id_sky_, *sky_);
    }
  }

 private:
  // The sky as the background radiance for the optics and detector (light.background, scene radiance).
  void prepare_sky(Context& c) {
    table_ = params_.has("sky_table");
    if (!table_ && !params_.has("sky_brightness")) return;
    if (!table_) {
      c.light.background = Radiation{RadiationForm::scene_radiance, ab_radiance_per_arcsec2(), 1.0};
      id_sky_ = c.declare(vocabulary::atmosphere_sky_brightness, "input, AB mag/arcsec² at the site, flat in f_ν (not extinguished again)");
      return;
    }
    const Spectrum& table = params_.spectrum("sky_table");
    if (table.value().minCoeff() < 0) params_.reject("sky_table", "a sky radiance cannot be negative");
    c.light.background = Radiation{RadiationForm::scene_radiance, table, 1.0};
    if (!params_.has("sky_band")) return;
    const Spectrum& band = params_.spectrum("sky_band");
    if (band.min_wavelength_m() < table.min_wavelength_m() || band.max_wavelength_m() > table.max_wavelength_m())
      params_.reject("sky_band", "the band (" + nm_range(band) + ") reaches outside the sky_table (" + nm_range(table) +
                                     "): the sky would count 0 there");
    table_in_band_ = physics::band_photon_rate(table, band);
    ab_in_band_ = physics::band_photon_rate(ab_radiance_per_arcsec2(), band);
    if (!(table_in_band_ > 0)) params_.reject("sky_table", "the sky has no light in sky_band");
    id_sky_ = c.declare(vocabulary::atmosphere_sky_brightness,
                        params_.has("sky_brightness") ? "input: sky_table scaled to it in sky_band (AB mag/arcsec²)"
                                                      : "AB mag/arcsec² of sky_table in sky_band: −2.5 lg(∫ L T λ dλ / ∫ L_AB T λ dλ)");
  }

  const Params& params_;
  const double *airmass_, *extinction_, *seeing_, *sky_;
  ResultId id_airmass_{}, id_transmittance_{};
  std::optional<ResultId> id_seeing_, id_seeing_zenith_, id_sky_;
  bool table_ = false;
  const double* log_table_source_ = nullptr;  // the transmittance table whose ln τ is log_table_
  Eigen::ArrayXd log_table_;
  double table_in_band_ = 0, ab_in_band_ = 0;  // photon radiances in sky_band (per arcsec²-scaled sr)
};

}  // namespace

RADCHAIN_PLUGIN(Site, {
    .summary = "ground site: airmass, extinction (mag/airmass, a τ(λ) table, or by default Rubin's Cerro Pachón curve), seeing at the zenith × X^0.6, sky in AB mag/arcsec² or as a spectral radiance table",
    .reference = "Bouguer's law; Roddier 1981 (seeing ∝ X^0.6); Ivezić et al. 2019 ApJ 873, 111 §3.2",
    .schema = schema,
    .publishes = {vocabulary::atmosphere_airmass, vocabulary::atmosphere_seeing_fwhm, vocabulary::atmosphere_sky_brightness},
})

// Observing conditions at a ground site, for objects above the atmosphere (stars, satellites): only the up path.
//   extinction   the object's light is dimmed by 10^{-0.4 k X}, or by a table τ(λ)^{X/X_table} (Bouguer-Lambert-Beer): k in mag per airmass in the band the target's
//                magnitude is given in (Bouguer's law in magnitudes; e.g. Ivezić et al. 2019 eq. 6's −k_m (X − 1)
//                term relative to the zenith)
//   seeing       FWHM θ(X) = θ_zenith X^0.6 (Kolmogorov turbulence, r0 ∝ X^{-3/5}: Roddier 1981, Prog. Optics 19,
//                281; Ivezić et al. 2019 §3.2), published for the detector's PSF
//   sky          surface brightness in AB mag/arcsec² as measured at the site in the detector's band: it is
//                already the light that reaches the telescope, so it is published as is and never extinguished
//                again (the detector counts it by étendue per pixel)
// Every condition is explicit: airmass and one of extinction / transmittance_table are required; seeing and sky are optional (absent: none).
#include "radchain/physics/emva1288.hpp"
#include "radchain/plugin.hpp"

#include <cmath>

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      number("airmass", "1.2").needed().at_least(1).at_most(40).affects_spectrum().described("airmass X of the line of sight"),
      number("extinction", "0.10").at_least(0).at_most(5)
          .described("extinction coefficient k in mag per airmass, in the target's band (or give transmittance_table)"),
      spectrum_file("transmittance_table", "1", "lsst_atmos_10_throughputs1.9.csv")
          .described("spectral transmittance τ(λ) of the atmosphere at table_airmass (instead of extinction)"),
      number("table_airmass", "1").fallback("1").at_least(1).at_most(40).affects_spectrum()
          .described("airmass at which transmittance_table was computed: τ(λ)^{X/X_table} at airmass X"),
      quantity("seeing", "rad", "0.7 arcsec").above(0)
          .described("seeing FWHM at the zenith (scaled by X^0.6); default: no seeing"),
      number("sky_brightness", "21.2").at_least(10).at_most(30)
          .described("sky surface brightness at the site in AB mag/arcsec² in the detector's band; default: no sky"),
  };
  return s;
}

class Site final : public Stage {
 public:
  explicit Site(const Params& p)
      : params_(p), airmass_(p.handle("airmass")), extinction_(p.handle("extinction")), seeing_(p.handle("seeing")),
        sky_(p.handle("sky_brightness")) {
    if (p.has("extinction") == p.has("transmittance_table"))
      p.reject(p.has("extinction") ? "extinction" : "airmass",
               "give either extinction (mag per airmass) or transmittance_table (τ(λ) at table_airmass)");
  }

  void prepare(Context& c) override {
    if (params_.has("transmittance_table")) {
      // The airmass is spectral here: it changes the table's shape τ^{X/X_table}.
      const Spectrum& table = params_.spectrum("transmittance_table");
      const double power = params_.get("airmass") / params_.get("table_airmass");
      const Spectrum path(table.wavelength_m(), table.value().max(0.0).pow(power), "1", Extrapolation::zero);
      c.light.up_path_transmittance =
          c.light.up_path_transmittance.empty() ? path : c.light.up_path_transmittance.product(path, "1");
    }
    id_airmass_ = c.declare(vocabulary::atmosphere_airmass, "input X");
    id_transmittance_ = c.declare("transmittance", "1", params_.has("extinction") ? "10^{-0.4 k X} (Bouguer, in magnitudes)" : "1 (the table's τ(λ)^{X/X_table} is spectral)");
    if (params_.has("seeing"))
      id_seeing_ = c.declare(vocabulary::atmosphere_seeing_fwhm, "θ_zenith X^0.6 (Roddier 1981)", "arcsec");
    if (params_.has("sky_brightness"))
      id_sky_ = c.declare(vocabulary::atmosphere_sky_brightness, "input, AB mag/arcsec² at the site (not extinguished again)");
  }

  void evaluate(Context& c) override {
    const double x = *airmass_;
    const double tau = params_.has("extinction") ? std::pow(10.0, -0.4 * *extinction_ * x) : 1.0;
    c.light.up_path_scale *= tau;
    c.results.set(id_airmass_, x);
    c.results.set(id_transmittance_, tau);
    if (id_seeing_) c.results.set(*id_seeing_, physics::seeing_at_airmass(*seeing_, x));
    if (id_sky_) c.results.set(*id_sky_, *sky_);
  }

 private:
  const Params& params_;
  const double *airmass_, *extinction_, *seeing_, *sky_;
  ResultId id_airmass_{}, id_transmittance_{};
  std::optional<ResultId> id_seeing_, id_sky_;
};

}  // namespace

RADCHAIN_PLUGIN(Site, {
    .summary = "ground site: airmass, extinction (mag/airmass), seeing at the zenith × X^0.6, sky in AB mag/arcsec²",
    .reference = "Bouguer's law; Roddier 1981 (seeing ∝ X^0.6); Ivezić et al. 2019 ApJ 873, 111 §3.2",
    .schema = schema,
    .publishes = {vocabulary::atmosphere_airmass, vocabulary::atmosphere_seeing_fwhm, vocabulary::atmosphere_sky_brightness},
})

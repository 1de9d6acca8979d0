// A telescope or objective: entrance pupil D with a central obscuration, transmittance (constant or a
// curve) and focal length. A point object's pupil irradiance becomes image power
//   P_λ = E_λ · π D²/4 · (1 - ε²) · τ            (Pan 2010 eq. 2, in spectral form)
// and an extended scene's radiance becomes focal-plane irradiance
//   E'_λ = π L_λ τ / (4 N²) = ¼ (D/f')² τ M_λ       (Kolobrodov 1996 eq. 5, M = π L; on axis, object at infinity)
// Optionally a point spread function for the detector's ensquared energy (not in Pan 2010, which puts all
// of a star's energy in one pixel): psf = "airy" (diffraction-limited annular pupil at psf_wavelength, needs
// focal_length) or "gaussian" (FWHM on the focal plane). See docs/physics/ensquared-energy-and-background.md.
#include "radchain/physics/psf.hpp"
#include "radchain/curve_components.hpp"
#include "radchain/plugin.hpp"

#include <cmath>
#include <numbers>

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      quantity("aperture", "m", "15 cm").needed().above(0).at_most(100).scales(Scaling::power_law).described("entrance pupil diameter D"),
      number("obscuration", "0.3").fallback("0").at_least(0).below(1)
          .described("central obscuration, linear ratio ε (collecting area × (1 - ε²))"),
      number("transmittance", "0.56").fallback("1").above(0).at_most(1)
          .described("optical transmittance τ (in-band average; multiplies any transmittance_curve)"),
      spectrum_file("transmittance_curve", "1", "lsst_m1_throughputs1.9.csv").as_list()
          .described("spectral transmittance τ(λ): one table, or a list of the components' tables (mirror "
                     "coatings, lenses, window, filter), multiplied into the signal spectrum; each component's mean "
                     "is a result"),
      quantity("focal_length", "m", "832 mm").above(0).at_most(1000).scales(Scaling::power_law)
          .described("effective focal length f' (needed for extended scenes and pixel geometry)"),
      choice("psf", {"none", "airy", "gaussian"}).fallback("none")
          .described("point spread function published for the detector's ensquared energy (none: not modelled)"),
      quantity("psf_wavelength", "m", "0.6 um").above(0)
          .described("wavelength of the monochromatic Airy PSF (psf = \"airy\"; e.g. the band's mean)"),
      quantity("gaussian_fwhm", "m", "15 um").above(0)
          .described("full width at half maximum of a Gaussian PSF on the focal plane (psf = \"gaussian\")"),
  };
  return s;
}

class Telescope final : public LaneStage<Telescope> {
  friend class LaneStage<Telescope>;  // calls compute()

 public:
  bool power_law() const override { return true; }  // area ∝ D², N = f'/D, transmittance a factor

  explicit Telescope(const Params& p)
      : params_(p), aperture_(p.handle("aperture")), obscuration_(p.handle("obscuration")),
        transmittance_(p.handle("transmittance")), focal_length_(p.handle("focal_length")),
        psf_wavelength_(p.handle("psf_wavelength")), gaussian_fwhm_(p.handle("gaussian_fwhm")),
        airy_(p.text("psf") == "airy"), gaussian_(p.text("psf") == "gaussian") {
    if (airy_ && !p.has("psf_wavelength")) p.reject("psf", "psf = \"airy\" needs psf_wavelength, e.g. \"0.6 um\"");
    if (airy_ && !p.has("focal_length")) p.reject("psf", "psf = \"airy\" needs focal_length (the Airy radius is 1.22 λ f'/D)");
    if (gaussian_ && !p.has("gaussian_fwhm")) p.reject("psf", "psf = \"gaussian\" needs gaussian_fwhm, e.g. \"15 um\"");
    if (!airy_ && p.has("psf_wavelength")) p.reject("psf_wavelength", "is used only with psf = \"airy\"");
    if (!gaussian_ && p.has("gaussian_fwhm")) p.reject("gaussian_fwhm", "is used only with psf = \"gaussian\"");
  }

  void prepare(Context& c) override {
    Radiation& signal = c.light.signal;
    if (params_.has("transmittance_curve") && signal.form != RadiationForm::none)
      signal.spectrum = signal.spectrum.product(params_.spectrum("transmittance_curve"), signal.spectrum.unit());
    note_table(c.light, params_, "transmittance_curve");
    if (signal.form == RadiationForm::pupil_irradiance) {
      signal.form = RadiationForm::focal_power;
    } else if (signal.form == RadiationForm::scene_radiance) {
      if (!params_.has("focal_length"))
        params_.reject("aperture", "an extended scene needs focal_length as well (image irradiance depends on f/D)");
      signal.form = RadiationForm::focal_irradiance;
    } else if (signal.form != RadiationForm::none) {  // none: a geometry-only file, nothing to image
      c.refuse_form("a point irradiance or a scene radiance at the pupil", signal.form);
    }
    form_ = signal.form;
    // A scene background (ground, sky) goes through the same optics — transmittance curve included — as an
    // extended scene, behind an extended or a point target alike (the sky of a star field).
    Radiation& background = c.light.background;
    if (background.form == RadiationForm::scene_radiance && params_.has("focal_length")) {
      if (params_.has("transmittance_curve"))
        background.spectrum = background.spectrum.product(params_.spectrum("transmittance_curve"), background.spectrum.unit());
      background.form = RadiationForm::focal_irradiance;
    }
    // The atmosphere's path radiance enters the pupil beside the scene and crosses the same spectral transmittance
    // (it stays a radiance: the detector that counts it applies the étendue and the scalar τ, as for the scene).
    if (params_.has("transmittance_curve") && !c.light.path_radiance.empty())
      c.light.path_radiance = c.light.path_radiance.product(params_.spectrum("transmittance_curve"), c.light.path_radiance.unit());
    id_area_ = c.declare(vocabulary::optics_collecting_area, "π D²/4 (1 - ε²)", "cm2");
    id_aperture_ = c.declare(vocabulary::optics_aperture, "input D", "cm");
    id_transmittance_ = c.declare(vocabulary::optics_transmittance, "input τ");
    id_obscuration_ = c.declare(vocabulary::optics_obscuration, "input ε (linear)");
    has_focal_length_ = params_.has("focal_length");
    if (has_focal_length_) {
      id_focal_ = c.declare(vocabulary::optics_focal_length, "input f'", "mm");
      id_f_number_ = c.declare(vocabulary::optics_f_number, "N = f'/D");
    }
    // The PSF, by name: the detector finds "optics.psf_wavelength" (Airy) or "optics.gaussian_fwhm".
    if (airy_) {
      id_psf_wavelength_ = c.declare(vocabulary::optics_psf_wavelength, "input λ of the Airy PSF", "um");
      id_airy_radius_ = c.declare("airy_radius", "m", "first dark ring v₁ λ N/π (v₁ = 3.8317 for ε = 0: 1.2197 λ N; "
                                  "Born & Wolf §8.5.2)", "um");
    }
    if (gaussian_) id_gaussian_fwhm_ = c.declare(vocabulary::optics_gaussian_fwhm, "input FWHM of the Gaussian PSF", "um");
    // Each component of the curve and their product as band means (curve_components.hpp): over the source's
    // reporting band when it has one, else over the product's own passband (≥ 1 % of its peak).
    if (params_.has("transmittance_curve")) {
      const auto [lo, hi] = c.light.has_report_band()
                                ? std::pair{c.light.report_band_min_m, c.light.report_band_max_m}
                                : passband_m(params_.spectrum("transmittance_curve"));
      components_ = declare_component_means(c, params_, "transmittance_curve", lo, hi);
    }
    if (auto lux = c.find(vocabulary::target_illuminance))
      target_lux_ = *lux, id_flux_ = c.declare("luminous_flux", "lm", "Pan 2010 eq. (2): F = π D² E_t / 4", "lm");
  }

  private:
  template <class Access>
  void compute(Access& a) {
    using V = typename Access::Value;
    using std::sqrt;
    const V d = a.param(aperture_), eps = a.param(obscuration_), tau = a.param(transmittance_);
    const V unobscured = 1.0 - eps * eps;
    const V area = std::numbers::pi / 4.0 * d * d * unobscured;
    a.set(id_area_, area);
    a.set(id_aperture_, d);
    a.set(id_transmittance_, tau);
    a.set(id_obscuration_, eps);
    if (form_ == RadiationForm::focal_power) {
      a.signal_scale() *= area * tau;
    }
    if (has_focal_length_) {  // Kolobrodov 1996 eq. 5: E' = π L τ (1 − ε²) / (4 N²)
      const V n = a.param(focal_length_) / d;
      const V radiance_to_irradiance = std::numbers::pi * unobscured * tau / (4.0 * n * n);
      if (form_ == RadiationForm::focal_irradiance) a.signal_scale() *= radiance_to_irradiance;
      if (a.light().background.form == RadiationForm::focal_irradiance) a.background_scale() *= radiance_to_irradiance;
    }
    if (has_focal_length_) {
      a.set(id_focal_, a.param(focal_length_));
      a.set(id_f_number_, a.param(focal_length_) / d);
    }
    if (airy_) {
      // The first dark ring moves with ε (a scalar parameter): recomputed when it changes, per lane.
      V ring = broadcast<V>(0.0);
      if constexpr (std::is_same_v<V, double>) ring = first_dark_ring_v(eps);
      else for (int i = 0; i < lane_count; ++i) ring(i) = first_dark_ring_v(eps(i));
      a.set(id_psf_wavelength_, a.param(psf_wavelength_));
      a.set(id_airy_radius_, ring * a.param(psf_wavelength_) * (a.param(focal_length_) / d) / std::numbers::pi);
    }
    if (gaussian_) a.set(id_gaussian_fwhm_, a.param(gaussian_fwhm_));
    if (target_lux_ && a.full_detail()) a.set(id_flux_, std::numbers::pi / 4.0 * d * d * a.value(*target_lux_));
    for (const ComponentMean& m : components_) a.set(m.id, broadcast<V>(m.mean));
  }

  double first_dark_ring_v(double eps) {
    if (eps != ring_obscuration_) first_dark_ring_v_ = physics::airy_first_dark_ring_v(eps), ring_obscuration_ = eps;
    return first_dark_ring_v_;
  }

  const Params& params_;
  const double *aperture_, *obscuration_, *transmittance_, *focal_length_, *psf_wavelength_, *gaussian_fwhm_;
  bool airy_, gaussian_;
  double first_dark_ring_v_ = 0, ring_obscuration_ = -1;
  RadiationForm form_ = RadiationForm::none;
  bool has_focal_length_ = false;  // read once per spectral phase: evaluate() does no lookups by name
  std::optional<ResultId> target_lux_;
  std::vector<ComponentMean> components_;
  ResultId id_area_{}, id_aperture_{}, id_transmittance_{}, id_focal_{}, id_f_number_{}, id_flux_{}, id_obscuration_{},
      id_psf_wavelength_{}, id_airy_radius_{}, id_gaussian_fwhm_{};
};

}  // namespace

RADCHAIN_PLUGIN(Telescope, {
    .summary = "entrance pupil, obscuration, transmittance, focal length and PSF of an objective",
    .reference = "Pan 2010 eq. (2); Kolobrodov 1996 eq. (5); Born & Wolf §8.5.2 (Airy PSF)",
    .schema = schema,
    .publishes = {vocabulary::optics_collecting_area, vocabulary::optics_aperture, vocabulary::optics_transmittance,
                  vocabulary::optics_obscuration, vocabulary::optics_focal_length, vocabulary::optics_f_number,
                  vocabulary::optics_psf_wavelength, vocabulary::optics_gaussian_fwhm},
    .needs = {if_present(vocabulary::target_illuminance)},
})

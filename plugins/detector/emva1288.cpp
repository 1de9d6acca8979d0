// A CMOS or CCD camera described by its EMVA 1288 datasheet (Release 4.0 Linear, 2021), counting a point image
// in an n×n window (ensquared energy) or by PSF-weighted photometry (noise-equivalent area n_eff), over
// `exposures` co-added frames, optionally with `tdi_stages` of charge-domain TDI and b×b digital binning.
//   image     S_img = N_tdi t ∫ P_λ η(λ) λ/(hc) dλ        (EMVA 1288 eq. 1, μ_e = η μ_p; Pan 2010 eqs. 6-8)
//   signal    window: S₁ = EE · S_img;  circle: S₁ = EC(R) · S_img;  psf: S₁ = S_img (the optimal estimator
//             recovers the whole image)
//   per (binned) pixel, one exposure (b² native pixels summed digitally; TDI: signal and dark × N_tdi, read once):
//     temporal  v_t = b² [N_tdi (B + μ_I t) + σ_d0² + σ_q²/K² + σ_other²],  σ_q² = 1/12 DN²   (EMVA eqs. 5, 29)
//     spatial   v_s = b² σ_DSNU²                                                               (EMVA §2.4, eq. 18)
//   noise over M co-added exposures: n² = M (S₁ + n_pix v_t) + M² (n_pix v_s + s_g² S₁²/n_eff)
//     temporal noise adds in variance over M frames; the fixed patterns (DSNU, PRNU s_g) repeat in every frame
//     of the same pixels and add in amplitude (EMVA 1288 §2.4: spatial non-uniformity does not average out).
//     PRNU on the point image: Σ_i (s_g S f_i)² = s_g² S² Σ f_i² = s_g² S²/n_eff (n_eff = 1/Σ f_i²), and under TDI
//     s_g² S²/(n_eff N_tdi): each stage is another pixel row with gains of its own (physics/emva1288.hpp).
//   n_pix = n² (window), π R²/(b p)² (circle of radius R on the focal plane: the aperture's area in pixels, as
//   aperture photometry counts its sky and read noise; Howell, Handbook of CCD Astronomy 2nd ed. (2006) eq. 4.4),
//   or n_eff (psf: King 1983; LSST SMTN-002; physics/emva1288.hpp)
//   SNR = M S₁ / n                                           (EMVA eq. 6 summed over the photometric aperture)
// The PSF: optics' Airy (psf = "airy") or Gaussian (psf = "gaussian"), or atmospheric seeing (an atmosphere that
// publishes atmosphere.seeing_fwhm) added in quadrature to the diffraction core as a Gaussian (Ivezić et al. 2019
// §3.2). Without a PSF all of the image falls in one pixel (Pan 2010's assumption): the brightest pixel gets it all.
// Line-of-sight jitter (`jitter`, rms per axis, σ_j) blurs the exposure by a Gaussian of σ_j f' (its MTF is
// exp(−2π² σ_j² ν²): Holst, Electro-Optical Imaging System Performance 5th ed. (2008) §10.4), added in quadrature
// to the PSF's Gaussian FWHM; an Airy core is then taken as its Gaussian (physics::diffraction_fwhm_rad).
// Circular apertures (`photometry = "circle"`, `aperture_radius` on the sky): encircled energy of the PSF,
// Gaussian 1 − exp(−R²/2σ²) or the (obscured) Airy closed form of physics/psf.hpp.
// Sky: the background radiance of the atmosphere (light.background: the site's sky, flat in f_ν or a dark-sky
// table), imaged by the optics as an extended scene (E'_λ = π L_λ τ(λ) (1 − ε²)/(4N²), transmittance curve
// included) is counted by étendue per native pixel, like an extended scene below:
//   B = t p² ∫ E'_λ η(λ) λ/(hc) dλ  = t A τ Ω_pix ∫ L_λ η λ/(hc) dλ   (A_pixel Ω = A_pupil IFOV²)
// for a flat-f_ν sky of m AB mag/arcsec² this is t A τ Ω_pix[arcsec²] 10^{-0.4 m} ∫ f_ν,AB η/(hλ) dλ (SMTN-002).
// MOVING TARGETS (physics/streak.hpp): a target crossing the field at `target_rate` ω (relative
// to the stars) streaks over L = ω t f' per exposure under sidereal tracking (`tracking = "sidereal"`); under
// rate tracking the target is a point and the stars streak by L. PSF-weighted photometry of the streak is the
// matched filter along it: n_eff = 1/Σ f_ij² of the Gaussian PSF ⊗ the segment on the (binned) pixel grid, which
// then enters the noise and PRNU terms above; the peak pixel is the streak's; trailing loss
// 1.25 lg(n_eff,streak/n_eff,static) (background-limited; Jones et al. 2018, Icarus 303, 181).
// SATURATION (EMVA §2.3, saturation capacity μ_e.sat): the brightest native pixel's charge in one exposure,
// f_peak S_img,1 + N_tdi (B_native + μ_I t) (f_peak: the PSF's fraction in the pixel it is centred on), over
// min(μ_e.sat, (2^bits − 1)/K), is detector.peak_pixel_fill; the criterion "unsaturated" fails when it exceeds 1.
//
// EXTENDED SCENES (Earth-observation line, TDI and frame cameras). When the optics deliver a
// focal-plane irradiance E'_λ (a scene radiance through a telescope with a focal length: E' = π L τ (1−ε²)/(4N²)),
// one native pixel counts, per exposure (line time or frame time t; N_tdi stages summed in the charge domain),
//   μ_e = N_tdi t p² ∫ E'_λ η(λ) λ/(hc) dλ         = the étendue count A_pixel Ω τ ∫ L_λ η λ/(hc) dλ
// (EMVA 1288 R4.0 §2.1 μ_p = A E t λ/(hc), eq. 1 μ_e = η μ_p; Ω = π(1−ε²)/(4N²), i.e. A_pixel Ω = A_pupil IFOV²:
// physics::pixel_projected_solid_angle_sr). The noise of one (b×b binned) pixel over M exposures is the EMVA
// model with spatial terms (eqs. 5, 6, 18; physics::emva_uniform_scene_variance_e2), SNR = M S₁ / n.
// The mission convention (ESA Sentinel-2 User Handbook (2015), radiometric table: "SNR at L_ref" per band, the
// mission requirement; Landsat-8 OLI: SNR at L_typ, Knight & Kvaran 2014) states the SNR of one pixel at a
// band-averaged spectral radiance L_ref in W m-2 sr-1 µm-1. Averaged
// with the system's response per watt (τ η λ), μ_e = k L_ref for any spectrum, k = N_tdi t p² Ω τ ∫ η λ/(hc) dλ
// (physics::radiance_responsivity_e). Published: detector.scene_radiance (the scene's L̄ = μ_e/k),
// detector.reference_radiance (`reference_radiance`, or `reference_reflectance` × L̄/ρ of a reflectance
// target, or the scene itself), detector.reference_signal_electrons, detector.snr_at_reference,
// detector.noise_equivalent_radiance NEΔL = n_ref / (dS/dL) = L_ref / SNR_ref,
// detector.noise_equivalent_reflectance NEΔρ = n_ref / (dS/dρ) = n_ref ρ / S (the scene's sun angle and
// atmosphere: dL/dρ = L̄/ρ for reflectance_ground, whose path radiance does not enter the signal),
// detector.saturation_radiance L_sat = (min(μ_e.sat, (2^bits−1)/K) − N_tdi μ_I t) / k, and the scene pixel's
// fill. Limits: τ is the optics' scalar transmittance (a transmittance_curve is folded into the scene spectrum
// and then weights the scene's L̄ as well); on axis (no cos⁴ fall-off). The atmosphere's path radiance is part of
// the scene's radiance (signal, noise, fill, L_ref from a reflectance) but not of dS/dρ (NEΔρ).
#include "radchain/physics/emva1288.hpp"
#include "radchain/physics/magnitudes.hpp"
#include "radchain/physics/photometry.hpp"
#include "radchain/physics/psf.hpp"
#include "radchain/physics/streak.hpp"
#include "radchain/curve_components.hpp"
#include "radchain/look.hpp"
#include "radchain/physics/earth_geometry.hpp"
#include "radchain/plugin.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      number("qe", "0.6").fallback("1").above(0).at_most(1)
          .described("quantum efficiency η (EMVA 1288 §2.1; multiplies any qe_curve)"),
      spectrum_file("qe_curve", "1", "cmos_sony_imx428_mono_qe.csv").as_list()
          .described("spectral quantum efficiency η(λ): one table, or a list (window, filter, sensor QE) multiplied; "
                     "each component's mean over the band is a result"),
      quantity("band_min", "m", "0.4 um").needed().above(0).affects_spectrum().described("detector band lower limit"),
      quantity("band_max", "m", "0.9 um").needed().above(0).affects_spectrum().described("detector band upper limit"),
      quantity("integration_time", "s", "10 ms").fallback("0 s").at_least(0)
          .described("exposure time t of one frame (of one TDI stage for tdi_stages > 1); 0 or absent for a scene seen "
                     "from an orbiting platform: the line time GSD_along / ground speed, a pushbroom's one line per "
                     "ground line"),
      quantity("gain", "electron-1", "0.25 DN/e-").needed().above(0).described("system gain K in DN/e- (EMVA eq. 3), or its reciprocal 1/K in e-/DN (e-/ADU)"),
      quantity("read_noise", "electron", "2.3 e-").needed().at_least(0).formerly("dark_noise")
          .described("read noise: EMVA's temporal dark noise σ_d0 (§4.2: at zero exposure time, read noise included)"),
      quantity("full_well", "electron", "10500 e-").needed().above(0).formerly("saturation_capacity")
          .described("full well: EMVA's saturation capacity μ_e.sat (§2.3)"),
      quantity("dark_current", "electron/s", "1 e-/s").fallback("0 e-/s").at_least(0)
          .described("dark current μ_I (EMVA §4.2)"),
      number("prnu", "0.005").fallback("0").at_least(0).below(1)
          .described("photo-response non-uniformity s_g as a fraction (EMVA §2.4: PRNU1288 / 100 %)"),
      quantity("dsnu", "electron", "1 e-").fallback("0 e-").at_least(0)
          .described("dark signal non-uniformity σ_o in electrons (EMVA §2.4: DSNU1288)"),
      quantity("other_noise", "electron", "1 e-").fallback("0 e-").at_least(0)
          .described("any further temporal noise per pixel and frame, rms"),
      integer("adc_bits", "12").needed().at_least(1).at_most(32).described("ADC resolution (bits)"),
      integer("binning", "2").fallback("1").at_least(1).at_most(16)
          .described("b×b digital binning: b² native pixels summed, each with its own read noise"),
      integer("exposures", "4").fallback("1").at_least(1).at_most(1000000).described("frames co-added M"),
      integer("tdi_stages", "64").fallback("1").at_least(1).at_most(10000)
          .described("charge-domain TDI stages N: signal and dark × N, read noise once"),
      quantity("pixel_pitch", "m", "4.5 um").needed().above(0).described("native pixel pitch"),
      // Conventions of other tools, to reproduce their numbers (docs/validation.md); the defaults are EMVA 1288's
      // noise and the n_eff of the PSF as the pixels sample it.
      choice("noise_equivalent_area", {"pixel_sampled", "continuous"}).fallback("pixel_sampled")
          .described("n_eff of a Gaussian PSF (seeing, gaussian_fwhm, jitter): 1/Σf² on the pixel grid, or the "
                     "continuous 4πσ² = 2.266 (FWHM/p)² of LSST SMTN-002 and the ETCs built on it"),
      choice("quantisation", {"emva", "none"}).fallback("emva")
          .described("quantisation noise: EMVA 1288's 1/(12 K²) e-² per pixel (eq. 5), or none, as tools that model an "
                     "ideal ADC (m4opt, SMTN-002)"),
      choice("photometry", {"window", "circle", "psf"}).fallback("window")
          .described("window: n×n pixels with the PSF's ensquared energy; circle: a circular aperture of "
                     "aperture_radius with its encircled energy; psf: PSF-weighted, n_eff pixels"),
      quantity("aperture_radius", "rad", "1.5 arcsec").above(0).below(0.1)
          .described("radius R of the circular photometric aperture on the sky (photometry = \"circle\")"),
      quantity("jitter", "rad", "0.2 arcsec").fallback("0 rad").at_least(0).below(0.1)
          .described("rms line-of-sight jitter per axis during the exposure: a Gaussian blur added to the PSF"),
      integer("window_pixels", "3").fallback("1").at_least(1).at_most(1000)
          .described("side n of the n×n window in (binned) pixels (photometry = \"window\")"),
      number("ensquared_energy", "0.8").above(0).at_most(1)
          .described("fraction of the point image in the window (default: from the PSF, else 1)"),
      quantity("target_rate", "rad/s", "15 arcsec/s").at_least(0)
          .described("angular rate ω of a point target across the sky relative to the stars (a moving target streaks)"),
      choice("tracking", {"sidereal", "rate"}).fallback("sidereal")
          .described("sidereal: the telescope follows the stars and the target streaks; rate: it follows the "
                     "target, which stays a point while the stars streak"),
      quantity("reference_radiance", "W m-2 sr-1 m-1", "108 W m-2 sr-1 um-1").above(0)
          .described("extended scenes: band-averaged spectral radiance L_ref of the SNR requirement (mission "
                     "convention, e.g. Sentinel-2 L_ref; default: the scene's own radiance)"),
      number("reference_reflectance", "0.3").above(0).at_most(1)
          .described("extended scenes: L_ref as the reflectance of the target's scene (its sun angle, atmosphere)"),
  };
  return s;
}

class Emva1288 final : public Stage {
 public:
  // The flux enters linearly (the window's electrons, the peak pixel, the shot variance; PRNU's variance as its
  // square) beside terms it does not move (n_eff, the window, sky, dark, read): a magnitude solve may be inverted
  // in closed form. Not power_law(): n_eff and the ensquared energy are PSF integrals over the optics' f-number.
  bool power_law_in_signal() const override { return true; }

  explicit Emva1288(const Params& p)
      : params_(p), qe_(p.handle("qe")), time_(p.handle("integration_time")), gain_(p.handle("gain")),
        dark_noise_(p.handle("read_noise")), saturation_(p.handle("full_well")),
        dark_current_(p.handle("dark_current")), prnu_(p.handle("prnu")), dsnu_(p.handle("dsnu")),
        other_(p.handle("other_noise")), bits_(p.handle("adc_bits")), binning_(p.handle("binning")),
        exposures_(p.handle("exposures")), tdi_(p.handle("tdi_stages")), pitch_(p.handle("pixel_pitch")),
        window_(p.handle("window_pixels")), ensquared_(p.handle("ensquared_energy")),
        psf_photometry_(p.text("photometry") == "psf"), circle_photometry_(p.text("photometry") == "circle"),
        continuous_neff_(p.text("noise_equivalent_area") == "continuous"), quantisation_(p.text("quantisation") == "emva"),
        aperture_radius_(p.handle("aperture_radius")), jitter_(p.handle("jitter")), rate_(p.handle("target_rate")),
        moving_(p.given("target_rate")), rate_tracking_(p.text("tracking") == "rate"),
        reference_radiance_(p.handle("reference_radiance")),
        reference_reflectance_(p.handle("reference_reflectance")) {
    if (!(p.get("band_max") > p.get("band_min"))) p.reject("band_max", "must be larger than band_min");
    if (continuous_neff_ && moving_ && !rate_tracking_)
      p.reject("noise_equivalent_area", "\"continuous\" is the still Gaussian's n_eff; a streak's is taken on the pixel grid");
    if (psf_photometry_ && p.given("window_pixels"))
      p.reject("window_pixels", "is used only with photometry = \"window\" (PSF-weighted photometry uses n_eff pixels)");
    if (psf_photometry_ && p.given("ensquared_energy"))
      p.reject("ensquared_energy", "is used only with photometry = \"window\"");
    if (circle_photometry_) {
      for (const char* key : {"window_pixels", "ensquared_energy"})
        if (p.given(key)) p.reject(key, "is used only with photometry = \"window\" (a circle takes aperture_radius)");
      if (!p.given("aperture_radius")) p.reject("photometry", "photometry = \"circle\" needs aperture_radius");
    } else if (p.given("aperture_radius")) {
      p.reject("aperture_radius", "is used only with photometry = \"circle\"");
    }
    if (moving_ && !psf_photometry_)
      p.reject("target_rate", "a streak is measured by PSF-weighted photometry along it: set photometry = \"psf\"");
    if (moving_ && p.get("tdi_stages") > 1)
      p.reject("target_rate", "a moving target in a TDI camera is not modelled (give tdi_stages = 1)");
    if (p.given("tracking") && !moving_) p.reject("tracking", "needs the target's target_rate");
  }

  void prepare(Context& c) override {
    const Radiation& signal = c.light.signal;
    extended_ = signal.form == RadiationForm::focal_irradiance;
    if (signal.form != RadiationForm::focal_power && !extended_)
      c.refuse_form("a point image's power (a point target) or a focal-plane irradiance (an extended scene)", signal.form);
    if (!extended_) {
      for (const char* key : {"reference_radiance", "reference_reflectance"})
        if (params_.given(key)) params_.reject(key, "is used only for an extended scene (a ground target through optics)");
    }
    const double lo = params_.get("band_min"), hi = params_.get("band_max");
    const Spectrum* qe_curve = params_.has("qe_curve") ? &params_.spectrum("qe_curve") : nullptr;
    require_band_inside_own_table(params_, "qe_curve", lo, hi);
    require_band_inside_tables(params_, c.light, c.light.signal.spectrum, lo, hi);
    qe_components_ = declare_component_means(c, params_, "qe_curve", lo, hi);  // curve_components.hpp
    if (extended_) {
      prepare_extended(c, lo, hi, qe_curve);
      return;
    }
    if (!(*time_ > 0)) params_.reject("integration_time", "a point image needs the exposure of one frame, e.g. \"10 ms\"");
    // EMVA eq. 1 in spectral form: photoelectrons per second per unit signal scale.
    photon_rate_per_scale_ = physics::photon_rate(signal.spectrum, lo, hi, qe_curve);
    // AB magnitude 0 (flat f_ν of m_AB = −2.5 lg f_ν − 48.60, 3630.78 Jy: magnitudes.hpp, as the sky and the targets
    // use it) through this detector: n_λ = f_ν/(hλ), electrons s-1 m-2 (times qe).
    ab_electrons_per_m2_s_ = physics::photon_rate(physics::flat_f_nu_sed(), lo, hi, qe_curve);

    psf_wavelength_ = c.find(vocabulary::optics_psf_wavelength);
    gaussian_fwhm_ = c.find(vocabulary::optics_gaussian_fwhm);
    f_number_ = c.find(vocabulary::optics_f_number);
    obscuration_ = c.find(vocabulary::optics_obscuration);
    focal_length_ = c.find(vocabulary::optics_focal_length);
    aperture_ = c.find(vocabulary::optics_aperture);
    seeing_ = c.find(vocabulary::atmosphere_seeing_fwhm);
    band_magnitude_ = c.find(vocabulary::target_band_magnitude);
    if (band_magnitude_)
      id_zero_point_ = c.declare("instrumental_zero_point", "1",
                                 "m + 2.5 lg(S_img/(M N_tdi t)): the target-system magnitude giving 1 e-/s (SMTN-002)");
    const Radiation& background = c.light.background;
    has_sky_ = background.form != RadiationForm::none;
    if ((seeing_ || has_sky_) && !focal_length_)
      params_.reject("pixel_pitch", "the atmosphere gives seeing or sky brightness in angle: the optics need a "
                                    "focal_length to map it onto pixels");
    if (has_sky_ && background.form != RadiationForm::focal_irradiance)
      c.refuse_form("the sky as a focal-plane irradiance (a telescope with a focal_length)", background.form);
    // Electrons s-1 per m² of focal plane per unit background scale (before qe), as for an extended scene.
    if (has_sky_) sky_rate_per_scale_ = physics::photon_rate(background.spectrum, lo, hi, qe_curve);
    if ((psf_photometry_ || circle_photometry_) && !seeing_ && !gaussian_fwhm_ && !(psf_wavelength_ && f_number_))
      params_.reject("photometry", "photometry = \"" + params_.text("photometry") + "\" needs a PSF: seeing from the "
                                   "atmosphere or psf = \"airy\"/\"gaussian\" in the optics");
    for (const char* key : {"aperture_radius", "jitter"})
      if (params_.given(key) && !focal_length_)
        params_.reject(key, "an angle on the sky needs the optics' focal_length to give it on the pixels");
    if (moving_ && !focal_length_)
      params_.reject("target_rate", "a rate in angle needs the optics' focal_length to give the streak on the pixels");

    id_image_ = c.declare(vocabulary::detector_image_electrons, "S_img = M N_tdi t ∫ P_λ η λ/(hc) dλ (EMVA 1288 eq. 1)", "e-");
    id_signal_ = c.declare(vocabulary::detector_signal_electrons,
                           psf_photometry_ ? "S = S_img (PSF-weighted photometry)" : "S = EE × S_img in the n×n window", "e-");
    id_noise_ = c.declare(vocabulary::detector_noise_electrons,
                          "√(M (S₁ + n_pix v_t) + M² (n_pix v_s + s_g² S₁²/n_eff)) (EMVA 1288 eqs. 5, 6, 18)", "e-");
    id_snr_ = c.declare(vocabulary::detector_snr, "M S₁ / noise (EMVA 1288 eq. 6 over the photometric aperture)");
    id_time_ = c.declare(vocabulary::detector_integration_time, "input t", "s");
    id_pixels_ = c.declare(vocabulary::detector_window_pixel_count,
                           psf_photometry_      ? "n_eff (PSF-weighted photometry)"
                           : circle_photometry_ ? "π R²/(b p)²: the circular aperture's area in (binned) pixels"
                                                : "n² pixels of the window");
    id_ensquared_ = c.declare(vocabulary::detector_ensquared_energy,
                              psf_photometry_      ? "1 (PSF-weighted)"
                              : circle_photometry_ ? "EC(R): the PSF's encircled energy in the circular aperture"
                                                   : "EE of the PSF over the window (or input)");
    if (circle_photometry_)
      id_aperture_radius_ = c.declare(vocabulary::detector_aperture_radius_pixels, "R f' / (b p)");
    id_neff_ = c.declare(vocabulary::detector_noise_equivalent_area,
                         "n_eff = 1/Σ f_i² of the PSF on the (binned) pixel grid (King 1983; SMTN-002)");
    id_fill_ = c.declare(vocabulary::detector_peak_pixel_fill, "brightest native pixel / min(μ_e.sat, (2^bits−1)/K)", "%");
    id_peak_ = c.declare(vocabulary::detector_peak_pixel_electrons, "f_peak S_img,1 + N_tdi (B_native + μ_I t)", "e-");
    id_saturation_ = c.declare(vocabulary::detector_saturation_capacity, "min(μ_e.sat, (2^bits − 1)/K)", "e-");
    id_gain_ = c.declare(vocabulary::detector_system_gain, "input K", "DN/e-");
    id_tdi_ = c.declare(vocabulary::detector_tdi_stages, "input N_tdi");
    id_exposures_ = c.declare(vocabulary::detector_exposures, "input M");
    id_psf_weighted_ = c.declare(vocabulary::detector_psf_weighted, "photometry = \"psf\" (1) or a window or circle (0)");
    id_prnu_ = c.declare(vocabulary::detector_prnu, "input s_g", "%");
    id_dsnu_ = c.declare(vocabulary::detector_dsnu, "input σ_o", "e-");
    id_sky_ = c.declare(vocabulary::detector_sky_electrons_per_pixel,
                        "B = N_tdi b² t p² ∫ E'_λ,sky η λ/(hc) dλ (étendue) per binned pixel and frame", "e-");
    id_peak_fraction_ = c.declare("peak_pixel_fraction", "1", "fraction of the point image in the brightest native pixel");
    id_psf_fwhm_ = c.declare(vocabulary::detector_psf_fwhm,
                             "Gaussian PSF FWHM on the focal plane (seeing ⊕ diffraction ⊕ 2√(2 ln 2) σ_j f' jitter)", "um");
    id_quant_ = c.declare("quantisation_noise", "electron", "σ_q/K = 1/(√12 K) per pixel (EMVA eq. 5)", "e-");
    id_dark_ = c.declare("dark_electrons", "electron", "n_pix b² N_tdi μ_I t per frame", "e-");
    id_read_noise_ = c.declare("read_noise", "electron", "√(n_pix b² σ_d0²) per frame", "e-");
    id_background_ = c.declare("background_electrons", "electron", "n_pix × B per frame", "e-");
    id_shot_noise_ = c.declare("shot_noise", "electron", "√S over M frames", "e-");
    id_prnu_noise_ = c.declare("prnu_noise", "electron", "M s_g S₁/√(n_eff N_tdi)", "e-");
    // n² = M S₁ + Σ floor + prnu_noise², term by term (EMVA 1288 eqs. 6, 7 over the aperture's pixels).
    id_floor_sky_ = c.declare(vocabulary::detector_floor_variance_sky, "M n_pix b² N_tdi B");
    id_floor_dark_ = c.declare(vocabulary::detector_floor_variance_dark, "M n_pix b² N_tdi μ_I t");
    id_floor_read_ = c.declare(vocabulary::detector_floor_variance_read, "M n_pix b² (σ_d0² + σ_q²/K² + σ_other²)");
    id_floor_fixed_ = c.declare(vocabulary::detector_floor_variance_fixed_pattern, "M² n_pix b² σ_o²");
    id_ab_zero_ = c.declare("ab_zero_point_electron_rate", "m-2 s-1",
                            "electrons s-1 m-2 of AB magnitude 0 through the band and QE (before optics)", "cm-2 s-1");
    // What `radchain render` draws a frame with (docs/rendering.md): the pixel as read out, its read noise and dark.
    id_pitch_ = c.declare(vocabulary::detector_pixel_pitch, "b p: the (binned) pixel as read out", "um");
    id_bits_ = c.declare(vocabulary::detector_adc_bits, "input");
    id_dark_rate_ = c.declare(vocabulary::detector_dark_rate, "b² μ_I per (binned) pixel", "e-/s");
    id_read_pixel_ = c.declare(vocabulary::detector_read_noise_per_pixel, "b √(σ_d0² + σ_other²) per (binned) pixel", "e-");
    if (moving_) {
      id_target_streak_ = c.declare(vocabulary::detector_target_streak_pixels,
                                    rate_tracking_ ? "0: rate tracking holds the target still" : "ω t f' / (b p) (sidereal tracking)");
      id_star_streak_ = c.declare(vocabulary::detector_star_streak_pixels,
                                  rate_tracking_ ? "ω t f' / (b p) (rate tracking)" : "0: sidereal tracking holds the stars still");
      id_streak_angle_ = c.declare("streak_length", "rad", "ω t: the target's trail on the sky per exposure (0 under rate tracking)",
                                   "arcsec");
      id_static_neff_ = c.declare("static_noise_equivalent_area", "1", "n_eff of the PSF without the motion (physics/emva1288.hpp)");
      id_trailing_loss_ = c.declare(vocabulary::detector_trailing_loss,
                                    "1.25 lg(n_eff,streak / n_eff,static), background-limited (Jones et al. 2018)");
    }
  }

  void evaluate(Context& c) override {
    for (const ComponentMean& m : qe_components_) c.results.set(m.id, m.mean);
    if (extended_) {
      evaluate_extended(c);
      return;
    }
    ScalarAccess a(c);
    auto opt = [&](const std::optional<ResultId>& id) { return id ? a.value(*id) : 0.0; };
    const double t = *time_, qe = *qe_, gain = *gain_, pitch = *pitch_;
    const double b = *binning_, m = *exposures_, tdi = *tdi_;
    const double binned = b * pitch;
    // The PSF as a Gaussian FWHM on the focal plane when seeing, a Gaussian optics PSF or jitter is given.
    double fwhm = 0.0;
    const bool airy = psf_wavelength_ && f_number_;
    const double f = opt(focal_length_);
    const double jitter_fwhm = physics::gaussian_fwhm_from_sigma(*jitter_ * f);
    if (seeing_ || gaussian_fwhm_ || jitter_fwhm > 0) {
      double optics = opt(gaussian_fwhm_);
      if (airy) optics = physics::diffraction_fwhm_rad(a.value(*psf_wavelength_), 1.0) * a.value(*f_number_);
      const double seeing = seeing_ ? a.value(*seeing_) * f : 0.0;
      fwhm = std::hypot(std::hypot(seeing, optics), jitter_fwhm);
      // Seeing finer than the diffraction core is no atmosphere a site measures: most likely a delivered image
      // size that already includes the telescope, to which diffraction is added a second time here.
      if (seeing_ && airy && seeing < optics)
        c.warn(InputError({}, params_.context(), "atmosphere.seeing_fwhm",
                          fmt::format("the seeing {:.3g}\" is finer than the diffraction core {:.3g}\" (1.028 λ/D at "
                                      "{:.4g} nm): is it a delivered image size that already includes the optics?",
                                      seeing / f * 206264.806, optics / f * 206264.806, 1e9 * a.value(*psf_wavelength_))));
    }
    double neff = 1.0, peak_fraction = 1.0, ensquared = 1.0;
    const double n = *window_;
    const double radius_m = circle_photometry_ ? *aperture_radius_ * f : 0.0;
    if (fwhm > 0) {
      const GaussianIntegrals& g =
          gaussian_.of(fwhm, binned, pitch, circle_photometry_ ? -radius_m : n * binned, continuous_neff_);
      neff = g.neff, peak_fraction = g.peak_fraction, ensquared = g.ensquared;
    } else if (airy) {
      if (continuous_neff_)
        throw params_.problem("noise_equivalent_area", "\"continuous\" is a Gaussian PSF's n_eff (seeing, gaussian_fwhm or "
                                                       "jitter); an Airy PSF alone has only the pixel-sampled one");
      const double lambda = a.value(*psf_wavelength_), fn = a.value(*f_number_), eps = opt(obscuration_);
      peak_fraction = physics::airy_ensquared_energy(pitch, lambda, fn, eps);
      ensquared = circle_photometry_ ? physics::airy_encircled_energy(radius_m, lambda, fn, eps)
                                     : physics::airy_ensquared_energy(n * binned, lambda, fn, eps);
      neff = airy_noise_equivalent_area(binned, lambda, fn, eps);  // (binned: the b×b pixel's side)
    }
    if (params_.given("ensquared_energy")) ensquared = *ensquared_;
    if (psf_photometry_) ensquared = 1.0;
    // A moving target: the PSF (as the Gaussian of the n_eff above) convolved with its streak (physics/streak.hpp).
    const double static_neff = neff, streak_m = moving_ ? *rate_ * t * opt(focal_length_) : 0.0;
    if (moving_ && !rate_tracking_ && streak_m > 0) {
      const double psf = fwhm > 0 ? fwhm : physics::diffraction_fwhm_rad(a.value(*psf_wavelength_), 1.0) * a.value(*f_number_);
      neff = physics::streak_noise_equivalent_area_px(psf / binned, streak_m / binned);
      // An Airy core streaks as its Gaussian, scaled to the exact still n_eff and peak pixel: no jump at zero
      // length, and the trailing loss is the Gaussian model's.
      const double still_peak = peak_fraction;
      peak_fraction = physics::streak_peak_pixel_fraction(psf / pitch, streak_m / pitch);
      if (fwhm == 0) {
        neff *= static_neff / physics::gaussian_noise_equivalent_area_px(psf / binned);
        peak_fraction *= still_peak / physics::gaussian_peak_pixel_fraction(psf / pitch);
      }
    }

    const double image1 = a.signal_scale() * qe * photon_rate_per_scale_ * t * tdi;  // one frame, all pixels
    const double signal1 = ensquared * image1;
    double sky_native = 0.0;  // one native pixel, one TDI stage
    if (has_sky_) sky_native = t * qe * pitch * pitch * sky_rate_per_scale_ * a.background_scale();
    const double sky_binned = b * b * tdi * sky_native;
    const double dark_binned = b * b * tdi * *dark_current_ * t;
    const double quant_var = quantisation_ ? physics::emva_quantisation_variance_e2(gain) : 0.0;
    const double read_var_binned = b * b * (*dark_noise_ * *dark_noise_ + quant_var + *other_ * *other_);
    const double circle_pixels = std::numbers::pi * radius_m * radius_m / (binned * binned);
    const double pixels = psf_photometry_ ? neff : circle_photometry_ ? circle_pixels : n * n;
    const double temporal = m * (signal1 + pixels * (sky_binned + dark_binned + read_var_binned));
    // The point image's N_tdi stages are N_tdi different pixel rows: their gains average as for binning.
    // PRNU is a property of each native pixel: a binned pixel sums b² of them, each with a gain of its own, so the
    // PSF-weighted sum runs over native pixels, s_g² S²/n_eff,native (the same point image's n_eff at the native pitch;
    // a streak keeps its ratio to the still image's). 1 × 1 binning: the n_eff above.
    double prnu_neff = neff;
    if (b > 1 && *prnu_ > 0 && (fwhm > 0 || airy)) {
      const double native = fwhm > 0 ? (continuous_neff_ ? physics::gaussian_continuous_noise_equivalent_area_px(fwhm / pitch)
                                                         : physics::gaussian_noise_equivalent_area_px(fwhm / pitch))
                                     : native_airy_neff_.of(pitch, a.value(*psf_wavelength_), a.value(*f_number_), opt(obscuration_));
      prnu_neff = native * neff / static_neff;
    }
    const double prnu_amp = m * *prnu_ * signal1 / std::sqrt(prnu_neff * tdi);
    const double spatial = m * m * pixels * b * b * *dsnu_ * *dsnu_ + prnu_amp * prnu_amp;
    const double noise = std::sqrt(temporal + spatial);
    const double signal = m * signal1;

    const double levels = static_cast<double>(std::uint64_t{1} << static_cast<int>(*bits_));
    const double capacity = std::min(*saturation_, (levels - 1.0) / gain);
    const double peak = peak_fraction * image1 + tdi * (sky_native + *dark_current_ * t);

    a.set(id_signal_, signal);
    a.set(id_noise_, noise);
    a.set(id_snr_, signal / noise);
    a.set(id_time_, t);
    a.set(id_fill_, peak / capacity);
    a.set(id_peak_, peak);
    a.set(id_saturation_, capacity);
    a.set(id_sky_, sky_binned);
    a.set(id_pixels_, pixels);
    a.set(id_neff_, neff);
    a.set(id_pitch_, binned);
    a.set(id_bits_, *bits_);
    a.set(id_dark_rate_, b * b * *dark_current_);
    a.set(id_read_pixel_, b * std::hypot(*dark_noise_, *other_));
    if (moving_) {
      a.set(id_target_streak_, rate_tracking_ ? 0.0 : streak_m / binned);
      a.set(id_star_streak_, rate_tracking_ ? streak_m / binned : 0.0);
      a.set(id_streak_angle_, rate_tracking_ ? 0.0 : *rate_ * t);
      a.set(id_static_neff_, static_neff);
      a.set(id_trailing_loss_, physics::trailing_loss_mag(neff, static_neff));
    }
    if (!a.full_detail()) return;
    a.set(id_image_, m * image1);
    a.set(id_ensquared_, ensquared);
    a.set(id_gain_, gain);
    a.set(id_tdi_, tdi);
    a.set(id_exposures_, m);
    a.set(id_psf_weighted_, psf_photometry_ ? 1.0 : 0.0);
    a.set(id_prnu_, *prnu_);
    a.set(id_dsnu_, *dsnu_);
    a.set(id_peak_fraction_, peak_fraction);
    a.set(id_psf_fwhm_, fwhm);
    if (circle_photometry_) a.set(id_aperture_radius_, radius_m / binned);
    a.set(id_quant_, std::sqrt(quant_var));
    a.set(id_dark_, pixels * dark_binned);
    a.set(id_read_noise_, std::sqrt(pixels * b * b) * *dark_noise_);
    a.set(id_background_, pixels * sky_binned);
    a.set(id_shot_noise_, std::sqrt(signal));
    a.set(id_prnu_noise_, prnu_amp);
    a.set(id_floor_sky_, m * pixels * sky_binned);
    a.set(id_floor_dark_, m * pixels * dark_binned);
    a.set(id_floor_read_, m * pixels * read_var_binned);
    a.set(id_floor_fixed_, m * m * pixels * b * b * *dsnu_ * *dsnu_);
    a.set(id_ab_zero_, ab_electrons_per_m2_s_ * qe);  // the scalar η multiplies any qe_curve, as for the target
    if (band_magnitude_) a.set(*id_zero_point_, a.value(*band_magnitude_) + 2.5 * std::log10(image1 / (tdi * t)));
  }

 private:
  // ---- extended scenes ----
  void prepare_extended(Context& c, double lo, double hi, const Spectrum* qe_curve) {
    for (const char* key : {"window_pixels", "ensquared_energy", "photometry", "aperture_radius", "jitter"})
      if (params_.given(key)) params_.reject(key, "is used only for a point image (the target here is an extended scene)");
    if (params_.given("reference_radiance") && params_.given("reference_reflectance"))
      params_.reject("reference_reflectance", "give the reference as reference_radiance or as reference_reflectance, not both");
    // Electrons s-1 per m² of focal plane per unit signal scale (EMVA §2.1 and eq. 1 in spectral form, before qe).
    photon_rate_per_scale_ = physics::photon_rate(c.light.signal.spectrum, lo, hi, qe_curve);
    // ∫_band η(λ) λ/(hc) dλ: electrons s-1 m-2 of a flat 1 W m-2 m-1 (before qe and the étendue).
    const Spectrum flat = Spectrum::sampled(Eigen::ArrayXd::LinSpaced(2001, lo, hi), [](double) { return 1.0; },
                                            "W m-2 m-1");
    flat_photon_integral_ = physics::photon_rate(flat, lo, hi, qe_curve);
    // The atmosphere's path radiance L_path,λ (W m-2 sr-1 m-1), already at the sensor: added to the scene's radiance
    // (L = τ↑ ρ E cos θ_s τ↓/π + L_path, Schott 2007 §4.1) and counted by the same étendue; ∫ L_path η λ/(hc) dλ here.
    path_photon_rate_ = c.light.path_radiance.empty() ? 0.0 : physics::photon_rate(c.light.path_radiance, lo, hi, qe_curve);
    f_number_ = c.find(vocabulary::optics_f_number);
    obscuration_ = c.find(vocabulary::optics_obscuration);
    transmittance_ = c.find(vocabulary::optics_transmittance);
    if (!f_number_)
      params_.reject("pixel_pitch", "an extended scene needs the optics' f-number (a telescope with a focal_length)");
    reflectance_ = c.find(vocabulary::target_reflectance);
    if (params_.given("reference_reflectance") && !reflectance_)
      params_.reject("reference_reflectance", "needs a reflectance target (target plugin \"reflectance_ground\")");
    reference_given_ = params_.given("reference_radiance");
    reference_from_reflectance_ = params_.given("reference_reflectance");
    const char* ref_how = params_.given("reference_radiance")      ? "input L_ref"
                          : params_.given("reference_reflectance") ? "ρ_ref × L̄_surface / ρ + L̄_path (the target's sun and atmosphere)"
                                                                   : "L̄_scene (no reference given: the scene itself)";

    id_signal_ = c.declare(vocabulary::detector_signal_electrons,
                           "M b² N_tdi t p² ∫ E'_λ η λ/(hc) dλ: the scene in one (binned) pixel (EMVA §2.1, eq. 1)", "e-");
    id_noise_ = c.declare(vocabulary::detector_noise_electrons,
                          "√(M (S₁ + b² v_t) + M² (b² σ_o² + s_g² S₁²/(b² N_tdi))) (EMVA 1288 eqs. 5, 6, 18)", "e-");
    id_snr_ = c.declare(vocabulary::detector_snr, "M S₁ / noise: the scene's pixel (EMVA 1288 eq. 6)");
    // Stated once: without an integration time of its own, a pushbroom integrates for its line time, the time the
    // ground takes to move one along-track GSD (physics/earth_geometry.hpp, line_time_s) at the platform's look.
    line_time_ = !(*time_ > 0);
    if (line_time_) {
      ground_speed_ = c.find(vocabulary::platform_ground_speed);
      if (!ground_speed_)
        params_.reject("integration_time", "no integration time: give one, or an orbiting platform (plugin "
                                           "\"earth_orbit\") whose ground speed sets the line time");
      look_.find(c, params_, "integration_time", true);
    }
    id_time_ = c.declare(vocabulary::detector_integration_time,
                         line_time_ ? "t = GSD_along / ground speed: the line time (no integration_time given)"
                                    : "input t (line or frame time of one TDI stage)",
                         "s");
    id_fill_ = c.declare(vocabulary::detector_peak_pixel_fill, "scene pixel (μ_e + N_tdi μ_I t) / min(μ_e.sat, (2^bits−1)/K)",
                         "%");
    id_peak_ = c.declare(vocabulary::detector_peak_pixel_electrons, "μ_e + N_tdi μ_I t of one native pixel, one exposure",
                         "e-");
    id_saturation_ = c.declare(vocabulary::detector_saturation_capacity, "min(μ_e.sat, (2^bits − 1)/K)", "e-");
    id_gain_ = c.declare(vocabulary::detector_system_gain, "input K", "DN/e-");
    id_tdi_ = c.declare(vocabulary::detector_tdi_stages, "input N_tdi");
    id_pitch_ = c.declare(vocabulary::detector_pixel_pitch, "input p (native)", "um");
    id_scene_radiance_ = c.declare(vocabulary::detector_scene_radiance,
                                   "L̄ = μ_e / k: the scene's band-averaged at-aperture radiance", "W m-2 sr-1 um-1");
    id_reference_radiance_ = c.declare(vocabulary::detector_reference_radiance, ref_how, "W m-2 sr-1 um-1");
    id_reference_signal_ = c.declare(vocabulary::detector_reference_signal_electrons,
                                     "M b² k L_ref (k = N_tdi t p² Ω τ ∫ η λ/(hc) dλ)", "e-");
    id_reference_snr_ = c.declare(vocabulary::detector_snr_at_reference,
                                  "M S₁(L_ref) / noise(L_ref) (EMVA 1288 eq. 6; mission convention: SNR at L_ref)");
    id_nedl_ = c.declare(vocabulary::detector_noise_equivalent_radiance, "noise(L_ref) / (dS/dL) = L_ref / SNR_ref",
                         "W m-2 sr-1 um-1");
    if (reflectance_)
      id_nedrho_ = c.declare(vocabulary::detector_noise_equivalent_reflectance,
                             "noise(L_ref) / (dS/dρ) = noise(L_ref) ρ / S_surface (at the target's sun angle)");
    id_path_electrons_ = c.declare(vocabulary::detector_path_radiance_electrons,
                                   "M b² k L̄_path: the atmosphere's path radiance in the scene's pixel (0 without one)", "e-");
    // What `render` draws the scene with (radchain/imaging/earth_scene.hpp): the ADC, dark, read and fixed-pattern noise.
    id_bits_ = c.declare(vocabulary::detector_adc_bits, "input");
    id_dark_rate_ = c.declare(vocabulary::detector_dark_rate, "b² μ_I per (binned) pixel", "e-/s");
    id_read_pixel_ = c.declare(vocabulary::detector_read_noise_per_pixel, "b √(σ_d0² + σ_other²) per (binned) pixel", "e-");
    id_binning_ = c.declare(vocabulary::detector_binning, "input b");
    id_exposures_ = c.declare(vocabulary::detector_exposures, "input M");
    id_prnu_ = c.declare(vocabulary::detector_prnu, "input s_g", "%");
    id_dsnu_ = c.declare(vocabulary::detector_dsnu, "input σ_o", "e-");
    id_saturation_radiance_ = c.declare(vocabulary::detector_saturation_radiance,
                                        "(min(μ_e.sat, (2^bits−1)/K) − N_tdi μ_I t) / k", "W m-2 sr-1 um-1");
    id_solid_angle_ = c.declare("pixel_solid_angle", "sr", "Ω = π (1 − ε²) / (4 N²): A_pixel Ω = A_pupil IFOV²");
    id_etendue_ = c.declare("pixel_etendue", "m2 sr", "A_pixel Ω = p² π (1 − ε²) / (4 N²)", "um2 sr");
    id_responsivity_ = c.declare("radiance_responsivity", "electron m2 sr m W-1",
                                 "k: electrons of one native pixel per exposure per unit band-averaged radiance",
                                 "e- / (W m-2 sr-1 um-1)");
    id_qe_integral_ = c.declare("qe_photon_integral", "m2 W-1 s-1",
                                "qe ∫_band η(λ) λ/(hc) dλ (electrons s-1 per W m-2 m-1 of a flat spectrum)");
    id_quant_ = c.declare("quantisation_noise", "electron", "σ_q/K = 1/(√12 K) per pixel (EMVA eq. 5)", "e-");
    id_dark_ = c.declare("dark_electrons", "electron", "b² N_tdi μ_I t per frame", "e-");
    id_read_noise_ = c.declare("read_noise", "electron", "√(b² σ_d0²) per frame", "e-");
    id_shot_noise_ = c.declare("shot_noise", "electron", "√S over M frames", "e-");
    id_prnu_noise_ = c.declare("prnu_noise", "electron", "M s_g S₁ / (b √N_tdi)", "e-");
    // n² = M S₁ + Σ floor + prnu_noise², term by term (EMVA 1288 eqs. 6, 7 for one (binned) pixel).
    id_floor_dark_ = c.declare(vocabulary::detector_floor_variance_dark, "M b² N_tdi μ_I t");
    id_floor_read_ = c.declare(vocabulary::detector_floor_variance_read, "M b² (σ_d0² + σ_q²/K² + σ_other²)");
    id_floor_fixed_ = c.declare(vocabulary::detector_floor_variance_fixed_pattern, "M² b² σ_o²");
    id_reference_noise_ = c.declare("reference_noise_electrons", "electron", "noise at L_ref", "e-");
    id_dynamic_range_ = c.declare("dynamic_range", "1", "L_sat / NEΔL(L→0): saturation over the dark noise floor");
  }

  void evaluate_extended(Context& c) {
    ScalarAccess a(c);
    // (A sweep may set a time where the file gave none: a positive value is used as given.)
    if (!(*time_ > 0) && !line_time_)
      params_.reject("integration_time", "0 s: no platform here sets the line time; give the integration time");
    const double t = *time_ > 0 ? *time_ : line_time(c.results);
    const double qe = *qe_, gain = *gain_, pitch = *pitch_;
    const double b = *binning_, m = *exposures_, tdi = *tdi_;
    const double omega = physics::pixel_projected_solid_angle_sr(a.value(*f_number_),
                                                                 obscuration_ ? a.value(*obscuration_) : 0.0);
    const double tau = transmittance_ ? a.value(*transmittance_) : 1.0;
    const double k = physics::radiance_responsivity_e(tdi, t, pitch, omega, tau, qe * flat_photon_integral_);
    // The scene: one native pixel, one exposure (the focal irradiance already carries Ω τ): the surface's light
    // plus the path radiance, which reaches the pupil as a radiance and is counted by the étendue A_pixel Ω τ.
    const double surface_native = a.signal_scale() * qe * photon_rate_per_scale_ * t * tdi * pitch * pitch;
    const double path_native = physics::radiance_responsivity_e(tdi, t, pitch, omega, tau, qe * path_photon_rate_);
    const double scene_native = surface_native + path_native;
    const double scene_radiance = scene_native / k;
    double reference = scene_radiance;
    if (reference_given_) reference = *reference_radiance_;
    else if (reference_from_reflectance_)
      reference = (*reference_reflectance_ * surface_native / a.value(*reflectance_) + path_native) / k;

    const double dark_native = tdi * *dark_current_ * t;
    const double quant_var = quantisation_ ? physics::emva_quantisation_variance_e2(gain) : 0.0;
    const double floor_native = *dark_noise_ * *dark_noise_ + quant_var + *other_ * *other_ + dark_native;
    auto noise_of = [&](double signal1) {
      return std::sqrt(physics::emva_uniform_scene_variance_e2(signal1, floor_native, *dsnu_, *prnu_, b, m, tdi));
    };
    const double signal1 = b * b * scene_native, reference1 = b * b * k * reference;
    const double noise = noise_of(signal1), reference_noise = noise_of(reference1);

    const double levels = static_cast<double>(std::uint64_t{1} << static_cast<int>(*bits_));
    const double capacity = std::min(*saturation_, (levels - 1.0) / gain);
    const double saturation_radiance = physics::saturation_radiance(capacity, dark_native, k);

    a.set(id_signal_, m * signal1);
    a.set(id_noise_, noise);
    a.set(id_snr_, m * signal1 / noise);
    a.set(id_time_, t);
    a.set(id_fill_, (scene_native + dark_native) / capacity);
    a.set(id_peak_, scene_native + dark_native);
    a.set(id_saturation_, capacity);
    a.set(id_scene_radiance_, scene_radiance);
    a.set(id_reference_radiance_, reference);
    a.set(id_reference_signal_, m * reference1);
    a.set(id_reference_snr_, m * reference1 / reference_noise);
    a.set(id_nedl_, reference_noise / (m * b * b * k));
    // dS/dρ = S_surface/ρ: the path radiance does not change with the ground's reflectance.
    if (id_nedrho_) a.set(*id_nedrho_, reference_noise * a.value(*reflectance_) / (m * b * b * surface_native));
    a.set(id_path_electrons_, m * b * b * path_native);
    a.set(id_saturation_radiance_, saturation_radiance);
    a.set(id_bits_, *bits_);
    a.set(id_dark_rate_, b * b * *dark_current_);
    a.set(id_read_pixel_, b * std::hypot(*dark_noise_, *other_));
    a.set(id_binning_, b);
    a.set(id_exposures_, m);
    a.set(id_prnu_, *prnu_);
    a.set(id_dsnu_, *dsnu_);
    if (!a.full_detail()) return;
    a.set(id_gain_, gain);
    a.set(id_tdi_, tdi);
    a.set(id_pitch_, pitch);
    a.set(id_solid_angle_, omega);
    a.set(id_etendue_, pitch * pitch * omega);
    a.set(id_responsivity_, k);
    a.set(id_qe_integral_, qe * flat_photon_integral_);
    a.set(id_quant_, std::sqrt(quant_var));
    a.set(id_dark_, b * b * dark_native);
    a.set(id_read_noise_, b * *dark_noise_);
    a.set(id_shot_noise_, std::sqrt(m * signal1));
    a.set(id_prnu_noise_, m * *prnu_ * signal1 / (b * std::sqrt(tdi)));
    a.set(id_floor_dark_, m * b * b * dark_native);
    a.set(id_floor_read_, m * b * b * (*dark_noise_ * *dark_noise_ + quant_var + *other_ * *other_));
    a.set(id_floor_fixed_, m * m * b * b * *dsnu_ * *dsnu_);
    a.set(id_reference_noise_, reference_noise);
    a.set(id_dynamic_range_, saturation_radiance * m * b * b * k / noise_of(0.0));
  }

  // The along-track GSD over the ground speed at the platform's look (spherical Earth), the native pixel's.
  double line_time(const Results& results) const {
    const Look look = look_.read(results);
    const double along = physics::gsd_along_track_m(look.altitude_m, look.roll_rad, look.pitch_rad,
                                                    look.pixel_pitch_m / look.focal_length_m, look.earth_radius_m);
    return physics::line_time_s(along, results.value(*ground_speed_));
  }

  const Params& params_;
  bool line_time_ = false;
  LookTerms look_;
  std::optional<ResultId> ground_speed_;
  // n_eff of the pixel-sampled Airy pattern (King 1983; physics::airy_noise_equivalent_area_px), remembered for the
  // last sampling: it depends on nothing else, and its pixel sum at a coarse pitch takes milliseconds.
  struct AiryNeff {
    double of(double pitch_m, double wavelength_m, double f_number, double obscuration) {
      const std::array<double, 4> key{pitch_m, wavelength_m, f_number, obscuration};
      if (key != key_) {
        value_ = physics::airy_noise_equivalent_area_px(pitch_m, wavelength_m, f_number, obscuration);
        key_ = key;  // (after: a throw leaves no stale value under this key)
      }
      return value_;
    }
    std::array<double, 4> key_{};
    double value_ = 0.0;
  };
  double airy_noise_equivalent_area(double pitch_m, double wavelength_m, double f_number, double obscuration) {
    return airy_neff_.of(pitch_m, wavelength_m, f_number, obscuration);
  }
  AiryNeff airy_neff_, native_airy_neff_;  // at the binned pitch (photometry) and the native one (PRNU)
  // The pixel-sampled Gaussian PSF's integrals, remembered for the last PSF and sampling: a sweep over exposure, sky
  // or airmass does not change them, and their erf sums were two thirds of such a point's cost. `aperture` is the
  // window's side, or minus the circle's radius.
  struct GaussianIntegrals {
    double neff = 0, peak_fraction = 0, ensquared = 0;
  };
  struct GaussianMemo {
    const GaussianIntegrals& of(double fwhm_m, double binned_m, double pitch_m, double aperture_m, bool continuous) {
      const std::array<double, 4> key{fwhm_m, binned_m, pitch_m, aperture_m};
      if (key != key_ || !valid_) {
        value_.neff = continuous ? physics::gaussian_continuous_noise_equivalent_area_px(fwhm_m / binned_m)
                                 : physics::gaussian_noise_equivalent_area_px(fwhm_m / binned_m);
        value_.peak_fraction = physics::gaussian_peak_pixel_fraction(fwhm_m / pitch_m);
        value_.ensquared = aperture_m < 0 ? physics::gaussian_encircled_energy(-aperture_m, fwhm_m)
                                          : physics::gaussian_ensquared_energy(aperture_m, fwhm_m);
        key_ = key;
        valid_ = true;
      }
      return value_;
    }
    std::array<double, 4> key_{};
    bool valid_ = false;
    GaussianIntegrals value_;
  };
  GaussianMemo gaussian_;

  const double *qe_, *time_, *gain_, *dark_noise_, *saturation_, *dark_current_, *prnu_, *dsnu_, *other_, *bits_,
      *binning_, *exposures_, *tdi_, *pitch_, *window_, *ensquared_;
  bool psf_photometry_, circle_photometry_, continuous_neff_, quantisation_;
  std::vector<ComponentMean> qe_components_;
  const double *aperture_radius_, *jitter_, *rate_;
  bool moving_, rate_tracking_;
  ResultId id_bits_{}, id_dark_rate_{}, id_read_pixel_{}, id_target_streak_{}, id_star_streak_{}, id_streak_angle_{}, id_static_neff_{}, id_trailing_loss_{};
  bool extended_ = false, reference_given_ = false, reference_from_reflectance_ = false;
  const double *reference_radiance_, *reference_reflectance_;
  double photon_rate_per_scale_ = 0, ab_electrons_per_m2_s_ = 0, flat_photon_integral_ = 0, path_photon_rate_ = 0;
  ResultId id_path_electrons_{}, id_binning_{}, id_exposures_{}, id_prnu_{}, id_dsnu_{};
  ResultId id_psf_weighted_{};
  std::optional<ResultId> reflectance_, id_nedrho_;
  ResultId id_pitch_{}, id_scene_radiance_{}, id_reference_radiance_{}, id_reference_signal_{}, id_reference_snr_{},
      id_nedl_{}, id_saturation_radiance_{}, id_solid_angle_{}, id_etendue_{}, id_responsivity_{}, id_qe_integral_{},
      id_reference_noise_{}, id_dynamic_range_{};
  std::optional<ResultId> psf_wavelength_, gaussian_fwhm_, f_number_, obscuration_, focal_length_, aperture_,
      transmittance_, seeing_, band_magnitude_, id_zero_point_;
  bool has_sky_ = false;
  double sky_rate_per_scale_ = 0;  // electrons s-1 m-2 of focal plane per unit background scale, before qe
  ResultId id_image_{}, id_signal_{}, id_noise_{}, id_snr_{}, id_time_{}, id_pixels_{}, id_ensquared_{}, id_neff_{},
      id_fill_{}, id_peak_{}, id_saturation_{}, id_gain_{}, id_tdi_{}, id_sky_{}, id_peak_fraction_{}, id_psf_fwhm_{},
      id_quant_{}, id_dark_{}, id_read_noise_{}, id_background_{}, id_shot_noise_{}, id_prnu_noise_{}, id_ab_zero_{},
      id_aperture_radius_{}, id_floor_sky_{}, id_floor_dark_{}, id_floor_read_{}, id_floor_fixed_{};
};

}  // namespace

RADCHAIN_PLUGIN(Emva1288, {
    .summary = "CMOS/CCD camera from its EMVA 1288 datasheet: gain, dark noise, DSNU/PRNU, saturation, binning, "
               "co-added frames, TDI; window or PSF-weighted (n_eff) photometry; sky by étendue; extended scenes "
               "by étendue: SNR at L_ref, NEΔL, NEΔρ, saturation radiance",
    .reference = "EMVA Standard 1288 Release 4.0 Linear (2021) eqs. 1-6, 18, 29; King 1983 (n_eff); LSST SMTN-002; "
                 "SNR at L_ref per band: ESA Sentinel-2 User Handbook (2015)",
    .schema = schema,
    .publishes = {vocabulary::detector_signal_electrons, vocabulary::detector_image_electrons,
                  vocabulary::detector_noise_electrons, vocabulary::detector_snr, vocabulary::detector_integration_time,
                  vocabulary::detector_window_pixel_count, vocabulary::detector_ensquared_energy,
                  vocabulary::detector_aperture_radius_pixels, vocabulary::detector_sky_electrons_per_pixel,
                  vocabulary::detector_peak_pixel_fill, vocabulary::detector_peak_pixel_electrons, vocabulary::detector_saturation_capacity,
                  vocabulary::detector_noise_equivalent_area, vocabulary::detector_system_gain,
                  vocabulary::detector_tdi_stages, vocabulary::detector_pixel_pitch, vocabulary::detector_scene_radiance,
                  vocabulary::detector_reference_radiance, vocabulary::detector_reference_signal_electrons,
                  vocabulary::detector_snr_at_reference, vocabulary::detector_noise_equivalent_radiance,
                  vocabulary::detector_noise_equivalent_reflectance, vocabulary::detector_saturation_radiance,
                  vocabulary::detector_target_streak_pixels, vocabulary::detector_star_streak_pixels,
                  vocabulary::detector_trailing_loss, vocabulary::detector_psf_fwhm, vocabulary::detector_adc_bits,
                  vocabulary::detector_dark_rate, vocabulary::detector_read_noise_per_pixel,
                  vocabulary::detector_path_radiance_electrons, vocabulary::detector_binning,
                  vocabulary::detector_exposures, vocabulary::detector_prnu, vocabulary::detector_dsnu,
                  vocabulary::detector_psf_weighted, vocabulary::detector_floor_variance_sky,
                  vocabulary::detector_floor_variance_dark, vocabulary::detector_floor_variance_read,
                  vocabulary::detector_floor_variance_fixed_pattern},
    .needs = {if_present(vocabulary::optics_psf_wavelength), if_present(vocabulary::optics_gaussian_fwhm),
              if_present(vocabulary::optics_f_number), if_present(vocabulary::optics_obscuration),
              if_present(vocabulary::optics_focal_length), if_present(vocabulary::optics_aperture),
              if_present(vocabulary::optics_collecting_area), if_present(vocabulary::optics_transmittance),
              if_present(vocabulary::atmosphere_seeing_fwhm), if_present(vocabulary::atmosphere_sky_brightness),
              if_present(vocabulary::target_band_magnitude), if_present(vocabulary::target_reflectance),
              if_present(vocabulary::platform_altitude), if_present(vocabulary::platform_tilt),
              if_present(vocabulary::platform_roll), if_present(vocabulary::platform_pitch),
              if_present(vocabulary::platform_earth_radius), if_present(vocabulary::platform_ground_speed)},
})

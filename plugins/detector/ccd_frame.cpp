// A frame-transfer CCD counting a point object's photoelectrons in one frame, with its noise budget.
//   image    S_img = t ∫_{λ1}^{λ2} P_λ η(λ) λ/(h c) dλ                (Pan 2010 eqs. 6-8)
//   signal   S = EE · S_img   in a centred n×n detection window      (Pan: EE = 1, n = 1)
//   noise    n² = N_d + n²σ_o² + n² n_q² + B + S                     (Pan 2010 eq. 9, plus the sky B)
//   N_d = n² × dark rate × t (Poisson);  σ_o read noise per pixel;  shot noise √S;  background √B
//   n_q²: "emva" (n_well/2^N)²/12  (EMVA 1288 linear camera model, σ_q² = 1/12 DN²; a uniform quantiser of step n_well/2^N)
//         "paper" n_well/(2^N √12)   (as printed in Pan 2010, §3.2; see docs/physics/quantisation.md)
// Beyond the paper (docs/physics/ensquared-energy-and-background.md):
//   EE   the fraction of the point image inside the window: `ensquared_energy` as given, else from the optics'
//        PSF (optics.psf_wavelength → Airy, optics.gaussian_fwhm → Gaussian) over a square of side n × pitch,
//        else 1 (the paper's assumption);
//   B    sky background (zodiacal light + unresolved stars) of `sky_brightness` V mag/arcsec², solar spectrum:
//        a source of magnitude m gives S(m) electrons, so B = n² · S(m_sky) · Ω_pixel/arcsec², Ω_pixel = (pitch/f')².
#include "radchain/physics/photometry.hpp"
#include "radchain/physics/psf.hpp"
#include "radchain/plugin.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>

namespace {
using namespace radchain;

constexpr double arcsec_per_rad = 180.0 * 3600.0 / std::numbers::pi;

const Schema& schema() {
  static const Schema s = {
      number("qe", "0.27").fallback("1").above(0).at_most(1)
          .described("mean quantum efficiency η (multiplies any qe_curve)"),
      spectrum_file("qe_curve", "1", "ccd_back_illuminated_hamamatsu_S10420-01_qe.csv")
          .described("spectral quantum efficiency η(λ) (optional)"),
      quantity("band_min", "m", "0.3 um").needed().above(0).affects_spectrum().described("detector band lower limit λ1"),
      quantity("band_max", "m", "0.9 um").needed().above(0).affects_spectrum().described("detector band upper limit λ2"),
      quantity("integration_time", "s", "0.625 s").needed().above(0).scales(Scaling::power_law).described("frame integration time t"),
      quantity("full_well", "electron", "1e5 e-").needed().above(0).described("potential well depth n_well"),
      integer("adc_bits", "12").needed().at_least(1).at_most(32).described("ADC resolution N (bits)"),
      quantity("dark_current", "electron/s", "18 e-/s").fallback("0 e-/s").at_least(0).formerly("dark_rate")
          .described("dark current per pixel at the operating temperature"),
      quantity("read_noise", "electron", "6 e-").fallback("0 e-").at_least(0).described("output amplifier noise σ_o (rms)"),
      choice("quantisation", {"emva", "paper"}).fallback("emva")
          .described("quantisation noise form: EMVA 1288 (n_well/2^N)²/12, or Pan 2010 as printed n_well/(2^N √12)"),
      quantity("pixel_pitch", "m", "15 um").above(0)
          .described("pixel pitch (needed for an ensquared energy from the optics PSF and for sky_brightness)"),
      integer("window_pixels", "3").fallback("1").at_least(1).at_most(1000)
          .described("side n of the n×n detection window; dark, read, quantisation and sky noise add over n² pixels"),
      number("ensquared_energy", "0.8").above(0).at_most(1)
          .described("fraction of the point image in the window (default: from the optics PSF if any, else 1 as in Pan 2010)"),
      number("sky_brightness", "22.5").at_least(-10).at_most(40).scales(Scaling::magnitude)
          .described("sky background in V mag/arcsec² (zodiacal light + unresolved stars; 22-23 in space); default none"),
  };
  return s;
}

class CcdFrame final : public LaneStage<CcdFrame> {
  friend class LaneStage<CcdFrame>;  // calls compute()

 public:
  // Signal, sky, dark ∝ their factors; read and quantisation constant. An Airy PSF's ensquared energy depends on
  // the f-number: not a power law of D or f' then.
  bool power_law() const override { return ensquared_entry_.present || !psf_wavelength_; }
  // The ensquared energy does not depend on the flux: a magnitude solve is a power law through the frame.
  bool power_law_in_signal() const override { return true; }

  explicit CcdFrame(const Params& p)
      : params_(p), qe_(p.handle("qe")), time_(p.handle("integration_time")), well_(p.handle("full_well")),
        bits_(p.handle("adc_bits")), dark_(p.handle("dark_current")), read_(p.handle("read_noise")),
        pitch_(p.handle("pixel_pitch")), window_(p.handle("window_pixels")), ensquared_(p.handle("ensquared_energy")),
        sky_(p.handle("sky_brightness")), pitch_entry_(p.entry("pixel_pitch")),
        ensquared_entry_(p.entry("ensquared_energy")), sky_entry_(p.entry("sky_brightness")),
        paper_quantisation_(p.text("quantisation") == "paper") {
    if (!(p.get("band_max") > p.get("band_min"))) p.reject("band_max", "must be larger than band_min");
  }

  void prepare(Context& c) override {
    const Radiation& signal = c.light.signal;
    if (signal.form != RadiationForm::focal_power) c.refuse_form("a point image's power (a point target)", signal.form);
    const double lo = params_.get("band_min"), hi = params_.get("band_max");
    band_min_ = lo, band_max_ = hi;
    require_band_inside_tables(params_, c.light, signal.spectrum, lo, hi);
    require_band_inside_own_table(params_, "qe_curve", lo, hi);
    // Spectral phase: photons per second per unit signal scale, QE curve included (Pan eqs. 6-7).
    photon_rate_per_scale_ = physics::photon_rate(signal.spectrum, lo, hi,
                                                  params_.has("qe_curve") ? &params_.spectrum("qe_curve") : nullptr);

    // The optics' PSF, found by name (telescope: psf = "airy" / "gaussian").
    psf_wavelength_ = c.find(vocabulary::optics_psf_wavelength);
    gaussian_fwhm_ = c.find(vocabulary::optics_gaussian_fwhm);
    f_number_ = c.find(vocabulary::optics_f_number);
    obscuration_ = c.find(vocabulary::optics_obscuration);
    const bool psf = (psf_wavelength_ && f_number_) || gaussian_fwhm_;
    if (psf && !ensquared_entry_.present && !pitch_entry_.present)
      params_.reject("pixel_pitch", "the optics publish a PSF: give pixel_pitch to compute the ensquared energy over the "
                                    "window (or give ensquared_energy)");
    // What a sky background needs: the pixel's solid angle and the photometry of a magnitude.
    focal_length_ = c.find(vocabulary::optics_focal_length);
    area_ = c.find(vocabulary::optics_collecting_area);
    optics_transmittance_ = c.find(vocabulary::optics_transmittance);
    sun_magnitude_ = c.find(vocabulary::source_visual_magnitude);
    if (sky_entry_.present) {
      if (!pitch_entry_.present) params_.reject("sky_brightness", "needs pixel_pitch (the pixel's solid angle is (pitch/f')²)");
      if (!focal_length_) params_.reject("sky_brightness", "needs the optics' focal_length (the pixel's solid angle is (pitch/f')²)");
      if (!area_ || !optics_transmittance_ || !sun_magnitude_)
        params_.reject("sky_brightness", "needs a source with a visual magnitude (sun) and a telescope");
    }

    id_signal_ = c.declare(vocabulary::detector_signal_electrons, "S = EE × S_image: the point image's electrons in the detection window (Pan 2010 eq. 8, EE = 1)", "e-");
    id_image_ = c.declare(vocabulary::detector_image_electrons, "Pan 2010 eq. (8): S_image = t ∫ P_λ η λ/(hc) dλ", "e-");
    id_ensquared_ = c.declare(vocabulary::detector_ensquared_energy, ensquared_equation(psf));
    id_pixels_ = c.declare(vocabulary::detector_window_pixel_count, "n² pixels of the n×n detection window");
    id_dark_ = c.declare("dark_electrons", "electron", "N_d = n² × dark rate × t (Pan 2010 §3.2 1)", "e-");
    id_dark_noise_ = c.declare("dark_noise", "electron", "√N_d (Poisson)", "e-");
    id_read_noise_ = c.declare("read_noise", "electron", "n σ_o: √(n² σ_o²) (Pan 2010 §3.2 2)", "e-");
    id_quant_noise_ = c.declare("quantisation_noise", "electron",
                                paper_quantisation_ ? "Pan 2010 §3.2 3) as printed: n_q² = n² n_well/(2^N √12)"
                                                    : "EMVA 1288: n_q² = n² (n_well/2^N)²/12",
                                "e-");
    id_background_ = c.declare("background_electrons", "electron",
                               "B = n² S(m_sky) Ω_pixel/arcsec² (sky V mag/arcsec², solar spectrum)", "e-");
    id_background_noise_ = c.declare("background_noise", "electron", "√B (Poisson)", "e-");
    id_shot_noise_ = c.declare("shot_noise", "electron", "√S (Pan 2010 §3.2 4)", "e-");
    id_noise_ = c.declare(vocabulary::detector_noise_electrons, "Pan 2010 eq. (9) + sky: √(N_d + n²σ_o² + n² n_q² + B + S)", "e-");
    id_snr_ = c.declare(vocabulary::detector_snr, "Pan 2010 eq. (10): S / n");
    id_time_ = c.declare(vocabulary::detector_integration_time, "input t", "s");
    // What render and validate read (their frames use the detector's own well, ADC and noise).
    id_well_ = c.declare(vocabulary::detector_saturation_capacity, "input n_well", "e-");
    id_peak_ = c.declare(vocabulary::detector_peak_pixel_electrons,
                         "EE(1 pixel) S_image + dark rate × t + sky per pixel (all of the image when no PSF is known: Pan 2010)", "e-");
    id_fill_ = c.declare(vocabulary::detector_peak_pixel_fill, "brightest pixel / n_well (> 1: saturated, EMVA 1288 §2.3)", "%");
    id_bits_ = c.declare(vocabulary::detector_adc_bits, "input N");
    id_dark_rate_ = c.declare(vocabulary::detector_dark_rate, "input dark current", "e-/s");
    id_read_pixel_ = c.declare(vocabulary::detector_read_noise_per_pixel, "input σ_o", "e-");
    id_band_min_ = c.declare(vocabulary::detector_band_min, "input λ1", "um");
    id_band_max_ = c.declare(vocabulary::detector_band_max, "input λ2", "um");
    if (pitch_entry_.present) id_pitch_ = c.declare(vocabulary::detector_pixel_pitch, "input pitch", "um");
    if (pitch_entry_.present && focal_length_) {
      id_pixel_angle_ = c.declare("pixel_solid_angle", "sr", "Ω_pixel = (pitch/f')²", "arcsec2");
      id_sky_pixel_ = c.declare(vocabulary::detector_sky_electrons_per_pixel, "S(m_sky) Ω_pixel/arcsec²: one pixel's sky electrons per frame", "e-");
    }
  }

 private:
  const char* ensquared_equation(bool psf) const {  // literals: the declaration's memo knows them by address
    if (ensquared_entry_.given) return "input EE";
    if (psf_wavelength_ && f_number_)
      return "Airy PSF over a centred square of side n × pitch: (4/π) ∫0^{π/4} EC(n p/(2 cos θ)) dθ, "
             "EC = encircled energy (Born & Wolf §8.5.2; annular pupil: Mahajan 2001)";
    if (gaussian_fwhm_) return "Gaussian PSF over a centred square of side n × pitch: erf(n p/(2√2 σ))²";
    return psf ? "input EE" : "1: all of the image in the window (Pan 2010)";
  }

  template <class Access>
  void compute(Access& a) {
    using V = typename Access::Value;
    using std::sqrt;
    const V t = a.param(time_), qe = a.param(qe_), well = a.param(well_);
    const V n = a.param(window_), pixels = n * n;
    const V image = a.signal_scale() * qe * photon_rate_per_scale_ * t;
    V ensquared = broadcast<V>(1.0);
    if (ensquared_entry_.present) ensquared = a.param(ensquared_);
    else if constexpr (std::is_same_v<V, double>) ensquared = ensquared_energy(a, n, *pitch_);
    else if (psf_wavelength_ || gaussian_fwhm_) ensquared_energy_lanes(a, n, ensquared);
    const V signal = ensquared * image;
    const V dark = pixels * a.param(dark_) * t;
    V levels = broadcast<V>(0.0);  // 2^N (N ≤ 32: exact as a double)
    auto power_of_two = [](double bits) { return static_cast<double>(std::uint64_t{1} << static_cast<int>(bits)); };
    if constexpr (std::is_same_v<V, double>) levels = power_of_two(*bits_);
    else if (!a.varies(bits_)) levels = broadcast<V>(power_of_two(*bits_));
    else for (int i = 0; i < lane_count; ++i) levels(i) = power_of_two(a.param(bits_)(i));
    const V step = well / levels;
    const V quant_var = paper_quantisation_ ? V(pixels * step / std::sqrt(12.0)) : V(pixels * step * step / 12.0);
    const V read = a.param(read_);
    const V read_var = pixels * read * read;
    V sky_per_pixel = broadcast<V>(0.0);
    if (id_pixel_angle_) {
      const V angle = a.param(pitch_) / a.value(*focal_length_);
      a.set(*id_pixel_angle_, angle * angle);
      if (sky_entry_.present && area_ && optics_transmittance_ && sun_magnitude_) {
        // A solar-spectrum source of magnitude m_sky gives this many electrons per frame (the target's photometry,
        // per unit ratio of eq. 1); the sky gives that per square arcsecond.
        const V electrons_per_ratio = photon_rate_per_scale_ * qe * t * a.value(*area_) * a.value(*optics_transmittance_);
        const V ratio = physics::magnitude_ratio(a.param(sky_), a.value(*sun_magnitude_));
        const V pixel_arcsec2 = angle * angle * (arcsec_per_rad * arcsec_per_rad);
        sky_per_pixel = electrons_per_ratio * ratio * pixel_arcsec2;
      }
      a.set(*id_sky_pixel_, sky_per_pixel);
    }
    const V background = pixels * sky_per_pixel;
    const V noise = sqrt(dark + read_var + quant_var + background + signal);
    a.set(id_signal_, signal);
    a.set(id_noise_, noise);
    a.set(id_snr_, signal / noise);
    a.set(id_time_, t);
    // The brightest pixel's charge in one frame (a criterion may read it in a solve, so in every detail): the PSF's share in one centred pixel (all of it without a PSF).
    V peak_fraction = broadcast<V>(1.0);
    if constexpr (std::is_same_v<V, double>) peak_fraction = peak_pixel_fraction(a);
    else for (int i = 0; i < lane_count; ++i) peak_fraction(i) = peak_pixel_fraction(a, i);
    const V peak = peak_fraction * image + a.param(dark_) * t + sky_per_pixel;
    a.set(id_peak_, peak);
    a.set(id_fill_, peak / well);
    if (!a.full_detail()) return;  // the noise budget's terms: for the report
    a.set(id_image_, image);
    a.set(id_ensquared_, ensquared);
    a.set(id_pixels_, pixels);
    a.set(id_dark_, dark);
    a.set(id_dark_noise_, sqrt(dark));
    a.set(id_read_noise_, sqrt(read_var));
    a.set(id_quant_noise_, sqrt(quant_var));
    a.set(id_background_, background);
    a.set(id_background_noise_, sqrt(background));
    a.set(id_shot_noise_, sqrt(signal));
    a.set(id_well_, well);
    a.set(id_bits_, a.param(bits_));
    a.set(id_dark_rate_, a.param(dark_));
    a.set(id_read_pixel_, read);
    a.set(id_band_min_, broadcast<V>(band_min_));
    a.set(id_band_max_, broadcast<V>(band_max_));
    if (id_pitch_) a.set(*id_pitch_, a.param(pitch_));
  }

  // EE as given; else from the optics' PSF (cached: it changes only with the window, pitch, λ, N, ε or FWHM);
  // else 1. One lane's values in lane mode.
  void ensquared_energy_lanes(LaneContext& a, const Lanes& n, Lanes& out) {
    const Lanes side = n * a.param(pitch_);
    auto at = [&](const std::optional<ResultId>& id, int lane) { return id ? a.value(*id)(lane) : 0.0; };
    for (int i = 0; i < lane_count; ++i)
      out(i) = ensquared_energy_of(side(i), at(psf_wavelength_, i), at(f_number_, i), at(obscuration_, i),
                                   at(gaussian_fwhm_, i), 0.0);
  }
  double ensquared_energy(ScalarAccess& a, double n, double pitch) {
    auto at = [&](const std::optional<ResultId>& id) { return id ? a.value(*id) : 0.0; };
    return ensquared_energy_of(n * pitch, at(psf_wavelength_), at(f_number_), at(obscuration_), at(gaussian_fwhm_),
                               *ensquared_);
  }
  double ensquared_energy_of(double side, double lambda, double f_number, double eps, double fwhm, double given) {
    if (ensquared_entry_.present) return given;
    if (!pitch_entry_.present) return 1.0;
    if (psf_wavelength_ && f_number_) {
      if (side != cache_[0] || lambda != cache_[1] || f_number != cache_[2] || eps != cache_[3]) {
        cache_[0] = side, cache_[1] = lambda, cache_[2] = f_number, cache_[3] = eps;
        cached_ensquared_ = physics::airy_ensquared_energy(side, lambda, f_number, eps);
      }
      return cached_ensquared_;
    }
    if (gaussian_fwhm_) return physics::gaussian_ensquared_energy(side, fwhm);
    return 1.0;
  }

  // The PSF's share in one pixel centred on it (a square of side `pitch`): 1 without a pixel pitch or a PSF.
  template <class Access>
  double peak_pixel_fraction(Access& a, int lane = 0) {
    auto at = [&](const std::optional<ResultId>& id) {
      if (!id) return 0.0;
      if constexpr (std::is_same_v<Access, ScalarAccess>) return a.value(*id);
      else return a.value(*id)(lane);
    };
    if (!pitch_entry_.present) return 1.0;
    double pitch = 0;
    if constexpr (std::is_same_v<Access, ScalarAccess>) pitch = a.param(pitch_);
    else pitch = a.param(pitch_)(lane);
    if (psf_wavelength_ && f_number_) {
      const double lambda = at(psf_wavelength_), f_number = at(f_number_), eps = at(obscuration_);
      if (pitch != peak_cache_[0] || lambda != peak_cache_[1] || f_number != peak_cache_[2] || eps != peak_cache_[3]) {
        peak_cache_[0] = pitch, peak_cache_[1] = lambda, peak_cache_[2] = f_number, peak_cache_[3] = eps;
        cached_peak_fraction_ = physics::airy_ensquared_energy(pitch, lambda, f_number, eps);
      }
      return cached_peak_fraction_;
    }
    if (gaussian_fwhm_) return physics::gaussian_ensquared_energy(pitch, at(gaussian_fwhm_));
    return 1.0;
  }

  const Params& params_;
  const double *qe_, *time_, *well_, *bits_, *dark_, *read_, *pitch_, *window_, *ensquared_, *sky_;
  double peak_cache_[4] = {-1, -1, -1, -1}, cached_peak_fraction_ = 1;
  const Params::Entry &pitch_entry_, &ensquared_entry_, &sky_entry_;
  bool paper_quantisation_;
  double photon_rate_per_scale_ = 0, band_min_ = 0, band_max_ = 0;
  double cache_[4] = {-1, -1, -1, -1}, cached_ensquared_ = 1;
  std::optional<ResultId> psf_wavelength_, gaussian_fwhm_, f_number_, obscuration_, focal_length_, area_,
      optics_transmittance_, sun_magnitude_, id_pixel_angle_, id_sky_pixel_, id_pitch_;
  ResultId id_signal_{}, id_image_{}, id_ensquared_{}, id_pixels_{}, id_dark_{}, id_dark_noise_{}, id_read_noise_{},
      id_quant_noise_{}, id_background_{}, id_background_noise_{}, id_shot_noise_{}, id_noise_{}, id_snr_{}, id_time_{},
      id_well_{}, id_peak_{}, id_fill_{}, id_bits_{}, id_dark_rate_{}, id_read_pixel_{}, id_band_min_{}, id_band_max_{};
};

}  // namespace

RADCHAIN_PLUGIN(CcdFrame, {
    .summary = "frame CCD: a point image's electrons in an n×n window and the dark/read/quantisation/sky/shot noise budget",
    .reference = "Pan et al. 2010 eqs. (6)-(10); EMVA 1288 R4.0; Born & Wolf §8.5.2 (ensquared energy)",
    .schema = schema,
    .publishes = {vocabulary::detector_signal_electrons, vocabulary::detector_image_electrons,
                  vocabulary::detector_ensquared_energy, vocabulary::detector_window_pixel_count,
                  vocabulary::detector_noise_electrons, vocabulary::detector_snr,
                  vocabulary::detector_integration_time, vocabulary::detector_sky_electrons_per_pixel,
                  vocabulary::detector_saturation_capacity, vocabulary::detector_adc_bits, vocabulary::detector_dark_rate,
                  vocabulary::detector_read_noise_per_pixel, vocabulary::detector_band_min, vocabulary::detector_band_max,
                  vocabulary::detector_pixel_pitch, vocabulary::detector_peak_pixel_fill,
                  vocabulary::detector_peak_pixel_electrons},
    .needs = {if_present(vocabulary::optics_psf_wavelength), if_present(vocabulary::optics_gaussian_fwhm),
              if_present(vocabulary::optics_f_number), if_present(vocabulary::optics_obscuration),
              if_present(vocabulary::optics_focal_length), if_present(vocabulary::optics_collecting_area),
              if_present(vocabulary::optics_transmittance), if_present(vocabulary::source_visual_magnitude)},
})

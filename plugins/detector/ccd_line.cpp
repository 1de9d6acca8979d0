// A CCD line array in a pushbroom camera (Kolobrodov 1996: a CCD151-like device). Its sensitivity is a
// noise-equivalent exposure H_nt measured with a reference lamp; for the working source it becomes
//   H_nr = H_nt k_i / k_c                                   (Kolobrodov 1996, after eq. 20; Ishanin et al. 1991)
// with k_i the utilisation of the lamp over the whole response, k_c that of the working source in the band
// (docs/utilisation-coefficients.md: the reading that reproduces the printed sizes). Then
//   t_i = N / f_D,   E_n = H_nr / t_i                        (eq. 20 and the worked example)
//   E'  = ∫_{λ1}^{λ2} E'_λ dλ  (the contrast signal's image irradiance; eq. 21 in spectral form, eq. 6)
//   snr = E' / E_n  (= 1 at the energy threshold: eq. 21 = eq. 20)
// Geometry: line length l_D = pitch × N; element MTF sinc(π V_D ν) (eq. 8); ν at contrast 0.5 (eq. 11);
// the system resolution element V_s from eq. (15) (or the printed V_s/V_D = 1.49 pinned) and its frequency at
// contrast 0.5, ν_x2 = u/V_s (eq. 14).
#include "radchain/physics/band.hpp"
#include "radchain/physics/mtf.hpp"
#include "radchain/physics/pushbroom.hpp"
#include "radchain/plugin.hpp"

#include <cmath>
#include <stdexcept>

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      quantity("pixel_pitch", "m", "7 um").needed().above(0).described("distance between element centres"),
      quantity("element_size", "m", "7 um").needed().above(0).described("width V_D of the sensitive element (≤ pitch)"),
      integer("element_count", "5000").needed().at_least(1).described("number of elements N in the line"),
      quantity("clock", "Hz", "5 MHz").needed().above(0).described("readout clock f_D (t_i = N / f_D)"),
      quantity("integration_time", "s", "1 ms").above(0).described("pin the line integration time (default N / f_D)"),
      quantity("band_min", "m", "0.5 um").needed().above(0).affects_spectrum().described("working band lower limit λ1"),
      quantity("band_max", "m", "0.76 um").needed().above(0).affects_spectrum().described("working band upper limit λ2"),
      quantity("nee", "J m-2", "0.0002 uJ/cm2").needed().above(0)
          .described("noise-equivalent exposure H_nt, measured with the reference lamp"),
      quantity("saturation_exposure", "J m-2", "0.5 uJ/cm2").above(0).described("saturation exposure H_m (reference lamp)"),
      quantity("reference_temperature", "K", "2854 K").fallback("2854 K").above(0).affects_spectrum()
          .described("colour temperature of the calibration lamp"),
      choice("reference_c2", {"ipts48", "exact", "cie_a_1931"}).fallback("ipts48")
          .described("c2 convention of that temperature: 1.438e-2 (IPTS-48, '2854 K' lamps), SI exact, or 1.435e-2"),
      spectrum_file("relative_response", "1", "ccd_front_illuminated_fairchild_relative.csv")
          .fallback("ccd_front_illuminated_fairchild_relative.csv")
          .described("relative spectral response per watt (normalised to peak 1 here)"),
      number("utilisation_reference", "0.187").above(0).at_most(1)
          .described("paper value: pin k_i (the report shows the computed one beside it)"),
      number("utilisation_working", "0.852").above(0).at_most(1)
          .described("paper value: pin k_c (the report shows the computed one beside it)"),
      choice("sinc_root", {"paper", "exact"}).fallback("exact")
          .described("u with sinc(πu) = 0.5 in eqs. (11), (14), (15): the paper's 0.6 or the exact 0.603355"),
      number("system_element_ratio", "1.49").at_least(1)
          .described("paper value: pin V_s / V_D (eq. 15, printed 1.49; default: eq. 15 solved with sinc_root)"),
  };
  return s;
}

double c2_of(const std::string& convention) {
  if (convention == "ipts48") return constants::second_radiation_ipts48_m_K;
  if (convention == "cie_a_1931") return constants::second_radiation_1931_m_K;
  return constants::second_radiation_m_K;
}

class CcdLine final : public Stage {
 public:
  // Signal ∝ the light's scale; threshold, element and line from the inputs: SNR = signal / threshold (eq. 5).
  bool power_law() const override { return true; }

  explicit CcdLine(const Params& p)
      : params_(p), pitch_(p.handle("pixel_pitch")), element_(p.handle("element_size")),
        count_(p.handle("element_count")), clock_(p.handle("clock")), pinned_time_(p.handle("integration_time")),
        nee_(p.handle("nee")), saturation_(p.handle("saturation_exposure")),
        pinned_ratio_(p.handle("system_element_ratio")) {
    if (p.get("element_size") > p.get("pixel_pitch")) p.reject("element_size", "must not exceed pixel_pitch");
    if (!(p.get("band_max") > p.get("band_min"))) p.reject("band_max", "must be larger than band_min");
  }

  void prepare(Context& c) override {
    const Radiation& signal = c.light.signal;
    if (signal.form != RadiationForm::focal_irradiance)
      c.refuse_form("a focal-plane irradiance (an extended scene through optics with a focal length)", signal.form);
    const double lo = params_.get("band_min"), hi = params_.get("band_max");
    require_band_inside_tables(params_, c.light, signal.spectrum, lo, hi);
    signal_in_band_ = signal.spectrum.integral(lo, hi);
    background_in_band_ =
        c.light.background.form == RadiationForm::focal_irradiance ? c.light.background.spectrum.integral(lo, hi) : 0.0;

    // Utilisation coefficients (Kolobrodov 1996 after eq. 20), calibration reading.
    const Spectrum response = physics::normalised_to_peak(params_.spectrum("relative_response"));
    const physics::WavelengthRange whole = physics::support(response), band{lo, hi};
    const Spectrum lamp = physics::blackbody_exitance_spectrum(params_.get("reference_temperature"),
                                                               c2_of(params_.text("reference_c2")));
    // A spectrum that radiates nothing where it is integrated is bad input (a lamp of a few kelvin), not a fault.
    // A spectrum that radiates nothing where it is integrated (a lamp of a few kelvin) is bad input, not a fault
    // and not a silent k = 0 (an infinite SNR).
    auto coefficient = [&](const Spectrum& source, const physics::WavelengthRange& response_range,
                           const physics::WavelengthRange& source_range, const char* key, const char* what) {
      std::string why = "k = 0";
      try {
        const double k = physics::utilisation_coefficient(source, response, response_range, source_range);
        if (k > 0) return k;
      } catch (const std::invalid_argument& error) {
        why = error.what();
      }
      params_.reject(key, std::string(what) + " (" + why + ")");
    };
    k_reference_computed_ = coefficient(lamp, whole, physics::support(lamp), "reference_temperature",
                                        "the calibration lamp gives no radiation the detector responds to; a tungsten lamp is near 2854 K");
    k_working_computed_ = coefficient(signal.spectrum, band, band, "band_min", "the scene gives no radiation the detector responds to in its band");
    k_reference_ = params_.has("utilisation_reference") ? params_.get("utilisation_reference") : k_reference_computed_;
    k_working_ = params_.has("utilisation_working") ? params_.get("utilisation_working") : k_working_computed_;

    const bool paper_root = params_.text("sinc_root") == "paper";
    time_pinned_ = params_.has("integration_time");
    sinc_root_ = paper_root ? physics::kolobrodov_sinc_half_root_printed : physics::sinc_half_contrast_root();
    element_ratio_computed_ = physics::kolobrodov_system_element_ratio(sinc_root_);

    const std::string pinned = " (pinned paper value)";
    id_time_ = c.declare(vocabulary::detector_integration_time, params_.has("integration_time") ? "input t_i" : "t_i = N / f_D (Kolobrodov 1996 worked example)", "ms");
    id_k_ref_ = c.declare("utilisation_reference", "1",
                          "k_i = ∫ S_lamp s_rel / ∫ S_lamp, whole response" +
                              (params_.has("utilisation_reference") ? pinned : std::string()));
    id_k_work_ = c.declare("utilisation_working", "1",
                           "k_c = ∫_band S s_rel / ∫_band S, working source" +
                               (params_.has("utilisation_working") ? pinned : std::string()));
    if (params_.has("utilisation_reference"))
      id_k_ref_computed_ = c.declare("utilisation_reference_computed", "1", "k_i from the lamp and the response curve");
    if (params_.has("utilisation_working"))
      id_k_work_computed_ = c.declare("utilisation_working_computed", "1", "k_c from the source and the response curve");
    id_ratio_ = c.declare(vocabulary::detector_utilisation_ratio, "k_i / k_c");
    id_nee_ = c.declare("nee_reference", "J m-2", "input H_nt (reference lamp)", "J/cm2");
    id_nee_working_ = c.declare(vocabulary::detector_nee_working, "H_nr = H_nt k_i / k_c", "J/cm2");
    id_threshold_ = c.declare("threshold_irradiance", "W m-2", "Kolobrodov 1996 eq. (20): E_n = H_nr / t_i", "W/cm2");
    id_signal_ = c.declare(vocabulary::detector_signal_irradiance, "eq. (21)/(6): E' = ∫_band E'_λ dλ of the contrast ΔM", "W/cm2");
    id_snr_ = c.declare(vocabulary::detector_snr, "E' / E_n (signal exposure over noise-equivalent exposure)");
    id_line_ = c.declare(vocabulary::detector_line_length, "l_D = pitch × N (eq. 17 text)", "mm");
    id_pitch_ = c.declare(vocabulary::detector_pixel_pitch, "input pitch", "um");
    id_band_min_ = c.declare(vocabulary::detector_band_min, "input λ1", "um");
    id_band_max_ = c.declare(vocabulary::detector_band_max, "input λ2", "um");
    if (params_.has("saturation_exposure"))
      id_saturation_exposure_ = c.declare(vocabulary::detector_saturation_exposure, "input H_m (reference lamp)", "J/cm2");
    id_element_ = c.declare(vocabulary::detector_element_size_for_mtf, "input V_D (eq. 8)", "um");
    id_nu_half_ = c.declare(vocabulary::detector_nu_half_contrast, std::string("eq. (11): ν_x1 = u/V_D, u = ") + (paper_root ? "0.6 (paper)" : "0.603355 (exact)"),
                            "mm-1");
    id_nyquist_ = c.declare("nyquist_frequency", "m-1", "1 / (2 pitch)", "mm-1");
    id_mtf_nyquist_ = c.declare("mtf_at_nyquist", "1", "eq. (8): |sinc(π V_D ν_N)|");
    if (params_.has("system_element_ratio")) {
      id_element_ratio_ = c.declare("system_element_ratio", "1", "V_s / V_D (eq. 15)" + pinned);
      id_element_ratio_computed_ = c.declare("system_element_ratio_computed", "1", "eq. (15) solved (TOMS 748): V_s / V_D");
    } else {
      id_element_ratio_ = c.declare("system_element_ratio", "1", "eq. (15) solved (TOMS 748): V_s / V_D");
    }
    id_system_element_ = c.declare(vocabulary::detector_system_element, "V_s = (V_s/V_D) V_D (eq. 15)", "um");
    id_nu_system_half_ = c.declare("nu_system_half_contrast", "m-1", "eq. (14): ν_x2 = u/V_s, the system's frequency at contrast 0.5",
                                   "mm-1");
    if (params_.has("saturation_exposure"))
      id_dynamic_range_ = c.declare("dynamic_range", "1", "H_m / H_n (saturation over noise-equivalent exposure)");
    if (background_in_band_ > 0 && params_.has("saturation_exposure"))
      id_saturation_ = c.declare("background_saturation_fraction", "1", "H_background / H_m (both for this source)");
  }

  void evaluate(Context& c) override {
    const double t = time_pinned_ ? *pinned_time_ : physics::line_integration_time_s(*count_, *clock_);
    const double nee_working = physics::exposure_for_working_source(*nee_, k_reference_, k_working_);
    const double threshold = physics::threshold_image_irradiance_W_m2(nee_working, t);
    const double signal = c.light.signal.scale * signal_in_band_;
    c.results.set(id_time_, t);
    c.results.set(id_k_ref_, k_reference_);
    c.results.set(id_k_work_, k_working_);
    if (id_k_ref_computed_) c.results.set(*id_k_ref_computed_, k_reference_computed_);
    if (id_k_work_computed_) c.results.set(*id_k_work_computed_, k_working_computed_);
    c.results.set(id_ratio_, k_reference_ / k_working_);
    c.results.set(id_nee_, *nee_);
    c.results.set(id_nee_working_, nee_working);
    c.results.set(id_threshold_, threshold);
    c.results.set(id_signal_, signal);
    c.results.set(id_snr_, signal / threshold);
    c.results.set(id_line_, physics::detector_line_length_m(*pitch_, *count_));
    c.results.set(id_pitch_, *pitch_);
    c.results.set(id_band_min_, params_.get("band_min"));
    c.results.set(id_band_max_, params_.get("band_max"));
    if (id_saturation_exposure_) c.results.set(*id_saturation_exposure_, *saturation_);
    c.results.set(id_element_, *element_);
    c.results.set(id_nu_half_, sinc_root_ / *element_);
    c.results.set(id_nyquist_, 0.5 / *pitch_);
    c.results.set(id_mtf_nyquist_, physics::detector_pixel_mtf(0.5 / *pitch_, *element_));
    const double element_ratio = id_element_ratio_computed_ ? *pinned_ratio_ : element_ratio_computed_;
    c.results.set(id_element_ratio_, element_ratio);
    if (id_element_ratio_computed_) c.results.set(*id_element_ratio_computed_, element_ratio_computed_);
    c.results.set(id_system_element_, element_ratio * *element_);
    c.results.set(id_nu_system_half_, sinc_root_ / (element_ratio * *element_));
    if (id_dynamic_range_) c.results.set(*id_dynamic_range_, *saturation_ / *nee_);
    if (id_saturation_) {
      const double saturation_working = physics::exposure_for_working_source(*saturation_, k_reference_, k_working_);
      c.results.set(*id_saturation_, c.light.background.scale * background_in_band_ * t / saturation_working);
    }
  }

 private:
  const Params& params_;
  const double *pitch_, *element_, *count_, *clock_, *pinned_time_, *nee_, *saturation_, *pinned_ratio_;
  double signal_in_band_ = 0, background_in_band_ = 0;
  double k_reference_ = 1, k_working_ = 1, k_reference_computed_ = 1, k_working_computed_ = 1;
  double sinc_root_ = 0.6, element_ratio_computed_ = 1.49;
  bool time_pinned_ = false;
  ResultId id_time_{}, id_k_ref_{}, id_k_work_{}, id_ratio_{}, id_nee_{}, id_nee_working_{}, id_threshold_{},
      id_signal_{}, id_snr_{}, id_line_{}, id_element_{}, id_nu_half_{}, id_nyquist_{}, id_mtf_nyquist_{}, id_element_ratio_{},
      id_system_element_{}, id_nu_system_half_{}, id_pitch_{}, id_band_min_{}, id_band_max_{};
  std::optional<ResultId> id_element_ratio_computed_, id_k_ref_computed_, id_k_work_computed_, id_saturation_, id_dynamic_range_, id_saturation_exposure_;
};

}  // namespace

RADCHAIN_PLUGIN(CcdLine, {
    .summary = "CCD line array of a pushbroom camera: NEE from a reference lamp, element MTF, geometry",
    .reference = "Kolobrodov 1996 eqs. (8), (11), (14), (15), (20)-(21); Ishanin et al. 1991",
    .schema = schema,
    .publishes = {vocabulary::detector_integration_time, vocabulary::detector_utilisation_ratio,
                  vocabulary::detector_nee_working, vocabulary::detector_signal_irradiance, vocabulary::detector_snr,
                  vocabulary::detector_line_length, vocabulary::detector_element_size_for_mtf,
                  vocabulary::detector_nu_half_contrast, vocabulary::detector_system_element, vocabulary::detector_pixel_pitch,
                  vocabulary::detector_band_min, vocabulary::detector_band_max, vocabulary::detector_saturation_exposure},
})

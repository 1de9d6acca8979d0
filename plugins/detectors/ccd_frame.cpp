// A frame-transfer CCD counting a point object's photoelectrons in one frame, with its noise budget.
//   signal   S  = t ∫_{λ1}^{λ2} P_λ η(λ) λ/(h c) dλ                  (Pan 2010 eqs. 6-8)
//   noise    n² = N_d + σ_o² + n_q² + S                              (Pan 2010 eq. 9)
//   N_d = dark rate × t (Poisson);  σ_o read noise;  shot noise √S
//   n_q²: "emva" (n_well/2^N)²/12  (EMVA 1288 R4.0 eq. 8; uniform quantiser of step n_well/2^N)
//         "paper" n_well/(2^N √12)   (as printed in Pan 2010, §3.2; see docs/physics/quantisation.md)
#include "radchain/physics/photometry.hpp"
#include "radchain/plugin.hpp"

#include <cmath>

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      number("qe", "0.27").fallback("1").above(0).at_most(1)
          .described("mean quantum efficiency η (multiplies any qe_curve)"),
      spectrum_file("qe_curve", "1", "ccd_back_illuminated_hamamatsu_S10420-01_qe.csv")
          .described("spectral quantum efficiency η(λ) (optional)"),
      quantity("band_min", "m", "0.3 um").needed().above(0).affects_spectrum().described("detector band lower limit λ1"),
      quantity("band_max", "m", "0.9 um").needed().above(0).affects_spectrum().described("detector band upper limit λ2"),
      quantity("integration_time", "s", "0.625 s").needed().above(0).described("frame integration time t"),
      quantity("full_well", "electron", "1e5 e-").needed().above(0).described("potential well depth n_well"),
      integer("adc_bits", "12").needed().at_least(1).at_most(32).described("ADC resolution N (bits)"),
      quantity("dark_rate", "electron/s", "18 e-/s").fallback("0 e-/s").at_least(0)
          .described("dark current per pixel at the operating temperature"),
      quantity("read_noise", "electron", "6 e-").fallback("0 e-").at_least(0).described("output amplifier noise σ_o (rms)"),
      choice("quantisation", {"emva", "paper"}).fallback("emva")
          .described("quantisation noise form: EMVA 1288 (n_well/2^N)²/12, or Pan 2010 as printed n_well/(2^N √12)"),
  };
  return s;
}

class CcdFrame final : public Stage {
 public:
  explicit CcdFrame(const Params& p)
      : params_(p), qe_(p.handle("qe")), time_(p.handle("integration_time")), well_(p.handle("full_well")),
        bits_(p.handle("adc_bits")), dark_(p.handle("dark_rate")), read_(p.handle("read_noise")),
        paper_quantisation_(p.text("quantisation") == "paper") {
    if (!(p.get("band_max") > p.get("band_min"))) p.reject("band_max", "must be larger than band_min");
  }

  void prepare(Context& c) override {
    const Radiation& signal = c.light.signal;
    if (signal.form != RadiationForm::focal_power) c.refuse_form("a point image's power (a point target)", signal.form);
    const double lo = params_.get("band_min"), hi = params_.get("band_max");
    auto photons = [](double l) { return physics::photons_per_joule(l); };
    // Spectral phase: photons per second per unit signal scale, QE curve included (Pan eqs. 6-7).
    if (params_.has("qe_curve"))
      photon_rate_per_scale_ = band_integral({&signal.spectrum, &params_.spectrum("qe_curve")}, lo, hi, photons);
    else
      photon_rate_per_scale_ = band_integral({&signal.spectrum}, lo, hi, photons);
    id_signal_ = c.declare("signal_electrons", "electron", "Pan 2010 eq. (8): S = t ∫ P_λ η λ/(hc) dλ", "e-");
    id_dark_ = c.declare("dark_electrons", "electron", "N_d = dark rate × t (Pan 2010 §3.2 1)", "e-");
    id_dark_noise_ = c.declare("dark_noise", "electron", "√N_d (Poisson)", "e-");
    id_read_noise_ = c.declare("read_noise", "electron", "σ_o (Pan 2010 §3.2 2)", "e-");
    id_quant_noise_ = c.declare("quantisation_noise", "electron",
                                paper_quantisation_ ? "Pan 2010 §3.2 3) as printed: n_q² = n_well/(2^N √12)"
                                                    : "EMVA 1288: n_q² = (n_well/2^N)²/12",
                                "e-");
    id_shot_noise_ = c.declare("shot_noise", "electron", "√S (Pan 2010 §3.2 4)", "e-");
    id_noise_ = c.declare("noise_electrons", "electron", "Pan 2010 eq. (9): √(N_d + σ_o² + n_q² + S)", "e-");
    id_snr_ = c.declare("snr", "1", "Pan 2010 eq. (10): S / n");
    id_time_ = c.declare("integration_time", "s", "input t", "s");
  }

  void evaluate(Context& c) override {
    const double t = *time_;
    const double signal = c.light.signal.scale * *qe_ * photon_rate_per_scale_ * t;
    const double dark = *dark_ * t;
    const double levels = std::exp2(*bits_);
    const double quant_var = paper_quantisation_ ? *well_ / (levels * std::sqrt(12.0))
                                                 : (*well_ / levels) * (*well_ / levels) / 12.0;
    const double noise = std::sqrt(dark + *read_ * *read_ + quant_var + signal);
    c.results.set(id_signal_, signal);
    c.results.set(id_dark_, dark);
    c.results.set(id_dark_noise_, std::sqrt(dark));
    c.results.set(id_read_noise_, *read_);
    c.results.set(id_quant_noise_, std::sqrt(quant_var));
    c.results.set(id_shot_noise_, std::sqrt(signal));
    c.results.set(id_noise_, noise);
    c.results.set(id_snr_, signal / noise);
    c.results.set(id_time_, t);
  }

 private:
  const Params& params_;
  const double *qe_, *time_, *well_, *bits_, *dark_, *read_;
  bool paper_quantisation_;
  double photon_rate_per_scale_ = 0;
  ResultId id_signal_{}, id_dark_{}, id_dark_noise_{}, id_read_noise_{}, id_quant_noise_{}, id_shot_noise_{},
      id_noise_{}, id_snr_{}, id_time_{};
};

const PluginInfo& info() {
  static const PluginInfo i{plugin_abi_version, framework_version, Kind::detector, "ccd_frame",
                            "frame CCD: photoelectrons of a point image and the dark/read/quantisation/shot noise budget",
                            "Pan et al. 2010 eqs. (6)-(10); EMVA 1288 R4.0", &schema,
                            [](const Params& p) -> std::unique_ptr<Stage> { return std::make_unique<CcdFrame>(p); }};
  return i;
}
}  // namespace

RADCHAIN_PLUGIN(info)

// Detection when SNR ≥ T (Pan 2010 eq. 10). T is given, or follows from the detection and false-alarm
// probabilities for a known signal in Gaussian noise: T = z(1 - P_fa) + z(P_d), z the standard normal
// quantile (physics/detection.hpp). The margin SNR/T − 1 (the criteria's convention: achieved/required − 1) is
// what a [[solve]] drives to zero.
// With a false-alarm probability (alone with T, or with P_d) the stage also reports the detection probability
// at the chain's SNR, Φ(SNR − z(1 − P_fa)); given T and P_fa that is what T buys, e.g. T = 5 at P_fa = 1 %:
// P_d = Φ(5 − 2.3263) = 0.99625 (docs/physics/detection-threshold.md).
#include "radchain/physics/detection.hpp"
#include "radchain/plugin.hpp"

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      number("threshold", "5").above(0).described("SNR threshold T (give this, or both probabilities)"),
      number("detection_probability", "0.99").above(0).below(1).described("required P_d (with false_alarm_probability)"),
      number("false_alarm_probability", "0.01").above(0).below(1)
          .described("allowed P_fa (with detection_probability; or with threshold, to report the P_d it gives)"),
  };
  return s;
}

class SnrThreshold final : public Stage {
 public:
  explicit SnrThreshold(const Params& p) : threshold_(p.handle("threshold")) {
    const bool probabilities = p.has("detection_probability") && p.has("false_alarm_probability");
    if (p.has("threshold") == probabilities)
      p.reject(p.has("threshold") ? "threshold" : "detection_probability",
               "give either threshold, or both detection_probability and false_alarm_probability");
    if (p.has("detection_probability") && !p.has("false_alarm_probability"))
      p.reject("detection_probability", "needs false_alarm_probability as well (T = z(1 - P_fa) + z(P_d))");
    if (probabilities)
      from_probabilities_ = physics::snr_threshold_for(p.get("detection_probability"), p.get("false_alarm_probability"));
    if (p.has("false_alarm_probability")) false_alarm_ = p.get("false_alarm_probability");
  }

  void prepare(Context& c) override {
    snr_ = c.require("detector.snr");
    id_threshold_ = c.declare("threshold", "1", from_probabilities_ ? "T = z(1 - P_fa) + z(P_d), Gaussian" : "input T");
    id_margin_ = c.declare("margin", "1", "SNR/T − 1 (≥ 0: detected, Pan 2010 eq. 10)");
    id_detected_ = c.declare("detected", "1", "1 if SNR ≥ T (to 1e-9 T)");
    if (false_alarm_) {
      id_false_alarm_ = c.declare("false_alarm_probability", "1", "input P_fa");
      id_detection_probability_ = c.declare("detection_probability", "1",
                                            "P_d at the chain's SNR: Φ(SNR − z(1 − P_fa)) (known signal, Gaussian noise)");
    }
  }

  void evaluate(Context& c) override {
    const double t = from_probabilities_ ? *from_probabilities_ : *threshold_;
    const double snr = c.results.value(snr_);
    const double margin = snr / t - 1.0;
    c.results.set(id_margin_, margin);
    if (!c.full_detail()) return;
    c.results.set(id_threshold_, t);
    // At a solved limit the margin is zero to rounding; 1e-9 keeps that point on the detected side.
    c.results.set(id_detected_, margin >= -1e-9 ? 1.0 : 0.0);
    if (false_alarm_) {
      c.results.set(*id_false_alarm_, *false_alarm_);
      c.results.set(*id_detection_probability_, physics::detection_probability_at(snr, *false_alarm_));
    }
  }

 private:
  const double* threshold_;
  std::optional<double> from_probabilities_, false_alarm_;
  ResultId snr_{}, id_threshold_{}, id_margin_{}, id_detected_{};
  std::optional<ResultId> id_false_alarm_, id_detection_probability_;
};

const PluginInfo& info() {
  static const PluginInfo i{plugin_abi_version, framework_version, Kind::criterion, "snr_threshold",
                            "detection when SNR ≥ T; T given or from P_d and P_fa (Gaussian)",
                            "Pan et al. 2010 eqs. (10)-(11); Gaussian detection theory", &schema,
                            [](const Params& p) -> std::unique_ptr<Stage> { return std::make_unique<SnrThreshold>(p); }};
  return i;
}
}  // namespace

RADCHAIN_PLUGIN(info)

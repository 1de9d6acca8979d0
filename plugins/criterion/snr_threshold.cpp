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

class SnrThreshold final : public LaneStage<SnrThreshold> {
  friend class LaneStage<SnrThreshold>;  // calls compute()

 public:
  explicit SnrThreshold(const Params& p)
      : threshold_(p.handle("threshold")), detection_(p.handle("detection_probability")),
        false_alarm_(p.handle("false_alarm_probability")) {
    const bool probabilities = p.has("detection_probability") && p.has("false_alarm_probability");
    if (p.has("threshold") == probabilities)
      p.reject(p.has("threshold") ? "threshold" : "detection_probability",
               "give either threshold, or both detection_probability and false_alarm_probability");
    if (p.has("detection_probability") && !p.has("false_alarm_probability"))
      p.reject("detection_probability", "needs false_alarm_probability as well (T = z(1 - P_fa) + z(P_d))");
    from_probabilities_ = probabilities;
    with_false_alarm_ = p.has("false_alarm_probability");
  }

  void prepare(Context& c) override {
    snr_ = c.require(vocabulary::detector_snr);
    id_threshold_ = c.declare(vocabulary::criterion_threshold, from_probabilities_ ? "T = z(1 - P_fa) + z(P_d), Gaussian" : "input T");
    id_margin_ = c.declare(vocabulary::criterion_margin, "SNR/T − 1 (≥ 0: detected, Pan 2010 eq. 10)");
    id_detected_ = c.declare("detected", "1", "1 if SNR ≥ T (to 1e-9 T)");
    if (with_false_alarm_) {
      id_false_alarm_ = c.declare("false_alarm_probability", "1", "input P_fa");
      id_detection_probability_ = c.declare("detection_probability", "1",
                                            "P_d at the chain's SNR: Φ(SNR − z(1 − P_fa)) (known signal, Gaussian noise)");
    }
  }

 private:
  template <class Access>
  void compute(Access& a) {
    using V = typename Access::Value;
    V t = a.param(threshold_);
    if (from_probabilities_) {  // T from (P_d, P_fa): normal quantiles, recomputed only when the pair changes
      if constexpr (std::is_same_v<V, double>) t = threshold_for(a.param(detection_), a.param(false_alarm_));
      else for (int i = 0; i < lane_count; ++i) t(i) = threshold_for(a.param(detection_)(i), a.param(false_alarm_)(i));
    }
    const V snr = a.value(snr_);
    const V margin = snr / t - 1.0;
    a.set(id_margin_, margin);
    a.set(id_threshold_, t);  // essential: the closed-form solve reads T (solver.cpp)
    if (!a.full_detail()) return;
    // At a solved limit the margin is zero to rounding; 1e-9 keeps that point on the detected side.
    a.set(id_detected_, indicator(margin >= -1e-9));
    if (with_false_alarm_) {
      const V p_fa = a.param(false_alarm_);
      a.set(*id_false_alarm_, p_fa);
      V pd = broadcast<V>(0.0);
      if constexpr (std::is_same_v<V, double>) pd = physics::detection_probability_at(snr, p_fa);
      else for (int i = 0; i < lane_count; ++i) pd(i) = physics::detection_probability_at(snr(i), p_fa(i));
      a.set(*id_detection_probability_, pd);
    }
  }

  double threshold_for(double detection, double false_alarm) {
    if (detection != cached_[0] || false_alarm != cached_[1])
      cached_[0] = detection, cached_[1] = false_alarm, cached_[2] = physics::snr_threshold_for(detection, false_alarm);
    return cached_[2];
  }

  const double *threshold_, *detection_, *false_alarm_;
  bool from_probabilities_ = false, with_false_alarm_ = false;
  double cached_[3] = {-1, -1, 0};  // P_d, P_fa, T
  ResultId snr_{}, id_threshold_{}, id_margin_{}, id_detected_{};
  std::optional<ResultId> id_false_alarm_, id_detection_probability_;
};

}  // namespace

RADCHAIN_PLUGIN(SnrThreshold, {
    .summary = "detection when SNR ≥ T; T given or from P_d and P_fa (Gaussian)",
    .reference = "Pan et al. 2010 eqs. (10)-(11); Gaussian detection theory",
    .schema = schema,
    .publishes = {vocabulary::criterion_threshold, vocabulary::criterion_margin},
    .needs = {vocabulary::detector_snr},
    .inverse = InverseForm::noise_equation,
})

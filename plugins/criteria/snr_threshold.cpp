// Detection when SNR ≥ T (Pan 2010 eq. 10). T is given, or follows from the detection and false-alarm
// probabilities for a known signal in Gaussian noise: T = z(1 - P_fa) + z(P_d), z the standard normal
// quantile (Boost.Math). The margin SNR - T is what a [[solve]] drives to zero.
#include "radchain/plugin.hpp"

#include <boost/math/distributions/normal.hpp>

namespace {
using namespace radchain;

const Schema& schema() {
  static const Schema s = {
      number("threshold", "5").above(0).described("SNR threshold T (give this, or both probabilities)"),
      number("detection_probability", "0.99").above(0).below(1).described("required P_d (with false_alarm_probability)"),
      number("false_alarm_probability", "0.01").above(0).below(1).described("allowed P_fa (with detection_probability)"),
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
    if (probabilities) {
      const boost::math::normal unit_normal;
      from_probabilities_ = boost::math::quantile(unit_normal, 1.0 - p.get("false_alarm_probability")) +
                            boost::math::quantile(unit_normal, p.get("detection_probability"));
    }
  }

  void prepare(Context& c) override {
    snr_ = c.require("detector.snr");
    id_threshold_ = c.declare("threshold", "1", from_probabilities_ ? "T = z(1 - P_fa) + z(P_d), Gaussian" : "input T");
    id_margin_ = c.declare("margin", "1", "SNR - T (Pan 2010 eq. 10)");
    id_detected_ = c.declare("detected", "1", "1 if SNR ≥ T");
  }

  void evaluate(Context& c) override {
    const double t = from_probabilities_ ? *from_probabilities_ : *threshold_;
    const double margin = c.results.value(snr_) - t;
    c.results.set(id_threshold_, t);
    c.results.set(id_margin_, margin);
    c.results.set(id_detected_, margin >= 0 ? 1.0 : 0.0);
  }

 private:
  const double* threshold_;
  std::optional<double> from_probabilities_;
  ResultId snr_{}, id_threshold_{}, id_margin_{}, id_detected_{};
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

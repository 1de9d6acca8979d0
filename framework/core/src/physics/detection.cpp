#include "radchain/physics/detection.hpp"

#include <boost/math/distributions/normal.hpp>

#include <stdexcept>

namespace radchain::physics {

namespace {
const boost::math::normal unit_normal;
}

double standard_normal_cdf(double x) { return boost::math::cdf(unit_normal, x); }

double standard_normal_tail(double x) { return boost::math::cdf(boost::math::complement(unit_normal, x)); }

double standard_normal_quantile(double probability) {
  if (!(probability > 0.0 && probability < 1.0))
    throw std::domain_error("standard_normal_quantile: the probability must lie in (0, 1)");
  return boost::math::quantile(unit_normal, probability);
}

double snr_threshold_for(double detection_probability, double false_alarm_probability) {
  if (!(false_alarm_probability > 0.0 && false_alarm_probability < 1.0))
    throw std::domain_error("snr_threshold_for: the false-alarm probability must lie in (0, 1)");
  // z(1 − P_fa) from the complement, so that a tiny P_fa keeps its digits.
  const double decision_level = boost::math::quantile(boost::math::complement(unit_normal, false_alarm_probability));
  return decision_level + standard_normal_quantile(detection_probability);
}

double detection_probability_at(double snr, double false_alarm_probability) {
  if (!(false_alarm_probability > 0.0 && false_alarm_probability < 1.0))
    throw std::domain_error("detection_probability_at: the false-alarm probability must lie in (0, 1)");
  const double decision_level = boost::math::quantile(boost::math::complement(unit_normal, false_alarm_probability));
  return standard_normal_cdf(snr - decision_level);
}

double false_alarm_probability_at(double snr, double detection_probability) {
  return standard_normal_tail(snr - standard_normal_quantile(detection_probability));
}

}  // namespace radchain::physics

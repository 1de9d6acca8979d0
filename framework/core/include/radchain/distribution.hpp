#pragma once
// Input distributions, in a parameter's units: what `radchain uncertainty --vary` and a sensor file's
// [uncertainty] section say about an input's tolerance.
//   normal(mean, sd)          Gaussian
//   uniform(lo, hi)           flat on [lo, hi]
//   lognormal(mean, sd)       exp of a Gaussian, given by the mean and standard deviation of the value itself
//   triangular(lo, mode, hi)  triangular
//   truncated(D, lo, hi)      any of the above restricted to [lo, hi] and renormalised (a tolerance that cannot
//                             leave its physical range, e.g. a transmittance ≤ 1): truncated(normal(0.9, 0.05), 0, 1)
// Each number carries its unit as --set takes it ("9 e-"); plain numbers for dimensionless keys.
#include "radchain/chain.hpp"

#include <string>

namespace radchain {

struct Distribution {
  enum class Kind { normal, uniform, lognormal, triangular };
  Kind kind = Kind::normal;
  double a = 0, b = 0, c = 0;  // SI: normal (mean, sd), uniform (lo, hi), lognormal (mean, sd), triangular (lo, mode, hi)
  // Truncation to [lo, hi] (set by truncate()): samples are the parent's quantiles over [F(lo), F(hi)].
  bool truncated = false;
  double lo = 0, hi = 0;
  double cdf_lo = 0, cdf_hi = 1, survival_lo = 1, survival_hi = 0, truncated_mean = 0, truncated_sd = 0;  // by truncate()
  double mean() const;
  double sd() const;
  double quantile(double u) const;  // u in (0, 1)
  double cdf(double x) const;       // of the distribution before truncation: F(x)
  double survival(double x) const;  // 1 − F(x), without cancellation in the upper tail
  // Restricts to [lo, hi] and returns the probability the parent gives that interval. Below
  // least_truncated_probability nothing is truncated (`truncated` stays false) and the caller refuses it.
  static constexpr double least_truncated_probability = 1e-6;
  double truncate(double lo, double hi);
  // The probabilities u the samples of `radchain uncertainty` are drawn at lie in [least_u, greatest_u]
  // (sample_uniform). parse_varied_input refuses a distribution whose quantile at either end, mean or sd is not a
  // finite double; the quantile is monotonic, so every sample is then finite.
  static constexpr double least_u = 0x1.0p-54, greatest_u = 1 - 0x1.0p-53;

 private:
  double parent_mean() const;
  double parent_sd() const;
  double parent_quantile(double u) const;        // x with F(x) = u
  double parent_upper_quantile(double q) const;  // x with 1 − F(x) = q
};

struct VariedInput {
  std::string key;        // "optics.transmittance"
  std::string as_written; // "normal(0.56, 0.02)"
  std::string unit;       // SI unit of the key ("1" for a number)
  Distribution distribution;
};

// Parses `spec_text` ("normal(0.56, 0.02)") for `key`, a numeric, non-spectral, unsolved parameter of `chain`.
// Throws InputError at `where` (context: "" for the command line, "[uncertainty]" for a sensor file).
VariedInput parse_varied_input(Chain& chain, const std::string& key, const std::string& spec_text, const SourceLocation& where,
                               const std::string& context);

}  // namespace radchain

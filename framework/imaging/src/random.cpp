#include "random.hpp"

#include <algorithm>
#include <cmath>

namespace radchain::render::detail {

void Random::fill(std::uint64_t* out, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) out[i] = engine_();
}

double Random::normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  double u = 0, v = 0, s = 0;
  do {
    u = 2.0 * uniform() - 1.0;
    v = 2.0 * uniform() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double f = std::sqrt(-2.0 * std::log(s) / s);
  spare_ = v * f;
  has_spare_ = true;
  return u * f;
}

std::int64_t Random::poisson(double mean) {
  if (!(mean > 0.0)) return 0;
  if (mean >= 1e15) {
    // Beyond any well: the normal limit (relative error ~1e-8), kept inside the integer range.
    return static_cast<std::int64_t>(std::min(std::round(mean + std::sqrt(mean) * normal()), 9e18));
  }
  if (mean >= 10.0) return poisson_ptrs(mean);
  // P(0) = e^-μ, P(k) = P(k-1) μ/k; the first k whose cumulative sum exceeds u.
  const double u = uniform();
  double p = std::exp(-mean), cdf = p;
  std::int64_t k = 0;
  while (u >= cdf) {
    ++k;
    p *= mean / static_cast<double>(k);
    cdf += p;
    if (p < 1e-18 * cdf) break;  // the tail no longer moves the sum: u sits in the last ulp of 1
  }
  return k;
}

std::int64_t Random::poisson_ptrs(double mean) {
  // Hörmann 1993, algorithm PTRS (constants from the paper).
  const double root = std::sqrt(mean), log_mean = std::log(mean);
  const double b = 0.931 + 2.53 * root;
  const double a = -0.059 + 0.02483 * b;
  const double inv_alpha = 1.1239 + 1.1328 / (b - 3.4);
  const double v_r = 0.9277 - 3.6224 / (b - 2.0);
  for (;;) {
    const double u = uniform_open() - 0.5;
    const double v = uniform_open();
    const double us = 0.5 - std::abs(u);
    const double k = std::floor((2.0 * a / us + b) * u + mean + 0.43);
    if (us >= 0.07 && v <= v_r) return static_cast<std::int64_t>(k);
    if (k < 0.0 || (us < 0.013 && v > us)) continue;
    if (std::log(v) + std::log(inv_alpha) - std::log(a / (us * us) + b) <= -mean + k * log_mean - std::lgamma(k + 1.0))
      return static_cast<std::int64_t>(k);
  }
}

}  // namespace radchain::render::detail

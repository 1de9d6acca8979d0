#include "noise_law.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace radchain::render::detail {

namespace {

// Φ(x) without cancellation in either tail.
double phi(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

constexpr double infinity = std::numeric_limits<double>::infinity();

std::int64_t dn_of(double electrons, const PixelLaw& law) {
  const double dn = std::floor(electrons / law.gain + law.offset_dn + 0.5);
  return static_cast<std::int64_t>(std::clamp(dn, 0.0, law.max_dn));
}

}  // namespace

double DiscreteLaw::tail_above(double x) const {
  double sum = 0;
  for (std::size_t i = 0; i < pmf.size(); ++i)
    if (static_cast<double>(first + static_cast<std::int64_t>(i)) > x) sum += pmf[i];
  return sum;
}

double DiscreteLaw::mean() const {
  double sum = 0;
  for (std::size_t i = 0; i < pmf.size(); ++i) sum += pmf[i] * static_cast<double>(first + static_cast<std::int64_t>(i));
  return sum;
}

DiscreteLaw poisson_law(double mean) {
  DiscreteLaw law;
  if (!(mean > 0)) {
    law.pmf = {1.0};
    return law;
  }
  const double spread = 12.0 * std::sqrt(mean) + 12.0;
  const auto lo = static_cast<std::int64_t>(std::max(0.0, std::floor(mean - spread)));
  const auto hi = static_cast<std::int64_t>(std::ceil(mean + spread));
  law.first = lo;
  law.pmf.resize(static_cast<std::size_t>(hi - lo + 1));
  const double log_mean = std::log(mean);
  double total = 0;
  for (std::int64_t k = lo; k <= hi; ++k) {
    const double kd = static_cast<double>(k);
    const double p = std::exp(-mean + kd * log_mean - std::lgamma(kd + 1.0));
    law.pmf[static_cast<std::size_t>(k - lo)] = p;
    total += p;
  }
  for (double& p : law.pmf) p /= total;
  return law;
}

DiscreteLaw dn_law(const PixelLaw& law) {
  if (!(law.gain > 0)) throw std::invalid_argument("dn_law: the gain must be positive");
  const DiscreteLaw counts = poisson_law(law.poisson_mean);
  const double spread = 12.0 * law.read_sigma;
  const double last = static_cast<double>(counts.first + static_cast<std::int64_t>(counts.pmf.size()) - 1);
  const double collected_lo = std::min(static_cast<double>(counts.first) + law.constant, law.full_well);
  const double collected_hi = std::min(last + law.constant, law.full_well);
  const std::int64_t k_lo = dn_of(collected_lo - spread, law);
  const std::int64_t k_hi = dn_of(collected_hi + spread, law);
  DiscreteLaw out;
  out.first = k_lo;
  out.pmf.assign(static_cast<std::size_t>(k_hi - k_lo + 1), 0.0);
  for (std::size_t i = 0; i < counts.pmf.size(); ++i) {
    const double p = counts.pmf[i];
    if (p == 0) continue;
    const double collected = std::min(static_cast<double>(counts.first + static_cast<std::int64_t>(i)) + law.constant, law.full_well);
    if (law.read_sigma <= 0) {
      out.pmf[static_cast<std::size_t>(dn_of(collected, law) - k_lo)] += p;
      continue;
    }
    // DN = k  <=>  (k − offset − ½) g ≤ e < (k − offset + ½) g, the ends open (the ADC clips).
    const std::int64_t a = dn_of(collected - spread, law), b = dn_of(collected + spread, law);
    for (std::int64_t k = a; k <= b; ++k) {
      const double lower = k == 0 ? -infinity : (static_cast<double>(k) - law.offset_dn - 0.5) * law.gain;
      const double upper = static_cast<double>(k) >= law.max_dn ? infinity : (static_cast<double>(k) - law.offset_dn + 0.5) * law.gain;
      // Φ differences taken on the side of the smaller tail (no cancellation far from the mean).
      const double zl = (lower - collected) / law.read_sigma, zu = (upper - collected) / law.read_sigma;
      const double mass = zl > 0 ? phi(-zl) - phi(-zu) : phi(zu) - phi(zl);
      out.pmf[static_cast<std::size_t>(k - k_lo)] += p * mass;
    }
  }
  double total = 0;
  for (double p : out.pmf) total += p;
  for (double& p : out.pmf) p /= total;
  return out;
}

DiscreteLaw sum_law(const DiscreteLaw& a, const DiscreteLaw& b) {
  DiscreteLaw out;
  out.first = a.first + b.first;
  out.pmf.assign(a.pmf.size() + b.pmf.size() - 1, 0.0);
  for (std::size_t i = 0; i < a.pmf.size(); ++i)
    for (std::size_t j = 0; j < b.pmf.size(); ++j) out.pmf[i + j] += a.pmf[i] * b.pmf[j];
  return out;
}

AliasTable::AliasTable(const DiscreteLaw& law) {
  if (law.pmf.empty()) throw std::invalid_argument("AliasTable: empty law");
  unsigned m = 1;
  while ((std::size_t{1} << m) < law.pmf.size()) ++m;
  if (m > 24) throw std::invalid_argument("AliasTable: more than 2^24 values");
  const std::size_t k = std::size_t{1} << m;
  shift_ = 32 - m;
  mask_ = static_cast<std::uint32_t>((std::uint64_t{1} << shift_) - 1);
  double total = 0;
  for (double p : law.pmf) total += p;
  // Vose: cells scaled to mean 1; small ones take an alias from large ones, in index order (deterministic).
  std::vector<double> scaled(k, 0.0);
  for (std::size_t i = 0; i < law.pmf.size(); ++i) scaled[i] = law.pmf[i] / total * static_cast<double>(k);
  std::vector<std::size_t> small, large, alias(k);
  for (std::size_t i = k; i-- > 0;) (scaled[i] < 1.0 ? small : large).push_back(i);
  std::vector<double> keep(k, 1.0);
  while (!small.empty() && !large.empty()) {
    const std::size_t s = small.back(), l = large.back();
    small.pop_back();
    keep[s] = scaled[s];
    alias[s] = l;
    scaled[l] = (scaled[l] + scaled[s]) - 1.0;
    if (scaled[l] < 1.0) {
      large.pop_back();
      small.push_back(l);
    }
  }
  for (std::size_t i : small) keep[i] = 1.0, alias[i] = i;  // rounding leftovers: probability 1 within the cell
  for (std::size_t i : large) keep[i] = 1.0, alias[i] = i;
  const double scale = static_cast<double>(std::uint64_t{1} << shift_);
  cells_.resize(k);
  for (std::size_t i = 0; i < k; ++i) {
    const double t = std::clamp(std::round(keep[i] * scale), 0.0, scale);
    cells_[i].threshold = t >= scale ? mask_ : static_cast<std::uint32_t>(t);
    // keep = 1 must always pick the value: the fraction is at most mask_, so compare "<" against mask_ + 1 — not
    // representable; use the value as its own alias instead.
    if (t >= scale) alias[i] = i;
    cells_[i].value[0] = static_cast<float>(law.first + static_cast<std::int64_t>(i));
    cells_[i].value[1] = static_cast<float>(law.first + static_cast<std::int64_t>(alias[i]));
  }
}

InverseSampler::InverseSampler(const DiscreteLaw& law) : first_(law.first) {
  if (law.pmf.empty()) throw std::invalid_argument("InverseSampler: empty law");
  cdf_.resize(law.pmf.size());
  double sum = 0;
  for (std::size_t i = 0; i < law.pmf.size(); ++i) cdf_[i] = (sum += law.pmf[i]);
  for (double& c : cdf_) c /= sum;
  cdf_.back() = 1.0;  // u < 1 always stops the search
  guide_.resize(std::max<std::size_t>(16, 2 * cdf_.size()));
  std::size_t i = 0;
  for (std::size_t j = 0; j < guide_.size(); ++j) {
    const double level = static_cast<double>(j) / static_cast<double>(guide_.size());
    while (cdf_[i] <= level) ++i;
    guide_[j] = static_cast<std::uint32_t>(i);
  }
}

}  // namespace radchain::render::detail

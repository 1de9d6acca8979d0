#pragma once
// The law of one pixel's value under the renderer's model (private to framework/src/render):
//   n = Poisson(μ) + c, n = min(n, well);  e = n + σ Z;  DN = clamp(floor(e/g + offset + ½), 0, max)
// tabulated exactly (Poisson terms beyond 12 standard deviations and normal tails below 1e-300 dropped), and
// sampled by inversion with a guide table (Chen & Asau 1974; Devroye 1986 §III.2.4): one uniform per value.
#include "random.hpp"

#include <cstdint>
#include <limits>
#include <vector>

namespace radchain::render::detail {

struct PixelLaw {
  double poisson_mean = 0;  // μ: what fluctuates as counts
  double constant = 0;      // c: means whose fluctuation is switched off
  double full_well = std::numeric_limits<double>::infinity();
  double read_sigma = 0;    // σ
  double gain = 1;          // g, electrons per DN
  double offset_dn = 0;
  double max_dn = 4095;
};

// Probabilities of consecutive integers first, first + 1, ...
struct DiscreteLaw {
  std::int64_t first = 0;
  std::vector<double> pmf;
  // P(X > x)
  double tail_above(double x) const;
  double mean() const;
};

// Poisson counts of mean μ.
DiscreteLaw poisson_law(double mean);
// The DN of a pixel (the ADC on).
DiscreteLaw dn_law(const PixelLaw& law);
// The sum of independent values (convolution).
DiscreteLaw sum_law(const DiscreteLaw& a, const DiscreteLaw& b);

// Walker's alias method (A. J. Walker, ACM TOMS 3 (1977) 253; built with Vose's algorithm, IEEE TSE 17 (1991)
// 972) on 32 random bits: the top m bits pick one of 2^m cells, the other 32 − m bits decide between the cell's
// value and its alias. Each value's probability is represented to within 2^-32 (values rarer than that per draw
// are not drawn). No loop and no unpredictable branch: the fast path for most pixels of a frame.
class AliasTable {
 public:
  AliasTable() = default;
  explicit AliasTable(const DiscreteLaw& law);
  float operator()(std::uint32_t bits) const {
    const Cell& c = cells_[bits >> shift_];
    return c.value[(bits & mask_) >= c.threshold];  // an index, not a branch
  }

 private:
  struct Cell {
    std::uint32_t threshold = 0;
    float value[2] = {0, 0};  // the cell's value, its alias
  };
  std::vector<Cell> cells_;
  unsigned shift_ = 31;
  std::uint32_t mask_ = 0x7fffffffu;
};

class InverseSampler {
 public:
  InverseSampler() = default;
  explicit InverseSampler(const DiscreteLaw& law);
  std::int64_t operator()(Random& random) const {
    const double u = random.uniform();
    std::size_t i = guide_[static_cast<std::size_t>(u * static_cast<double>(guide_.size()))];
    while (cdf_[i] <= u) ++i;
    return first_ + static_cast<std::int64_t>(i);
  }

 private:
  std::int64_t first_ = 0;
  std::vector<double> cdf_;          // cdf_.back() == 1 exactly
  std::vector<std::uint32_t> guide_; // guide_[j] = first i with cdf_[i] > j / guide_.size()
};

}  // namespace radchain::render::detail

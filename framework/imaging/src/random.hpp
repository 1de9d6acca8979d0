#pragma once
// Random numbers for the renderer (private to framework/src/render). std::mt19937_64's output sequence is fixed
// by the C++ standard ([rand.predef]: the 10000th output of a default-constructed engine is
// 9981545732273789042), so with the distributions below a seed gives the same numbers with any standard library.
// std::poisson_distribution and std::normal_distribution are implementation-defined: they would reproduce a
// frame only within one libstdc++. (The transcendental functions log/exp/lgamma come from the C library; glibc's
// are correctly rounded in practice, another libm could differ in the last bit, which moves a sample only when
// an acceptance test is that close.)
#include <cstddef>
#include <cstdint>
#include <random>

namespace radchain::render::detail {

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}

  std::uint64_t bits() { return engine_(); }
  // The next n outputs of the engine (the same numbers n calls of bits() would give), in a tight loop.
  void fill(std::uint64_t* out, std::size_t n);
  // [0, 1) on a 2^-53 grid.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  // (0, 1): the same grid shifted by half a step, never 0 or 1.
  double uniform_open() { return (static_cast<double>(engine_() >> 11) + 0.5) * 0x1.0p-53; }
  // Standard normal: Marsaglia & Bray's polar method (SIAM Review 6 (1964) 260), the second value kept.
  double normal();
  // Poisson of mean μ ≥ 0: inversion by sequential search below μ = 10 (Devroye 1986, Non-Uniform Random
  // Variate Generation, §X.3), Hörmann's transformed rejection with squeeze PTRS above (W. Hörmann, "The
  // transformed rejection method for generating Poisson random variables", Insurance: Mathematics and
  // Economics 12 (1993) 39); above 1e15 (no detector holds that many) the normal limit.
  std::int64_t poisson(double mean);

 private:
  std::int64_t poisson_ptrs(double mean);
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace radchain::render::detail

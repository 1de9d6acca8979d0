#pragma once
// Input distributions, in a parameter's units: what `radchain uncertainty --vary` and a sensor file's
// [uncertainty] section say about an input's tolerance.
//   normal(mean, sd)          Gaussian
//   uniform(lo, hi)           flat on [lo, hi]
//   lognormal(mean, sd)       exp of a Gaussian, given by the mean and standard deviation of the value itself
//   triangular(lo, mode, hi)  triangular
// Each number carries its unit as --set takes it ("9 e-"); plain numbers for dimensionless keys.
#include "radchain/chain.hpp"

#include <string>

namespace radchain {

struct Distribution {
  enum class Kind { normal, uniform, lognormal, triangular };
  Kind kind = Kind::normal;
  double a = 0, b = 0, c = 0;  // SI: normal (mean, sd), uniform (lo, hi), lognormal (mean, sd), triangular (lo, mode, hi)
  double mean() const;
  double sd() const;
  double quantile(double u) const;  // u in (0, 1)
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

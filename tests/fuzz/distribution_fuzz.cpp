// Input distributions as `radchain uncertainty --vary KEY=DIST` takes them (the grammar of a sensor file's
// [uncertainty] values too: normal, uniform, lognormal, triangular, truncated(D, lo, hi), each number with the
// key's unit): one input line per --vary, parsed by parse_vary against sensors/msx-sbv.toml. Each accepted
// distribution is then sampled as run_uncertainty samples it (quantile at sample_uniform(seed 1, k, j)), plus the
// two ends of sample_uniform's range, where extreme parameters (far tails, huge or tiny spreads) break first.
// A finding: anything but InputError escaping for bad input; an accepted distribution whose mean, standard
// deviation or a sample is NaN or infinite, or a truncated sample outside [lo, hi]; a sanitizer report; a hang.
#include "fuzz_input.hpp"

#include "radchain/batch/uncertainty.hpp"
#include "radchain/distribution.hpp"
#include "radchain/error.hpp"
#include "radchain/sensor_file.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <sstream>

namespace {

std::optional<radchain::Chain> chain;

[[noreturn]] void finding(const std::string& line, const char* what, double value) {
  std::fprintf(stderr, "distribution_fuzz: --vary \"%s\": %s = %g\n", line.c_str(), what, value);
  std::abort();
}

void sample(const std::string& line, const radchain::Distribution& d, std::uint64_t input) {
  auto finite = [&](const char* what, double value) {
    if (!std::isfinite(value)) finding(line, what, value);
  };
  finite("mean", d.mean());
  finite("sd", d.sd());
  if (!(d.sd() >= 0)) finding(line, "sd", d.sd());
  auto draw = [&](double u) {
    const double x = d.quantile(u);
    finite("a sample", x);
    if (d.truncated && !(x >= d.lo && x <= d.hi)) finding(line, "a truncated sample outside [lo, hi]", x);
  };
  // The ends of sample_uniform's range, then what it draws.
  draw(radchain::Distribution::least_u);
  draw(radchain::Distribution::greatest_u);
  for (std::uint64_t k = 0; k < 8; ++k) draw(radchain::sample_uniform(1, k, input));
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  radchain::fuzz::configure_host();
  chain.emplace(radchain::load_sensor(RADCHAIN_SOURCE_DIR "/sensors/msx-sbv.toml"));
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream lines{std::string(radchain::fuzz::as_text(data, size))};
  std::uint64_t input = 0;
  // A few --vary per input: each truncated(...) integrates its moments, so many lines only slow the fuzzer down.
  for (std::string line; input < 8 && std::getline(lines, line); ++input) {
    try {
      const radchain::VariedInput v = radchain::parse_vary(*chain, line);
      sample(line, v.distribution, input);
    } catch (const radchain::InputError&) {
    }
  }
  return 0;
}

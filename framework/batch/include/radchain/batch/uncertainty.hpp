#pragma once
// `radchain uncertainty`: Monte Carlo propagation of input uncertainties through the chain (its solves re-run at
// every sample), beside the linear (first-order) propagation from the budget's derivatives.
//
// The inputs: the sensor file's [uncertainty] section, and `--vary "optics.transmittance=normal(0.56, 0.02)"`
// (which replaces the file's distribution of the same key): distributions in the key's units
// (radchain/distribution.hpp).
// Sample k's value of input j is the distribution's quantile at u = hash(seed, k, j) (SplitMix64, a counter-based
// generator): a sample does not depend on which thread ran it or on the samples before it, so the output is the
// same for any --threads. A sample outside an input's accepted range, or whose evaluation or solve fails, is left
// out of the statistics and counted.
//
// Linear propagation: σ_r² ≈ Σ_j (∂r/∂x_j)² σ_j², with ∂r/∂x_j from compute_budget (Ridders) at the inputs'
// means — exact for a chain that is linear in the inputs over their spread (ISO GUM, JCGM 100:2008 §5.1.2, the law
// of propagation of uncertainty for uncorrelated inputs).
#include "radchain/chain.hpp"
#include "radchain/distribution.hpp"
#include "radchain/batch/table.hpp"

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace radchain {

// Parses "key=dist(args)" for a numeric, non-spectral, unsolved parameter of `chain`. Throws InputError (one line).
VariedInput parse_vary(Chain& chain, const std::string& text);

// Uniform u in [Distribution::least_u, greatest_u] ⊂ (0, 1) for sample `sample`, input `input` (SplitMix64 of the
// three; 53 bits).
double sample_uniform(std::uint64_t seed, std::uint64_t sample, std::uint64_t input);

struct UncertaintyOptions {
  std::string sensor_file;
  std::vector<Override> overrides;
  bool no_solve = false;
  SolverChoice solver = SolverChoice::automatic;
  std::vector<std::string> vary;      // "key=dist(args)"
  std::vector<std::string> results;   // at least one
  std::size_t samples = 1000;
  // The error of a Monte Carlo estimate falls as 1/√N: 10⁶ samples put a percentile within 0.1 % of σ. More than
  // max_samples (gigabytes of samples kept for the percentiles) is refused.
  static constexpr std::size_t max_samples = 10'000'000;
  std::uint64_t seed = 1;
};

struct ResultStatistics {
  std::string name, unit;            // SI unit
  double nominal = 0;                // at the inputs' means
  double mean = 0, sd = 0, p5 = 0, p50 = 0, p95 = 0;
  double linear_sd = 0;              // first-order propagation
  std::vector<double> correlation;   // Pearson, per varied input
  std::vector<double> derivative;    // ∂r/∂x_j at the means (SI)
  std::vector<double> linear_part;   // |∂r/∂x_j| σ_j
  std::vector<double> values;        // the used samples' values (SI), in sample order
};

// Equal-width bins over [min, max] of `values`: bins = ⌈√n⌉ clamped to [5, 60] (the square-root choice), edges[k],
// edges[k+1] bound counts[k]; the maximum falls in the last bin (all
// values equal: a range of 1e-9 relative, everything in the first bin).
struct Histogram {
  std::vector<double> edges;
  std::vector<std::size_t> counts;
};
Histogram histogram_of(const std::vector<double>& values);

struct Uncertainty {
  std::string sensor_file, sensor_name;
  std::vector<VariedInput> inputs;
  std::vector<ResultStatistics> results;
  std::size_t samples = 0, used = 0, out_of_range = 0, failed = 0;
  std::string first_failure;
};

// Throws InputError for bad input.
Uncertainty run_uncertainty(const UncertaintyOptions& options);

std::string format_uncertainty_text(const Uncertainty& u);
// CSV / JSON: columns result, input, statistic, value, unit (input "" for the result's own statistics);
// uncertainty_table() has the rows with their numbers as they are (Python binds these).
TableData uncertainty_table(const Uncertainty& u);
void write_uncertainty(const Uncertainty& u, TableFormat format, std::ostream& out);

}  // namespace radchain

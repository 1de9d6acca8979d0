#pragma once
// A stage's throughput as a list of tabulated curves: `transmittance_curve = ["m1.csv", "m2.csv",
// "filter.csv"]`, `qe_curve = ["window.csv", "qe.csv"]`. Validation multiplies the list into the key's spectrum
// (schema.cpp); these helpers give each component, and the product, as a result: its mean over a band,
//   τ̄_k = ∫_a^b τ_k(λ) dλ / (b − a),
// the unweighted band average a datasheet or a throughput budget quotes per component.
#include "radchain/plugin.hpp"

#include <string_view>
#include <utility>
#include <vector>

namespace radchain {

// The band [lo, hi] where `curve` is at least `fraction` of its peak (first and last such grid points): the
// passband of a stack of components that includes a filter (1 %: the usual cut-on/cut-off of a filter spec).
std::pair<double, double> passband_m(const Spectrum& curve, double fraction = 0.01);

struct ComponentMean {
  ResultId id{};
  double mean = 0;
};

// Declares "<key>_<k>" (k = 1…, each file of the list, named in the equation) and, for two or more, "<key>_product",
// each the mean over [lo_m, hi_m]; the values are the returned means (constant: they change when the spectral phase
// re-runs). Nothing when the key is not given.
std::vector<ComponentMean> declare_component_means(Context& context, const Params& params, std::string_view key,
                                                   double lo_m, double hi_m);

}  // namespace radchain

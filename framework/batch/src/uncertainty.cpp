// `radchain uncertainty`: Monte Carlo over input distributions, solves re-run at every sample, on all cores; the
// linear propagation from the budget's derivatives beside it.
#include "radchain/batch/uncertainty.hpp"
#include "radchain/strings.hpp"

#include "radchain/batch/budget.hpp"
#include "radchain/batch/run_batch.hpp"
#include "radchain/batch/thread_pool.hpp"
#include "radchain/error.hpp"
#include "radchain/units.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <ostream>

namespace radchain {
namespace {
using strings::trimmed;


std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

const double nan = std::numeric_limits<double>::quiet_NaN();

}  // namespace

double sample_uniform(std::uint64_t seed, std::uint64_t sample, std::uint64_t input) {
  const std::uint64_t h = splitmix64(splitmix64(splitmix64(seed) ^ sample) ^ (input + 0x632be59bd9b4e019ULL));
  // (0, 1): the top 53 bits plus ½, times 2⁻⁵³. At 2⁵³ − 1 the sum rounds to 2⁵³ (ties to even), which would be
  // u = 1 exactly, where Φ⁻¹ is infinite; that one value becomes the largest double below 1.
  return std::min((static_cast<double>(h >> 11) + 0.5) * 0x1.0p-53, Distribution::greatest_u);
}

VariedInput parse_vary(Chain& chain, const std::string& text) {
  const auto eq = text.find('=');
  const std::string key = trimmed(eq == std::string::npos ? text : text.substr(0, eq));
  if (eq == std::string::npos || key.empty())
    throw InputError(SourceLocation{"--vary", 0, 0}, "", text,
                     "expected <section>.<key>=<distribution>, e.g. optics.transmittance=\"normal(0.56, 0.02)\"");
  return parse_varied_input(chain, key, trimmed(text.substr(eq + 1)), SourceLocation{"--vary " + key, 0, 0}, "");
}

Uncertainty run_uncertainty(const UncertaintyOptions& options) {
  if (options.samples < 2)
    throw InputError(SourceLocation{"--samples", 0, 0}, "", std::to_string(options.samples), "at least 2 samples");
  if (options.samples > UncertaintyOptions::max_samples)
    throw InputError(SourceLocation{"--samples", 0, 0}, "", std::to_string(options.samples),
                     fmt::format("at most {} samples (the estimates' error falls as 1/√N: 10⁶ samples give percentiles "
                                 "to 0.1 % of σ)", UncertaintyOptions::max_samples));
  auto load = [&] {
    Chain chain = load_sensor(options.sensor_file, options.overrides,
                              options.no_solve ? Solving::forward_only : Solving::as_written);
    chain.solver = options.solver;
    return chain;
  };
  Chain chain = load();
  Uncertainty u;
  u.sensor_file = chain.sensor_file;
  u.sensor_name = chain.sensor_name;
  // The file's [uncertainty] tolerances, then --vary: a --vary of a key the file already varies replaces it.
  for (const auto& t : chain.uncertainties) u.inputs.push_back(parse_varied_input(chain, t.key, t.text, t.where, "[uncertainty]"));
  const std::size_t from_file = u.inputs.size();
  for (const auto& text : options.vary) {
    VariedInput v = parse_vary(chain, text);
    const auto same = std::find_if(u.inputs.begin(), u.inputs.end(), [&](const VariedInput& w) { return w.key == v.key; });
    if (same != u.inputs.end() && same - u.inputs.begin() >= static_cast<std::ptrdiff_t>(from_file))
      throw InputError(SourceLocation{"--vary " + v.key, 0, 0}, "", text, "the key is varied twice");
    if (same != u.inputs.end()) *same = std::move(v);
    else u.inputs.push_back(std::move(v));
  }
  if (u.inputs.empty())
    throw InputError(SourceLocation{"--vary", 0, 0}, "", "",
                     "nothing to vary: the file has no [uncertainty] section; give --vary key=dist(...), e.g. --vary "
                     "\"optics.transmittance=normal(0.56, 0.02)\"");
  const std::size_t ni = u.inputs.size(), nr = options.results.size();
  // The nominal point: every varied input at its mean; the budget there gives the linear propagation.
  for (const auto& v : u.inputs) chain.set(chain.parameter(v.key), v.distribution.mean());
  BudgetOptions budget_options;
  budget_options.results = options.results;
  Budget budget;
  try {
    budget = compute_budget(chain, budget_options);  // checks the result names (InputError)
  } catch (const InputError&) {
    throw;
  } catch (const std::runtime_error& error) {
    throw InputError(SourceLocation{options.sensor_file, 0, 0}, "", "", std::string("at the inputs' means: ") + error.what());
  }
  u.results.resize(nr);
  for (std::size_t k = 0; k < nr; ++k) {
    ResultStatistics& s = u.results[k];
    s.name = options.results[k];
    s.nominal = budget.nominal[k];
    s.derivative.assign(ni, nan);
    s.linear_part.assign(ni, nan);
    double variance = 0;
    bool linear_ok = true;
    for (std::size_t j = 0; j < ni; ++j) {
      for (const auto& e : budget.entries)
        if (e.result == s.name && e.parameter == u.inputs[j].key) {
          s.unit = e.result_unit;
          if (e.ok) s.derivative[j] = e.derivative;
        }
      s.linear_part[j] = std::abs(s.derivative[j]) * u.inputs[j].distribution.sd();
      if (std::isnan(s.linear_part[j])) linear_ok = false;
      variance += s.linear_part[j] * s.linear_part[j];
    }
    s.linear_sd = linear_ok ? std::sqrt(variance) : nan;
    if (s.unit.empty()) s.unit = chain.results().info(*chain.results().find(s.name)).si_unit;
  }

  // The samples: inputs[k * ni + j], outputs[k * nr + r]; status per sample: 0 used, 1 out of range, 2 failed.
  const std::size_t n = options.samples;
  u.samples = n;
  std::vector<double> inputs(n * ni), outputs(n * nr, nan);
  std::vector<char> status(n, 0);
  std::vector<std::string> why(n);
  struct Worker {
    Chain chain;
    std::vector<ParameterRef> refs;
    std::vector<const ParamSpec*> specs;
    std::vector<std::pair<ParameterRef, double>> unknowns;
    std::vector<ResultId> ids;
    std::vector<SolveOutcome> outcomes;
  };
  std::vector<std::unique_ptr<Worker>> workers(worker_slots());
  run_batch(
      n, 16384, 16,
      [&](std::size_t slot, std::size_t begin, std::size_t end) {
        auto& w = workers[slot];
        if (!w) {
          w = std::make_unique<Worker>(Worker{load(), {}, {}, {}, {}, {}});
          for (const auto& v : u.inputs) {
            w->refs.push_back(w->chain.parameter(v.key));
            const StageSlot& s = w->chain.slot(v.key.substr(0, v.key.rfind('.')));
            w->specs.push_back(&s.params->entry(v.key.substr(v.key.rfind('.') + 1)).spec[0]);
          }
          for (const auto& s : w->chain.solves) {
            ParameterRef ref = w->chain.parameter(s.unknown);
            w->unknowns.emplace_back(ref, ref.value());
          }
          w->chain.evaluate();
          for (const auto& name : options.results) w->ids.push_back(*w->chain.results().find(name));
        }
        for (std::size_t k = begin; k < end; ++k) {
          bool in_range = true;
          for (std::size_t j = 0; j < ni; ++j) {
            const double x = u.inputs[j].distribution.quantile(sample_uniform(options.seed, k, j));
            inputs[k * ni + j] = x;
            if (!w->specs[j]->in_range(x)) in_range = false;
          }
          if (!in_range) {
            status[k] = 1;
            continue;
          }
          for (std::size_t j = 0; j < ni; ++j) w->chain.set(w->refs[j], inputs[k * ni + j]);
          for (const auto& [ref, value] : w->unknowns) w->chain.set(ref, value);
          try {
            if (w->chain.solves.empty()) {
              w->chain.evaluate(Detail::full);
            } else {
              w->chain.solve_all(w->outcomes);
              for (const auto& o : w->outcomes)
                if (!o.converged) throw std::runtime_error("the [[solve]] of " + o.spec.unknown + " failed: " + o.message);
            }
            for (std::size_t r = 0; r < nr; ++r) {
              outputs[k * nr + r] = w->chain.results().value(w->ids[r]);
              if (!std::isfinite(outputs[k * nr + r])) throw std::runtime_error(options.results[r] + " is not finite");
            }
          } catch (const std::exception& error) {
            status[k] = 2;
            why[k] = error.what();
          }
        }
      },
      [](std::size_t) {});

  // Statistics in sample order (the same sums for any thread count).
  std::vector<std::size_t> used;
  for (std::size_t k = 0; k < n; ++k) {
    if (status[k] == 0) used.push_back(k);
    if (status[k] == 1) ++u.out_of_range;
    if (status[k] == 2) {
      if (u.failed == 0) u.first_failure = fmt::format("sample {}: {}", k, why[k]);
      ++u.failed;
    }
  }
  u.used = used.size();
  // Statistics of fewer than 2 samples are NaN: a table of them is no answer. Every draw fell outside an input's
  // accepted range (a distribution centred past it, or far wider than it) or failed: bad input, said once.
  if (used.size() < 2 && u.failed == 0)
    throw InputError(SourceLocation{"--vary", 0, 0}, "", "",
                     fmt::format("{} of {} samples fell outside an input's accepted range, {} remain: no statistics; "
                                 "narrow the distributions or move them inside the ranges (`radchain describe`)",
                                 u.out_of_range, n, used.size()));
  const double m = static_cast<double>(used.size());
  std::vector<double> input_mean(ni, 0), input_sd(ni, 0);
  for (std::size_t j = 0; j < ni; ++j) {
    for (std::size_t k : used) input_mean[j] += inputs[k * ni + j];
    input_mean[j] /= m;
    for (std::size_t k : used) input_sd[j] += std::pow(inputs[k * ni + j] - input_mean[j], 2);
    input_sd[j] = std::sqrt(input_sd[j] / (m - 1));
  }
  for (std::size_t r = 0; r < nr; ++r) {
    ResultStatistics& s = u.results[r];
    s.correlation.assign(ni, nan);
    if (used.size() < 2) {
      s.mean = s.sd = s.p5 = s.p50 = s.p95 = nan;
      continue;
    }
    std::vector<double> y;
    for (std::size_t k : used) y.push_back(outputs[k * nr + r]);
    s.values = y;
    double sum = 0;
    for (double v : y) sum += v;
    s.mean = sum / m;
    double ss = 0;
    for (double v : y) ss += (v - s.mean) * (v - s.mean);
    s.sd = std::sqrt(ss / (m - 1));
    for (std::size_t j = 0; j < ni; ++j) {
      double sxy = 0;
      for (std::size_t i = 0; i < used.size(); ++i) sxy += (inputs[used[i] * ni + j] - input_mean[j]) * (y[i] - s.mean);
      const double denominator = (m - 1) * input_sd[j] * s.sd;
      s.correlation[j] = denominator > 0 ? sxy / denominator : nan;
    }
    // Percentiles: linear interpolation between order statistics (Hyndman & Fan 1996 type 7, NumPy's default).
    std::sort(y.begin(), y.end());
    auto percentile = [&](double p) {
      const double h = (m - 1) * p;
      const auto lo = static_cast<std::size_t>(std::floor(h));
      const std::size_t hi = std::min(lo + 1, y.size() - 1);
      return y[lo] + (h - static_cast<double>(lo)) * (y[hi] - y[lo]);
    };
    s.p5 = percentile(0.05), s.p50 = percentile(0.50), s.p95 = percentile(0.95);
  }
  return u;
}

Histogram histogram_of(const std::vector<double>& values) {
  Histogram h;
  if (values.empty()) return h;
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  const std::size_t bins = std::clamp<std::size_t>(static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(values.size())))), 5, 60);
  const double low = *lo, width = (*hi > *lo ? *hi - *lo : std::max(std::abs(*lo), 1.0) * 1e-9) / static_cast<double>(bins);
  for (std::size_t k = 0; k <= bins; ++k) h.edges.push_back(low + width * static_cast<double>(k));
  h.counts.assign(bins, 0);
  for (const double v : values) ++h.counts[std::min(bins - 1, static_cast<std::size_t>((v - low) / width))];
  return h;
}

std::string format_uncertainty_text(const Uncertainty& u) {
  std::string text = fmt::format("uncertainty of {}  ({})\n", u.sensor_name, u.sensor_file);
  text += fmt::format("{} samples: {} used, {} outside an input's accepted range, {} failed{}\n", u.samples, u.used,
                      u.out_of_range, u.failed, u.failed ? " (first: " + u.first_failure + ")" : "");
  text += "inputs:\n";
  for (const auto& v : u.inputs)
    text += fmt::format("  {:<36} {:<28} mean {:.6g}  sd {:.6g}  {}\n", v.key, v.as_written, v.distribution.mean(),
                        v.distribution.sd(), v.unit == "1" ? "" : "(SI: " + v.unit + ")");
  for (const auto& s : u.results) {
    const std::string unit = s.unit == "1" ? "" : " " + s.unit;
    text += fmt::format("\n{}{}\n", s.name, s.unit == "1" ? "" : " [" + s.unit + "]");
    text += fmt::format("  at the means {:.10g}   Monte Carlo: mean {:.10g}  sd {:.6g}   5 % {:.10g}  50 % {:.10g}  95 % {:.10g}\n",
                        s.nominal, s.mean, s.sd, s.p5, s.p50, s.p95);
    text += fmt::format("  linear propagation: sd {:.6g}  (Monte Carlo / linear = {:.4f})\n", s.linear_sd, s.sd / s.linear_sd);
    text += fmt::format("  {:<36} {:>12} {:>14} {:>14}\n", "input", "correlation", "∂r/∂x", "|∂r/∂x| σ");
    for (std::size_t j = 0; j < u.inputs.size(); ++j)
      text += fmt::format("  {:<36} {:>12.4f} {:>14.6g} {:>14.6g}\n", u.inputs[j].key, s.correlation[j], s.derivative[j],
                          s.linear_part[j]);
  }
  return text;
}

TableData uncertainty_table(const Uncertainty& u) {
  TableData table;
  table.layout.kind = "uncertainty";
  table.layout.columns = {"result", "input", "statistic", "value", "unit"};
  table.layout.numeric = {false, false, false, true, false};
  for (const auto& s : u.results) {
    for (const auto& [name, value] : std::vector<std::pair<std::string, double>>{
             {"nominal", s.nominal}, {"mean", s.mean}, {"sd", s.sd}, {"p5", s.p5}, {"p50", s.p50}, {"p95", s.p95},
             {"linear_sd", s.linear_sd}, {"samples_used", static_cast<double>(u.used)}})
      table.rows.push_back({s.name, std::string(), name, value, std::string(name == "samples_used" ? "1" : s.unit)});
    for (std::size_t j = 0; j < u.inputs.size(); ++j) {
      table.rows.push_back({s.name, u.inputs[j].key, std::string("correlation"), s.correlation[j], std::string("1")});
      table.rows.push_back({s.name, u.inputs[j].key, std::string("derivative"), s.derivative[j], s.unit + "/" + u.inputs[j].unit});
      table.rows.push_back({s.name, u.inputs[j].key, std::string("linear_part"), s.linear_part[j], s.unit});
    }
  }
  return table;
}

void write_uncertainty(const Uncertainty& u, TableFormat format, std::ostream& out) {
  if (format == TableFormat::text) {
    out << format_uncertainty_text(u);
    return;
  }
  const TableData table = uncertainty_table(u);
  TableWriter writer(out, format, table.layout, table.rows.size());
  write_table(table, writer);
}

}  // namespace radchain

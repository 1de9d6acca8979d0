// `radchain uncertainty`: Monte Carlo over input distributions, solves re-run at every sample, on all cores; the
// linear propagation from the budget's derivatives beside it.
#include "radchain/batch/uncertainty.hpp"

#include "radchain/batch/budget.hpp"
#include "radchain/batch/run_batch.hpp"
#include "radchain/batch/thread_pool.hpp"
#include "radchain/error.hpp"
#include "radchain/units.hpp"

#include <boost/math/special_functions/erf.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <ostream>

namespace radchain {
namespace {

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

const double nan = std::numeric_limits<double>::quiet_NaN();

}  // namespace

double Distribution::mean() const {
  switch (kind) {
    case Kind::normal: return a;
    case Kind::uniform: return (a + b) / 2;
    case Kind::lognormal: return a;
    case Kind::triangular: return (a + b + c) / 3;
  }
  return nan;
}

double Distribution::sd() const {
  switch (kind) {
    case Kind::normal: return b;
    case Kind::uniform: return (b - a) / std::sqrt(12.0);
    case Kind::lognormal: return b;
    case Kind::triangular: return std::sqrt((a * a + b * b + c * c - a * b - a * c - b * c) / 18);
  }
  return nan;
}

double Distribution::quantile(double u) const {
  // Φ⁻¹(u) = −√2 erfc⁻¹(2u)
  auto z = [](double p) { return -std::numbers::sqrt2 * boost::math::erfc_inv(2 * p); };
  switch (kind) {
    case Kind::normal: return a + b * z(u);
    case Kind::uniform: return a + (b - a) * u;
    case Kind::lognormal: {
      const double s2 = std::log1p((b / a) * (b / a));
      return std::exp(std::log(a) - s2 / 2 + std::sqrt(s2) * z(u));
    }
    case Kind::triangular: {  // lo a, mode b, hi c
      const double f = (b - a) / (c - a);
      return u < f ? a + std::sqrt(u * (c - a) * (b - a)) : c - std::sqrt((1 - u) * (c - a) * (c - b));
    }
  }
  return nan;
}

double sample_uniform(std::uint64_t seed, std::uint64_t sample, std::uint64_t input) {
  const std::uint64_t h = splitmix64(splitmix64(splitmix64(seed) ^ sample) ^ (input + 0x632be59bd9b4e019ULL));
  return (static_cast<double>(h >> 11) + 0.5) * 0x1.0p-53;  // (0, 1), never 0 or 1
}

VariedInput parse_vary(Chain& chain, const std::string& text) {
  const auto eq = text.find('=');
  const std::string key = trimmed(eq == std::string::npos ? text : text.substr(0, eq));
  const std::string spec_text = eq == std::string::npos ? "" : trimmed(text.substr(eq + 1));
  const SourceLocation where{"--vary " + key, 0, 0};
  auto fail = [&](const std::string& problem) { return InputError(where, "", spec_text, problem); };
  if (eq == std::string::npos || key.empty())
    throw InputError(SourceLocation{"--vary", 0, 0}, "", text,
                     "expected <section>.<key>=<distribution>, e.g. optics.transmittance=\"normal(0.56, 0.02)\"");
  // The parameter: numeric, real, scalar, not spectral, not solved.
  const auto dot = key.rfind('.');
  const Params::Entry* entry = nullptr;
  const StageSlot* slot = nullptr;
  std::vector<std::string> keys;
  if (dot != std::string::npos)
    for (const auto& s : chain.stages)
      if (s.section == key.substr(0, dot)) {
        slot = &s;
        for (const auto& e : s.params->entries()) {
          if (e.spec->type == ParamType::quantity || e.spec->type == ParamType::number) keys.push_back(s.section + "." + e.spec->key);
          if (e.spec->key == key.substr(dot + 1)) entry = &e;
        }
      }
  if (!entry || (entry->spec->type != ParamType::quantity && entry->spec->type != ParamType::number)) {
    if (!slot) {
      std::vector<std::string> sections;
      for (const auto& s : chain.stages) sections.push_back(s.section);
      throw fail(fmt::format("the sensor file has no section \"{}\"; sections: {}", dot == std::string::npos ? key : key.substr(0, dot),
                             join(sections)));
    }
    const std::string near = nearest_match(key, keys);
    throw fail(fmt::format("{} has no real-valued parameter \"{}\"{}", slot->params->context(), key.substr(dot + 1),
                           near.empty() ? "" : " (did you mean \"" + near + "\"?)"));
  }
  const ParamSpec& spec = *entry->spec;
  if (spec.spectral) throw fail(key + " is spectral: vary it with a sweep instead");
  for (const auto& s : chain.solves)
    if (s.unknown == key) throw fail("a [[solve]] determines " + key + " (add --no-solve to vary it)");

  VariedInput v;
  v.key = key;
  v.as_written = spec_text;
  v.unit = spec.type == ParamType::quantity ? spec.si_unit : "1";
  const auto open = spec_text.find('(');
  if (open == std::string::npos || spec_text.back() != ')')
    throw fail("expected normal(mean, sd), uniform(lo, hi), lognormal(mean, sd) or triangular(lo, mode, hi)");
  const std::string name = trimmed(spec_text.substr(0, open));
  std::vector<std::string> args;
  {
    const std::string inner = spec_text.substr(open + 1, spec_text.size() - open - 2);
    std::size_t start = 0;
    for (std::size_t at; (at = inner.find(',', start)) != std::string::npos; start = at + 1) args.push_back(trimmed(inner.substr(start, at - start)));
    args.push_back(trimmed(inner.substr(start)));
  }
  std::size_t arity = 2;
  if (name == "normal") v.distribution.kind = Distribution::Kind::normal;
  else if (name == "uniform") v.distribution.kind = Distribution::Kind::uniform;
  else if (name == "lognormal") v.distribution.kind = Distribution::Kind::lognormal;
  else if (name == "triangular") v.distribution.kind = Distribution::Kind::triangular, arity = 3;
  else {
    const std::string near = nearest_match(name, {"normal", "uniform", "lognormal", "triangular"});
    throw fail(fmt::format("unknown distribution \"{}\"{}: normal, uniform, lognormal or triangular", name,
                           near.empty() ? "" : " (did you mean \"" + near + "\"?)"));
  }
  if (args.size() != arity) throw fail(fmt::format("{} takes {} values, {} given", name, arity, args.size()));
  const bool dimensionless = spec.type != ParamType::quantity || units::dimension_of(spec.si_unit) == "1";
  double values[3] = {0, 0, 0};
  for (std::size_t i = 0; i < arity; ++i) {
    units::ParsedQuantity q;
    try {
      q = units::split_quantity(args[i]);
    } catch (const std::invalid_argument&) {
      throw fail(fmt::format("\"{}\" does not start with a number", args[i]));
    }
    if (!std::isfinite(q.number)) throw fail(fmt::format("\"{}\" is not finite", args[i]));
    if (q.unit.empty() && !dimensionless)
      throw fail(fmt::format("\"{}\" has no unit: expected {}", args[i], units::dimension_name(spec.si_unit)));
    double factor = 1;
    try {
      factor = units::conversion(q.unit.empty() ? "1" : q.unit, spec.type == ParamType::quantity ? spec.si_unit : "1").factor;
    } catch (const std::invalid_argument&) {
      throw fail(fmt::format("\"{}\": unknown unit", args[i]));
    } catch (const std::domain_error&) {
      throw fail(fmt::format("\"{}\": wrong unit, expected {}", args[i], dimensionless ? std::string("a plain number") : units::dimension_name(spec.si_unit)));
    }
    values[i] = q.number * factor;
  }
  Distribution& d = v.distribution;
  d.a = values[0], d.b = values[1], d.c = values[2];
  switch (d.kind) {
    case Distribution::Kind::normal:
      if (!(d.b > 0)) throw fail("the standard deviation must be > 0");
      break;
    case Distribution::Kind::lognormal:
      if (!(d.a > 0) || !(d.b > 0)) throw fail("lognormal(mean, sd) needs mean > 0 and sd > 0");
      break;
    case Distribution::Kind::uniform:
      if (!(d.b > d.a)) throw fail("uniform(lo, hi) needs lo < hi");
      break;
    case Distribution::Kind::triangular:
      if (!(d.a <= d.b && d.b <= d.c && d.a < d.c)) throw fail("triangular(lo, mode, hi) needs lo <= mode <= hi, lo < hi");
      break;
  }
  if (!spec.in_range(d.mean()))
    throw fail(fmt::format("its mean {:g} {} is out of range: accepted {}", d.mean(), v.unit, spec.range_text()));
  return v;
}

Uncertainty run_uncertainty(const UncertaintyOptions& options) {
  if (options.samples < 2)
    throw InputError(SourceLocation{"--samples", 0, 0}, "", std::to_string(options.samples), "at least 2 samples");
  if (options.vary.empty())
    throw InputError(SourceLocation{"--vary", 0, 0}, "", "", "give at least one --vary key=dist(...), e.g. --vary \"optics.transmittance=normal(0.56, 0.02)\"");
  auto load = [&] {
    Chain chain = load_sensor(options.sensor_file, options.overrides);
    if (options.no_solve) chain.solves.clear();
    chain.solver = options.solver;
    return chain;
  };
  Chain chain = load();
  Uncertainty u;
  u.sensor_file = chain.sensor_file;
  u.sensor_name = chain.sensor_name;
  for (const auto& text : options.vary) {
    VariedInput v = parse_vary(chain, text);
    for (const auto& w : u.inputs)
      if (w.key == v.key) throw InputError(SourceLocation{"--vary " + v.key, 0, 0}, "", text, "the key is varied twice");
    u.inputs.push_back(std::move(v));
  }
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

void write_uncertainty(const Uncertainty& u, TableFormat format, std::ostream& out) {
  if (format == TableFormat::text) {
    out << format_uncertainty_text(u);
    return;
  }
  TableLayout layout;
  layout.kind = "uncertainty";
  layout.columns = {"result", "input", "statistic", "value", "unit"};
  layout.numeric = {false, false, false, true, false};
  std::vector<std::vector<std::string>> rows;
  for (const auto& s : u.results) {
    for (const auto& [name, value] : std::vector<std::pair<std::string, double>>{
             {"nominal", s.nominal}, {"mean", s.mean}, {"sd", s.sd}, {"p5", s.p5}, {"p50", s.p50}, {"p95", s.p95},
             {"linear_sd", s.linear_sd}, {"samples_used", static_cast<double>(u.used)}})
      rows.push_back({s.name, "", name, number_cell(value), name == "samples_used" ? "1" : s.unit});
    for (std::size_t j = 0; j < u.inputs.size(); ++j) {
      rows.push_back({s.name, u.inputs[j].key, "correlation", number_cell(s.correlation[j]), "1"});
      rows.push_back({s.name, u.inputs[j].key, "derivative", number_cell(s.derivative[j]), s.unit + "/" + u.inputs[j].unit});
      rows.push_back({s.name, u.inputs[j].key, "linear_part", number_cell(s.linear_part[j]), s.unit});
    }
  }
  TableWriter writer(out, format, layout, rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) writer.row(i, rows[i]);
  writer.finish(0);
}

}  // namespace radchain

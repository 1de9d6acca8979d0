// `radchain budget`: derivatives of results with respect to every numeric input, by Ridders' extrapolation of
// finite differences, the chain's solves re-run at every perturbed point.
#include "radchain/batch/budget.hpp"

#include "radchain/error.hpp"
#include "radchain/units.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <limits>
#include <ostream>
#include <stdexcept>

namespace radchain {
namespace {

bool is_real(ParamType type) { return type == ParamType::quantity || type == ParamType::number; }

std::string unit_of(const ParamSpec& spec) {
  return spec.type == ParamType::quantity && !spec.si_unit.empty() ? spec.si_unit : std::string("1");
}

// result unit / parameter unit, as text: "1/m", "e-/(electron/s)".
std::string ratio_unit(const std::string& result, const std::string& parameter) {
  if (parameter == "1") return result;
  if (parameter == result) return "1";
  const bool compound = parameter.find_first_of(" /*.^") != std::string::npos ||
                        parameter.find_first_of("0123456789") != std::string::npos;
  return (result == "1" ? std::string("1") : result) + "/" + (compound ? "(" + parameter + ")" : parameter);
}

// One numeric input: where it lives and how far it may move.
struct Input {
  std::string name;
  ParameterRef ref;
  const ParamSpec* spec = nullptr;
  std::string unit, as_written;
  double x0 = 0;
};

// Evaluates the chain (with its solves, from the unknowns' values in the file) and reads the results.
class Evaluator {
 public:
  Evaluator(Chain& chain, std::vector<ResultId> ids) : chain_(chain), ids_(std::move(ids)) {
    for (const auto& s : chain_.solves) {
      ParameterRef ref = chain_.parameter(s.unknown);
      unknowns_.emplace_back(ref, ref.value());
    }
  }

  // true with `out` filled; false with `why` when the evaluation, a solve or a result fails.
  bool operator()(std::vector<double>& out, std::string& why) {
    ++count;
    // Every point starts the solves from the file's values: a point does not depend on the ones before it.
    for (const auto& [ref, value] : unknowns_) chain_.set(ref, value);
    try {
      if (chain_.solves.empty()) {
        chain_.evaluate(Detail::full);
      } else {
        chain_.solve_all(outcomes_);
        for (const auto& o : outcomes_)
          if (!o.converged) {
            why = fmt::format("the [[solve]] of {} failed: {}", o.spec.unknown, o.message.empty() ? "did not converge" : o.message);
            return false;
          }
      }
    } catch (const std::exception& error) {
      why = std::string("the evaluation failed: ") + error.what();
      return false;
    }
    out.resize(ids_.size());
    for (std::size_t k = 0; k < ids_.size(); ++k) {
      out[k] = chain_.results().value(ids_[k]);
      if (!std::isfinite(out[k])) {
        why = fmt::format("{} is {}", chain_.results().info(ids_[k]).name, out[k]);
        return false;
      }
    }
    return true;
  }

  std::size_t count = 0;

 private:
  Chain& chain_;
  std::vector<ResultId> ids_;
  std::vector<std::pair<ParameterRef, double>> unknowns_;
  std::vector<SolveOutcome> outcomes_;
};

std::string value_text(const Input& in, double x) {
  return fmt::format("{} = {:.10g}{}", in.name, x, in.unit == "1" ? "" : " " + in.unit);
}

// Ridders' method (Ridders 1982; Numerical Recipes 3rd ed. §5.7, dfridr) for every result at once. The
// difference quotients D(h_i), h_i = h0 / 1.4^i, fill the first row of a Neville tableau; column j eliminates the
// error term h^(2j) (central) or h^j (one-sided); each new extrapolation's error is estimated as its largest
// difference from its two parents, and the estimate with the smallest error is kept. A result stops when the
// higher orders' error grows by SAFE over the best (the round-off regime) — NR's stopping rule.
struct Derivatives {
  std::vector<double> value, error;
  bool ok = true;
  std::string failure;
};

// The scale of a parameter at 0 (a jitter, a diffusion spread, a stray light left out): the schema's example value
// ("1 um" for a diffusion rms), the size a user writes; else the range's width, else 1 SI unit. One SI unit of
// a diffusion rms is a metre, where no design converges.
double example_scale(const ParamSpec& spec) {
  try {
    std::string text = spec.example;
    if (text.size() >= 2 && text.front() == '"' && text.back() == '"') text = text.substr(1, text.size() - 2);
    const units::ParsedQuantity q = units::split_quantity(text);
    const double factor = q.unit.empty() ? 1.0 : units::conversion(q.unit, spec.si_unit).factor;
    if (const double value = std::abs(q.number * factor); value > 0 && std::isfinite(value)) return value;
  } catch (const std::exception&) {
    // not a quantity (a choice, a list): fall through
  }
  return std::isfinite(spec.max - spec.min) ? spec.max - spec.min : 1.0;
}

Derivatives ridders(Chain& chain, Evaluator& evaluate, const Input& in, double& h0, DifferenceKind kind,
                    const std::vector<double>& f0) {
  constexpr double con = 1.4, safe = 2.0;
  constexpr std::size_t ntab = 10;
  const std::size_t nr = f0.size();
  Derivatives d;
  d.value.assign(nr, std::numeric_limits<double>::quiet_NaN());
  d.error.assign(nr, std::numeric_limits<double>::max());
  std::vector<std::array<std::array<double, ntab>, ntab>> a(nr);
  std::vector<bool> done(nr, false);
  std::vector<double> fp, fm;
  const double ratio = kind == DifferenceKind::central ? con * con : con;

  // The difference quotients at step h: one or two evaluations.
  auto quotient = [&](double h, std::vector<double>& q) -> bool {
    std::string why;
    const double xp = kind == DifferenceKind::backward ? in.x0 : in.x0 + h;
    const double xm = kind == DifferenceKind::forward ? in.x0 : in.x0 - h;
    if (xp != in.x0) {
      chain.set(in.ref, xp);
      if (!evaluate(fp, why)) {
        d.failure = fmt::format("at {}: {}", value_text(in, xp), why);
        return false;
      }
    } else {
      fp = f0;
    }
    if (xm != in.x0) {
      chain.set(in.ref, xm);
      if (!evaluate(fm, why)) {
        d.failure = fmt::format("at {}: {}", value_text(in, xm), why);
        return false;
      }
    } else {
      fm = f0;
    }
    const double span = xp - xm;  // the step as represented (NR: "trick to reduce finite-precision error")
    q.resize(nr);
    for (std::size_t k = 0; k < nr; ++k) q[k] = (fp[k] - fm[k]) / span;
    return true;
  };

  std::vector<double> q;
  // The first step is a guess from the value's scale (or its range, for a value at 0: a jitter of 0 stepped by a
  // tenth of its range was 412″, where no m5 exists). Where the chain cannot be evaluated that far away, a step ten
  // times smaller is tried, down to 1e-3 of the first: a derivative is local, but a chain that fails that close to
  // its nominal point is reported, not differentiated.
  bool first = quotient(h0, q);
  for (int shrink = 0; !first && shrink < 3; ++shrink) {
    h0 /= 10;
    first = quotient(h0, q);
  }
  if (!first) {
    d.ok = false;
    return d;
  }
  d.failure.clear();
  double h = h0;
  for (std::size_t k = 0; k < nr; ++k) a[k][0][0] = q[k], d.value[k] = q[k];
  for (std::size_t i = 1; i < ntab; ++i) {
    h /= con;
    if (!quotient(h, q)) {
      d.ok = false;
      return d;
    }
    for (std::size_t k = 0; k < nr; ++k) {
      if (done[k]) continue;
      auto& t = a[k];
      t[0][i] = q[k];
      double fac = ratio;
      for (std::size_t j = 1; j <= i; ++j) {
        t[j][i] = (t[j - 1][i] * fac - t[j - 1][i - 1]) / (fac - 1.0);
        fac *= ratio;
        const double errt = std::max(std::abs(t[j][i] - t[j - 1][i]), std::abs(t[j][i] - t[j - 1][i - 1]));
        if (errt <= d.error[k]) d.error[k] = errt, d.value[k] = t[j][i];
      }
      if (std::abs(t[i][i] - t[i - 1][i - 1]) >= safe * d.error[k]) done[k] = true;
    }
    if (std::all_of(done.begin(), done.end(), [](bool b) { return b; })) break;
  }
  return d;
}

// Finds a numeric parameter by its qualified name without touching it (Chain::parameter marks it present).
const Params::Entry* find_parameter(const Chain& chain, const std::string& name, const StageSlot** slot_out) {
  const auto dot = name.rfind('.');
  if (dot == std::string::npos) return nullptr;
  const std::string section = name.substr(0, dot), key = name.substr(dot + 1);
  for (const auto& s : chain.stages)
    if (s.section == section)
      for (const auto& e : s.params->entries())
        if (e.spec->key == key) {
          if (slot_out) *slot_out = &s;
          return &e;
        }
  return nullptr;
}

std::vector<ResultId> result_ids(const Chain& chain, const std::vector<std::string>& names) {
  std::vector<ResultId> ids;
  for (const auto& n : names) ids.push_back(*chain.results().find(n));
  return ids;
}

}  // namespace

std::string to_string(DifferenceKind kind) {
  switch (kind) {
    case DifferenceKind::central: return "central";
    case DifferenceKind::forward: return "forward";
    case DifferenceKind::backward: return "backward";
  }
  return "?";
}

void check_budget_results(Chain& chain, const std::vector<std::string>& results) {
  const SourceLocation where{"--results", 0, 0};
  if (results.empty())
    throw InputError(where, "", "", "give at least one result, e.g. --results target.magnitude,detector.snr");
  std::vector<std::string> all;
  for (std::size_t i = 0; i < chain.results().size(); ++i) all.push_back(chain.results().info(i).name);
  for (std::size_t i = 0; i < results.size(); ++i) {
    const std::string& name = results[i];
    if (std::find(results.begin(), results.begin() + static_cast<std::ptrdiff_t>(i), name) != results.begin() + static_cast<std::ptrdiff_t>(i))
      throw InputError(where, "", name, "the result is listed twice");
    if (chain.results().find(name)) continue;
    const StageSlot* slot = nullptr;
    if (find_parameter(chain, name, &slot))
      throw InputError(where, "", name,
                       fmt::format("an input parameter of {}, not a result: the budget's rows are the inputs; "
                                   "`radchain run {}` lists the results",
                                   slot->params->context(), chain.sensor_file));
    throw InputError(where, "", name,
                     fmt::format("no such result{}; `radchain run {}` lists them",
                                 did_you_mean(name, all), chain.sensor_file));
  }
}

Budget compute_budget(Chain& chain, const BudgetOptions& options) {
  check_budget_results(chain, options.results);
  Budget budget;
  budget.sensor_file = chain.sensor_file;
  budget.sensor_name = chain.sensor_name;
  budget.results = options.results;
  for (const auto& s : chain.solves) budget.solved.push_back(s.unknown);

  // The inputs: numeric (real), scalar, present, not spectral, not solved.
  std::vector<Input> inputs;
  for (auto& slot : chain.stages)
    for (auto& e : slot.params->entries()) {
      const ParamSpec& spec = *e.spec;
      if (!e.present || spec.shape != ParamShape::scalar) continue;
      const std::string name = slot.section + "." + spec.key;
      if (spec.type == ParamType::integer) {
        budget.skipped.push_back(name + " (integer)");
        continue;
      }
      if (!is_real(spec.type)) continue;
      if (spec.spectral) {
        budget.skipped.push_back(name + " (spectral)");
        continue;
      }
      if (std::find(budget.solved.begin(), budget.solved.end(), name) != budget.solved.end()) continue;
      if (!std::isfinite(e.number)) {
        budget.skipped.push_back(name + " (not finite)");
        continue;
      }
      Input in;
      in.name = name;
      in.ref = chain.parameter(name);
      in.spec = &spec;
      in.unit = unit_of(spec);
      in.as_written = e.given ? e.as_written : "(default) " + spec.default_value.value_or("");
      in.x0 = e.number;
      inputs.push_back(std::move(in));
    }

  // The nominal point (its solves run once first, so that every result exists).
  const std::vector<ResultId> ids = result_ids(chain, options.results);
  Evaluator evaluate(chain, ids);
  std::vector<double> f0;
  std::string why;
  if (!evaluate(f0, why)) {
    budget.evaluations = evaluate.count;
    throw std::runtime_error("at the nominal point: " + why);
  }
  budget.nominal = f0;

  const std::size_t nr = options.results.size();
  std::vector<std::vector<BudgetEntry>> by_result(nr);
  for (const Input& in : inputs) {
    const ParamSpec& spec = *in.spec;
    double scale = std::abs(in.x0);
    if (scale == 0) scale = example_scale(spec);
    double h0 = options.initial_step * scale;
    DifferenceKind kind = DifferenceKind::central;
    bool placed = false;
    for (int shrink = 0; shrink < 8 && !placed; ++shrink, h0 /= 10) {
      const bool up = spec.in_range(in.x0 + h0), down = spec.in_range(in.x0 - h0);
      placed = up || down;
      kind = up && down ? DifferenceKind::central : up ? DifferenceKind::forward : DifferenceKind::backward;
      if (placed) break;
    }
    Derivatives d;
    if (!placed) {
      d.ok = false;
      d.failure = fmt::format("no step of at least {:g} {} stays in the accepted range ({})", h0, in.unit, spec.range_text());
    } else {
      d = ridders(chain, evaluate, in, h0, kind, f0);
    }
    chain.set(in.ref, in.x0);  // back to the nominal value
    for (std::size_t k = 0; k < nr; ++k) {
      BudgetEntry e;
      e.result = options.results[k];
      e.result_unit = chain.results().info(ids[k]).si_unit;
      e.result_si = f0[k];
      e.parameter = in.name;
      e.parameter_unit = in.unit;
      e.as_written = in.as_written;
      e.value_si = in.x0;
      e.derivative_unit = ratio_unit(e.result_unit, in.unit);
      e.step = h0;
      e.kind = kind;
      e.ok = d.ok;
      if (!d.ok) {
        e.failure = d.failure;
        e.derivative = e.elasticity = e.log_elasticity = e.error = std::numeric_limits<double>::quiet_NaN();
        e.accurate = false;
      } else {
        e.derivative = d.value[k];
        e.error = d.error[k];
        if (e.derivative == 0) e.derivative = 0;  // no "-0"
        // x ∂r/∂x compares inputs by their relative change. A magnitude is already the logarithm of a flux, so a
        // relative change of it means nothing (−26.73 × ∂r/∂m for the Sun); its elasticity is by the flux it stands
        // for, F = 10^(−0.4 m): ∂r/∂ln F = ∂r/∂m · dm/dln F = −(2.5/ln 10) ∂r/∂m (Pogson), comparable with a QE's.
        e.per_flux = in.spec->scaling == Scaling::magnitude;
        e.elasticity = e.per_flux ? -2.5 / std::numbers::ln10 * e.derivative : in.x0 * e.derivative;
        if (e.elasticity == 0) e.elasticity = 0;
        e.log_elasticity = f0[k] > 0 ? e.elasticity / f0[k] : std::numeric_limits<double>::quiet_NaN();
        const double magnitude = std::max(std::abs(e.derivative), std::abs(f0[k]) / scale);
        e.accurate = e.error <= options.rel_tolerance * magnitude;
      }
      by_result[k].push_back(std::move(e));
    }
  }
  // Leave the chain as it was found: nominal parameters, solved, every result evaluated.
  std::vector<double> ignored;
  evaluate(ignored, why);
  budget.evaluations = evaluate.count;

  for (auto& entries : by_result) {
    std::stable_sort(entries.begin(), entries.end(), [](const BudgetEntry& a, const BudgetEntry& b) {
      if (a.ok != b.ok) return a.ok;
      return a.ok && std::abs(a.elasticity) > std::abs(b.elasticity);
    });
    for (std::size_t i = 0; i < entries.size(); ++i) entries[i].rank = i + 1;
    for (auto& e : entries) budget.entries.push_back(std::move(e));
  }
  return budget;
}

TableLayout budget_layout() {
  TableLayout layout;
  layout.kind = "budget";
  layout.columns = {"result",     "rank",       "parameter",   "value",          "unit",  "derivative", "derivative_unit",
                    "elasticity", "result_unit", "log_elasticity", "error", "method", "note"};
  layout.numeric = {false, true, false, true, false, true, false, true, false, true, true, false, false};
  return layout;
}

namespace {

std::string note_of(const BudgetEntry& e) {
  if (!e.ok) return "FAILED " + e.failure;
  std::string note = e.per_flux ? "magnitude: elasticity per ln flux" : "";
  if (!e.accurate) note += fmt::format("{}uncertain: error estimate {:.3g} exceeds the tolerance", note.empty() ? "" : "; ", e.error);
  return note;
}

}  // namespace

TableData budget_table(const Budget& budget) {
  TableData table{budget_layout(), {}};
  for (const BudgetEntry& e : budget.entries)
    table.rows.push_back({e.result, static_cast<double>(e.rank), e.parameter, e.value_si, e.parameter_unit, e.derivative,
                          e.derivative_unit, e.elasticity, e.result_unit, e.log_elasticity, e.error, to_string(e.kind),
                          note_of(e)});
  return table;
}

void write_budget(const Budget& budget, TableFormat format, std::ostream& out) {
  if (format == TableFormat::text) {
    out << format_budget_text(budget);
    return;
  }
  TableWriter writer(out, format, budget_layout(), budget.entries.size());
  write_table(budget_table(budget), writer);
}

std::string format_budget_text(const Budget& budget) {
  std::string text = fmt::format("sensitivity budget of {}  ({})\n", budget.sensor_name, budget.sensor_file);
  text += budget.solved.empty() ? std::string("no [[solve]]: forward evaluation at every point\n")
                                : "re-solved at every point: " + join(budget.solved) + "\n";
  text += "derivatives: Ridders' extrapolation of finite differences (Numerical Recipes §5.7); SI units; "
          "elasticity = ∂r/∂ln x = x ∂r/∂x (a magnitude m: ∂r/∂ln F = −1.0857 ∂r/∂m, F = 10^(−0.4 m))\n";
  if (!budget.skipped.empty()) text += "not varied: " + join(budget.skipped) + "\n";
  for (std::size_t k = 0; k < budget.results.size(); ++k) {
    std::string unit;
    std::vector<const BudgetEntry*> rows;
    for (const auto& e : budget.entries)
      if (e.result == budget.results[k]) rows.push_back(&e), unit = e.result_unit;
    text += fmt::format("\n{} = {:.10g}{}\n", budget.results[k], budget.nominal[k], unit == "1" || unit.empty() ? "" : " " + unit);
    std::vector<std::vector<std::string>> table;
    table.push_back({"rank", "parameter", "value (SI)", "∂r/∂x", "unit", "∂r/∂ln x", "∂ln r/∂ln x", "error", "method", "note"});
    for (const BudgetEntry* e : rows) {
      const std::string value = fmt::format("{:.6g}{}", e->value_si, e->parameter_unit == "1" ? "" : " " + e->parameter_unit);
      auto g = [](double v) { return std::isnan(v) ? std::string("-") : fmt::format("{:.6g}", v); };
      table.push_back({std::to_string(e->rank), e->parameter, value, g(e->derivative), e->derivative_unit,
                       g(e->elasticity), g(e->log_elasticity), e->ok ? fmt::format("{:.1e}", e->error) : "-",
                       to_string(e->kind), note_of(*e)});
    }
    // Column widths in code points (∂ and ln are multi-byte).
    auto width = [](const std::string& s) {
      std::size_t n = 0;
      for (unsigned char c : s) n += (c & 0xC0) != 0x80;
      return n;
    };
    std::vector<std::size_t> widths(table.front().size(), 0);
    for (const auto& row : table)
      for (std::size_t c = 0; c < row.size(); ++c) widths[c] = std::max(widths[c], width(row[c]));
    const std::vector<bool> right = {true, false, true, true, false, true, true, true, false, false};
    for (const auto& row : table) {
      std::string line = " ";
      for (std::size_t c = 0; c < row.size(); ++c) {
        const std::string pad(widths[c] - width(row[c]), ' ');
        if (c + 1 == row.size() && row[c].empty()) break;
        line += "  " + (right[c] ? pad + row[c] : row[c] + (c + 1 == row.size() ? "" : pad));
      }
      while (!line.empty() && line.back() == ' ') line.pop_back();
      text += line + "\n";
    }
  }
  std::size_t failed = 0, uncertain = 0;
  for (const auto& e : budget.entries) failed += !e.ok, uncertain += e.ok && !e.accurate;
  text += fmt::format("\n{} evaluations; {} entries, {} failed, {} uncertain\n", budget.evaluations, budget.entries.size(),
                      failed, uncertain);
  return text;
}

}  // namespace radchain

// `radchain compare A B`: every intermediate quantity side by side, and what differs in the inputs.
#include "radchain/batch/compare.hpp"
#include "radchain/strings.hpp"

#include "radchain/error.hpp"
#include "radchain/input_file.hpp"
#include "parameter_lookup.hpp"
#include "radchain/units.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <ostream>
#include <sstream>

namespace radchain {
namespace {
using strings::unquoted;


constexpr double nan = std::numeric_limits<double>::quiet_NaN();

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

using batch_detail::is_numeric;

// A results file of `radchain run --format json` -> the Report it was printed from (results and solves).
Report report_from_json(const std::string& path) {
  auto fail = [&](const std::string& problem) { return InputError(SourceLocation{path, 0, 0}, "results file", "", problem); };
  std::ifstream in = open_input_file(path, "results file", max_results_file_bytes);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw fail(std::string("not JSON: ") + e.what());
  }
  if (!j.is_object() || !j.contains("results") || !j["results"].is_array())
    throw fail("not a result file of `radchain run --format json` (no \"results\" array)");
  Report report;
  report.sensor_file = j.value("file", path);
  report.sensor_name = j.value("sensor", "");
  try {
    for (const auto& r : j["results"]) {
      ResultInfo info;
      info.name = r.at("name").get<std::string>();
      info.si_unit = r.value("si_unit", "1");
      info.display_unit = r.value("unit", info.si_unit);
      info.stage = r.value("stage", "");
      info.equation = r.value("equation", "");
      info.display_factor = 1;
      if (info.display_unit != info.si_unit) {
        try {
          info.display_factor = 1.0 / units::conversion(info.display_unit, info.si_unit).factor;
        } catch (const std::exception&) {
          info.display_unit = info.si_unit;
        }
      }
      const auto& v = r.at("value_si");
      report.results.push_back(info);
      report.values.push_back(v.is_number() ? v.get<double>() : nan);
    }
    if (j.contains("solves") && j["solves"].is_array())
      for (const auto& s : j["solves"]) {
        SolveOutcome o;
        o.spec.unknown = s.value("unknown", "");
        if (s.contains("criteria") && s["criteria"].is_array()) o.spec.criteria = s["criteria"].get<std::vector<std::string>>();
        o.value_si = s.contains("value_si") && s["value_si"].is_number() ? s["value_si"].get<double>() : nan;
        o.converged = s.value("converged", false);
        o.binding = s.value("binding", "");
        o.message = s.value("message", "");
        report.solves.push_back(o);
      }
  } catch (const nlohmann::json::exception& e) {
    throw fail(std::string("unexpected content: ") + e.what());
  }
  return report;
}

// How an entry reads in a sensor file: "15 cm", "(default) 0.56", "(absent)".
std::string as_written(const Params::Entry* e) {
  if (!e || !e->present) return "(absent)";
  const std::string text = unquoted(e->as_written);
  return e->given ? text : "(default) " + text;
}

bool same_entry(const Params::Entry* a, const Params::Entry* b) {
  const bool pa = a && a->present, pb = b && b->present;
  if (pa != pb) return false;
  if (!pa) return true;
  if (a->spec->type != b->spec->type) return false;
  switch (a->spec->type) {
    case ParamType::quantity:
    case ParamType::number:
    case ParamType::integer: return a->number == b->number;
    case ParamType::flag: return a->flag == b->flag;
    default: return a->text == b->text;
  }
}

// The unit a quantity entry was written in ("15 cm" -> "cm"), or "".
std::string written_unit(const Params::Entry* e) {
  if (!e || !e->present) return {};
  try {
    return units::split_quantity(unquoted(e->as_written)).unit;
  } catch (const std::exception&) {
    return {};
  }
}

InputDifference entry_difference(const std::string& name, const Params::Entry* a, const Params::Entry* b) {
  InputDifference d;
  d.name = name;
  d.a = as_written(a);
  d.b = as_written(b);
  d.a_value = d.b_value = d.a_si = d.b_si = nan;
  const ParamSpec* spec = a ? a->spec : b->spec;
  if (!is_numeric(spec->type)) return d;
  d.si_unit = spec->type == ParamType::quantity ? spec->si_unit : "1";
  if (a && a->present && is_numeric(a->spec->type)) d.a_si = a->number;
  if (b && b->present && is_numeric(b->spec->type)) d.b_si = b->number;
  double factor = 1;  // unit -> SI
  if (spec->type == ParamType::quantity) {
    d.unit = written_unit(a);
    if (d.unit.empty()) d.unit = written_unit(b);
    if (d.unit.empty()) {
      try {
        d.unit = units::split_quantity(unquoted(spec->example)).unit;
      } catch (const std::exception&) {
      }
    }
    try {
      factor = units::conversion(d.unit.empty() ? d.si_unit : d.unit, d.si_unit).factor;
    } catch (const std::exception&) {
      d.unit = d.si_unit;
    }
  }
  d.a_value = d.a_si / factor;
  d.b_value = d.b_si / factor;
  return d;
}

void compare_inputs(const Chain& a, const Chain& b, std::vector<InputDifference>& out) {
  if (a.sensor_name != b.sensor_name) {
    InputDifference d{"sensor.name", a.sensor_name, b.sensor_name, nan, nan, "", nan, nan, ""};
    out.push_back(d);
  }
  std::vector<std::string> sections;
  for (const auto& s : a.stages) sections.push_back(s.section);
  for (const auto& s : b.stages)
    if (std::find(sections.begin(), sections.end(), s.section) == sections.end()) sections.push_back(s.section);
  auto find_slot = [](const Chain& c, const std::string& section) -> const StageSlot* {
    for (const auto& s : c.stages)
      if (s.section == section) return &s;
    return nullptr;
  };
  for (const auto& section : sections) {
    const StageSlot* sa = find_slot(a, section);
    const StageSlot* sb = find_slot(b, section);
    if (!sa || !sb || sa->plugin != sb->plugin) {
      out.push_back(InputDifference{section + ".plugin", sa ? sa->plugin : "(absent)", sb ? sb->plugin : "(absent)", nan,
                                    nan, "", nan, nan, ""});
    }
    std::vector<std::string> keys;
    std::map<std::string, const Params::Entry*> ea, eb;
    if (sa)
      for (const auto& e : sa->params->entries()) keys.push_back(e.spec->key), ea[e.spec->key] = &e;
    if (sb)
      for (const auto& e : sb->params->entries()) {
        if (!ea.count(e.spec->key)) keys.push_back(e.spec->key);
        eb[e.spec->key] = &e;
      }
    for (const auto& key : keys) {
      const Params::Entry* x = ea.count(key) ? ea[key] : nullptr;
      const Params::Entry* y = eb.count(key) ? eb[key] : nullptr;
      if (!same_entry(x, y)) out.push_back(entry_difference(section + "." + key, x, y));
    }
  }

  auto text_difference = [&](const std::string& name, const std::string& x, const std::string& y) {
    if (x != y) out.push_back(InputDifference{name, x, y, nan, nan, "", nan, nan, ""});
  };
  const std::size_t solves = std::max(a.solves.size(), b.solves.size());
  for (std::size_t i = 0; i < solves; ++i) {
    const std::string name = fmt::format("solve[{}]", i + 1);
    const SolveSpec* x = i < a.solves.size() ? &a.solves[i] : nullptr;
    const SolveSpec* y = i < b.solves.size() ? &b.solves[i] : nullptr;
    auto describe = [](const SolveSpec* s, int what) -> std::string {
      if (!s) return "(absent)";
      if (what == 0) return s->unknown;
      if (what == 1) return join(s->criteria);
      return fmt::format("[{:.10g}, {:.10g}] (SI)", s->lo, s->hi);
    };
    text_difference(name + ".unknown", describe(x, 0), describe(y, 0));
    text_difference(name + ".criteria", describe(x, 1), describe(y, 1));
    text_difference(name + ".bracket", describe(x, 2), describe(y, 2));
  }
  std::vector<std::string> names;
  for (const auto& e : a.expected) names.push_back(e.result);
  for (const auto& e : b.expected)
    if (std::find(names.begin(), names.end(), e.result) == names.end()) names.push_back(e.result);
  auto find_expected = [](const Chain& c, const std::string& name) -> const Expectation* {
    for (const auto& e : c.expected)
      if (e.result == name) return &e;
    return nullptr;
  };
  for (const auto& name : names) {
    const Expectation* x = find_expected(a, name);
    const Expectation* y = find_expected(b, name);
    auto value = [](const Expectation* e) { return e ? e->as_written : std::string("(absent)"); };
    auto tolerance = [](const Expectation* e) {
      if (!e) return std::string("(absent)");
      return fmt::format("{:.10g} (SI){}", e->tolerance_si,
                         e->rel_tolerance > 0 ? fmt::format(", relative {:g}", e->rel_tolerance) : "");
    };
    auto follows = [](const Expectation* e) {
      return e ? (e->follows_si ? e->follows_as_written : std::string("-")) : std::string("(absent)");
    };
    text_difference("expected." + name + ".value", value(x), value(y));
    text_difference("expected." + name + ".tolerance", tolerance(x), tolerance(y));
    text_difference("expected." + name + ".follows", follows(x), follows(y));
  }
}

std::string solve_state(const SolveOutcome* s) {
  if (!s) return "no solve";
  if (!s->converged) return "FAILED" + (s->message.empty() ? "" : " (" + s->message + ")");
  return "converged" + (s->binding.empty() ? "" : ", " + s->binding + " binds");
}

std::string value_cell(double v) { return std::isnan(v) ? "" : fmt::format("{:.6g}", v); }
std::string delta_cell(double v) { return std::isnan(v) ? "" : fmt::format("{:+.4g}", v); }
std::string pct_cell(double relative) { return std::isnan(relative) ? "" : fmt::format("{:+.3g}", 100 * relative); }

// The solved unknowns (A's solves, then B's) to the front, each group in its previous order.
void solved_unknowns_first(const Report& a, const Report& b, std::vector<ResultDifference>& results) {
  std::vector<std::string> unknowns;
  for (const Report* report : {&a, &b})
    for (const auto& s : report->solves)
      if (std::find(unknowns.begin(), unknowns.end(), s.spec.unknown) == unknowns.end()) unknowns.push_back(s.spec.unknown);
  auto rank = [&](const ResultDifference& r) {
    return static_cast<std::size_t>(std::find(unknowns.begin(), unknowns.end(), r.name) - unknowns.begin());
  };
  std::stable_sort(results.begin(), results.end(),
                   [&](const ResultDifference& x, const ResultDifference& y) { return rank(x) < rank(y); });
}

TableLayout comparison_layout() {
  return TableLayout{"compare",
                     {"kind", "name", "a", "b", "unit", "delta", "delta_pct", "status"},
                     {false, false, true, true, false, true, true, false},
                     {}};
}

}  // namespace

std::string ResultDifference::status(std::optional<double> tolerance) const {
  if (!in_a) return tolerance ? "EXCEEDS (only in B)" : "only in B";
  if (!in_b) return tolerance ? "EXCEEDS (only in A)" : "only in A";
  if (same()) return "same";
  if (tolerance) return exceeds(*tolerance) ? "EXCEEDS" : "ok";
  return exceeds(rounding_tolerance) ? "differs" : "ok";
}

double ResultDifference::delta() const { return (b_si - a_si) * factor; }

double ResultDifference::relative() const {
  if (a_si == b_si) return 0.0;
  return (b_si - a_si) / std::abs(a_si);
}

bool ResultDifference::same() const {
  return in_a && in_b && (a_si == b_si || (std::isnan(a_si) && std::isnan(b_si)));
}

bool ResultDifference::exceeds(double rel_tolerance) const {
  if (!in_a || !in_b) return true;
  if (same()) return false;
  if (std::isnan(a_si) || std::isnan(b_si)) return true;
  return std::abs(b_si - a_si) > rel_tolerance * std::max({std::abs(a_si), std::abs(b_si), scale_floor()});
}

double ResultDifference::scale_floor() const {
  constexpr std::string_view margin = ".margin";
  return name.size() > margin.size() && name.compare(name.size() - margin.size(), margin.size(), margin) == 0 ? 1.0 : 0.0;
}

CompareInput load_compare_input(const std::string& path, const std::vector<Override>& overrides, bool solve) {
  CompareInput input;
  input.path = path;
  if (ends_with(path, ".json")) {
    input.results_file = true;
    input.report = report_from_json(path);
  } else {
    input.chain.emplace(load_sensor(path, overrides, solve ? Solving::as_written : Solving::forward_only));
    // run() leaves the solved values in the unknowns; the inputs compared are the file's (as validated).
    std::vector<std::pair<ParameterRef, double>> unknowns;
    for (const auto& s : input.chain->solves) {
      const ParameterRef p = input.chain->parameter(s.unknown);
      unknowns.emplace_back(p, p.value());
    }
    input.report = input.chain->run();
    for (const auto& [p, v] : unknowns) input.chain->set(p, v);
  }
  input.sensor_name = input.report.sensor_name;
  return input;
}

Comparison compare(const CompareInput& a, const CompareInput& b) {
  Comparison c;
  c.a_path = a.path, c.b_path = b.path, c.a_name = a.sensor_name, c.b_name = b.sensor_name;
  c.inputs_compared = a.chain && b.chain;
  if (c.inputs_compared) compare_inputs(*a.chain, *b.chain, c.inputs);

  std::map<std::string, std::size_t> in_b;
  for (std::size_t i = 0; i < b.report.results.size(); ++i) in_b.emplace(b.report.results[i].name, i);
  std::map<std::string, bool> seen;
  for (std::size_t i = 0; i < a.report.results.size(); ++i) {
    const ResultInfo& info = a.report.results[i];
    ResultDifference r{info.name, info.display_unit, info.display_factor, a.report.values[i], nan, true, false};
    if (auto it = in_b.find(info.name); it != in_b.end()) {
      r.in_b = true;
      r.b_si = b.report.values[it->second];
    }
    seen[info.name] = true;
    c.results.push_back(r);
  }
  for (std::size_t i = 0; i < b.report.results.size(); ++i) {
    const ResultInfo& info = b.report.results[i];
    if (seen.count(info.name)) continue;
    c.results.push_back(ResultDifference{info.name, info.display_unit, info.display_factor, nan, b.report.values[i], false, true});
  }
  solved_unknowns_first(a.report, b.report, c.results);

  std::vector<std::string> unknowns;
  for (const auto& s : a.report.solves) unknowns.push_back(s.spec.unknown);
  for (const auto& s : b.report.solves)
    if (std::find(unknowns.begin(), unknowns.end(), s.spec.unknown) == unknowns.end()) unknowns.push_back(s.spec.unknown);
  auto find_solve = [](const Report& r, const std::string& unknown) -> const SolveOutcome* {
    for (const auto& s : r.solves)
      if (s.spec.unknown == unknown) return &s;
    return nullptr;
  };
  for (const auto& u : unknowns)
    c.solves.push_back(fmt::format("{}: A {}; B {}", u, solve_state(find_solve(a.report, u)), solve_state(find_solve(b.report, u))));
  return c;
}

std::size_t count_exceeding(const Comparison& comparison, double rel_tolerance) {
  std::size_t n = 0;
  for (const auto& r : comparison.results) n += r.exceeds(rel_tolerance) ? 1 : 0;
  return n;
}

double parse_tolerance(const std::string& text) {
  std::string number = text;
  double scale = 1;
  if (!number.empty() && number.back() == '%') number.pop_back(), scale = 0.01;
  char* end = nullptr;
  const double v = std::strtod(number.c_str(), &end);
  if (number.empty() || *end != '\0' || !(v >= 0) || !std::isfinite(v))
    throw InputError(SourceLocation{"--tolerance", 0, 0}, "", text,
                     "expected a relative tolerance >= 0, e.g. 1e-6 or 0.1%");
  return v * scale;
}

std::string format_comparison_text(const Comparison& c, std::optional<double> tolerance) {
  std::string out = fmt::format("A  {}  ({})\nB  {}  ({})\n", c.a_path, c.a_name, c.b_path, c.b_name);
  if (!c.inputs_compared) {
    out += "\ninputs: not compared (a results file holds no inputs)\n";
  } else if (c.inputs.empty()) {
    out += "\ninputs: the same (every validated parameter, [[solve]] and [expected] entry)\n";
  } else {
    out += "\ninputs that differ (as validated; SI in brackets):\n";
    std::size_t name_w = 4, a_w = 1;
    for (const auto& d : c.inputs) name_w = std::max(name_w, d.name.size()), a_w = std::max(a_w, d.a.size());
    for (const auto& d : c.inputs) {
      std::string si;
      if (!std::isnan(d.a_si) && !std::isnan(d.b_si) && !d.si_unit.empty()) {
        std::vector<std::string> parts;
        if (d.si_unit != "1") parts.push_back(fmt::format("{:.6g} {} → {:.6g} {}", d.a_si, d.si_unit, d.b_si, d.si_unit));
        if (d.a_si != 0) parts.push_back(fmt::format("{:+.3g} %", 100 * (d.b_si - d.a_si) / std::abs(d.a_si)));
        if (!parts.empty()) si = "  [" + join(parts) + "]";
      }
      out += fmt::format("  {:<{}}  {:<{}}  →  {}{}\n", d.name, name_w, d.a, a_w, d.b, si);
    }
  }
  if (!c.solves.empty()) {
    out += "\nsolves:\n";
    for (const auto& s : c.solves) out += "  " + s + "\n";
  }
  out += "\nresults (delta = B − A, in the unit shown):\n";
  std::ostringstream table;
  {
    TableWriter writer(table, TableFormat::text,
                       TableLayout{"compare-results",
                                   {"result", "A", "B", "unit", "delta", "delta_pct", "status"},
                                   {false, true, true, false, true, true, false},
                                   {}},
                       c.results.size());
    for (std::size_t i = 0; i < c.results.size(); ++i) {
      const auto& r = c.results[i];
      writer.row(i, {r.name, value_cell(r.in_a ? r.a_si * r.factor : nan), value_cell(r.in_b ? r.b_si * r.factor : nan),
                     r.unit == "1" ? "" : r.unit, r.in_a && r.in_b ? delta_cell(r.delta()) : "",
                     r.in_a && r.in_b ? pct_cell(r.relative()) : "", r.status(tolerance)});
    }
    writer.finish(0);
  }
  std::istringstream lines(table.str());
  for (std::string line; std::getline(lines, line);) out += "  " + line + "\n";
  std::size_t differ = 0;
  for (const auto& r : c.results) differ += r.exceeds(rounding_tolerance) ? 1 : 0;
  out += fmt::format("{} results, {} differ by more than {:g}", c.results.size(), differ, rounding_tolerance);
  if (tolerance) out += fmt::format("; tolerance {:g}: {} exceed", *tolerance, count_exceeding(c, *tolerance));
  out += "\n";
  return out;
}

void write_comparison(const Comparison& c, TableFormat format, std::ostream& out, std::optional<double> tolerance) {
  if (format == TableFormat::text) {
    out << format_comparison_text(c, tolerance);
    return;
  }
  const std::size_t rows = c.inputs.size() + c.results.size();
  TableWriter writer(out, format, comparison_layout(), rows);
  std::size_t point = 0;
  for (const auto& d : c.inputs) {
    const bool numbers = !std::isnan(d.a_value) && !std::isnan(d.b_value);
    writer.row(point++, {"input", d.name, numbers ? fmt::format("{:.10g}", d.a_value) : d.a,
                         numbers ? fmt::format("{:.10g}", d.b_value) : d.b, d.unit,
                         numbers ? delta_cell(d.b_value - d.a_value) : "",
                         numbers && d.a_si != 0 ? pct_cell((d.b_si - d.a_si) / std::abs(d.a_si)) : "", "differs"});
  }
  for (const auto& r : c.results)
    writer.row(point++, {"result", r.name, r.in_a ? number_cell(r.a_si * r.factor) : "",
                         r.in_b ? number_cell(r.b_si * r.factor) : "", r.unit == "1" ? "" : r.unit,
                         r.in_a && r.in_b ? delta_cell(r.delta()) : "", r.in_a && r.in_b ? pct_cell(r.relative()) : "",
                         r.status(tolerance)});
  writer.finish(tolerance && count_exceeding(c, *tolerance) > 0 ? 1 : 0);
}

}  // namespace radchain

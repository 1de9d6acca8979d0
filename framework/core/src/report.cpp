#include "radchain/report.hpp"

#include "radchain/units.hpp"

#include <cmath>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace radchain {

std::string format_value(double value_si, const ResultInfo& info) {
  if (std::isnan(value_si)) return "-";
  const double v = value_si * info.display_factor;
  return fmt::format("{:.6g}", v);
}

// "206 mm" or, for an erratum, "206 mm (follows: 65.0 mm)".
static std::string display_of_expectation(const ExpectationOutcome& e) {
  if (!e.spec.follows_si) return e.spec.as_written;
  return e.spec.as_written + " (follows: " + e.spec.follows_as_written + ")";
}

std::string format_report_text(const Report& report) {
  std::string out = fmt::format("{}  ({})\n", report.sensor_name, report.sensor_file);
  std::size_t name_width = 6, value_width = 5, unit_width = 4, stage_width = 5;
  for (std::size_t i = 0; i < report.results.size(); ++i) {
    name_width = std::max(name_width, report.results[i].name.size());
    value_width = std::max(value_width, format_value(report.values[i], report.results[i]).size());
    unit_width = std::max(unit_width, report.results[i].display_unit.size());
    stage_width = std::max(stage_width, report.results[i].stage.size());
  }
  out += fmt::format("  {:<{}}  {:>{}}  {:<{}}  {:<{}}  {}\n", "result", name_width, "value", value_width, "unit",
                     unit_width, "stage", stage_width, "equation");
  for (std::size_t i = 0; i < report.results.size(); ++i) {
    const ResultInfo& info = report.results[i];
    out += fmt::format("  {:<{}}  {:>{}}  {:<{}}  {:<{}}  {}\n", info.name, name_width,
                       format_value(report.values[i], info), value_width, info.display_unit, unit_width, info.stage,
                       stage_width, info.equation);
  }
  if (!report.solves.empty()) {
    out += "solves:\n";
    for (const auto& s : report.solves) {
      std::string roots;
      if (s.roots.size() > 1)
        for (const auto& [name, value] : s.roots) roots += fmt::format("; {} alone gives {:.6g}", name, value);
      out += fmt::format("  {} from {}: {}{}\n", s.spec.unknown, join(s.spec.criteria, " + "),
                         s.converged ? fmt::format("converged in {} evaluations, {}, binding criterion \"{}\"{}", s.iterations, s.method,
                                                   s.binding, s.fallback.empty() ? "" : " (not in closed form: " + s.fallback + ")")
                                     : "FAILED: " + s.message,
                         roots);
    }
  }
  if (!report.expectations.empty()) {
    out += "expected (printed reference) vs computed:\n";
    for (const auto& e : report.expectations) {
      const ResultInfo* info = nullptr;
      for (const auto& r : report.results)
        if (r.name == e.spec.result) info = &r;
      std::string computed = "-";
      std::string delta = "-";
      if (info && e.found) {
        double factor = info->display_factor;
        std::string unit = info->display_unit;
        if (!e.spec.display_unit.empty()) {
          factor = 1.0 / units::conversion(e.spec.display_unit, info->si_unit).factor;
          unit = e.spec.display_unit;
        }
        computed = fmt::format("{:.6g} {}", e.computed_si * factor, unit == "1" ? "" : unit);
        const double d = (e.computed_si - e.spec.value_si) * factor;
        const double rel = e.spec.value_si != 0 ? (e.computed_si - e.spec.value_si) / std::abs(e.spec.value_si) : 0.0;
        delta = fmt::format("{:+.3g} ({:+.2f} %)", d, 100 * rel);
      }
      out += fmt::format("  {:<4} {:<40} printed {:<14} computed {:<18} delta {:<22} {}{}\n", e.passed ? "ok" : "FAIL",
                         e.spec.result, display_of_expectation(e), computed, delta,
                         e.spec.kind.empty() ? "" : "[" + e.spec.kind + "] ", e.spec.source);
    }
  }
  if (!report.criteria.empty()) {
    out += "criteria:\n";
    for (const auto& c : report.criteria)
      out += fmt::format("  {:<4} {:<28} margin {:+.4g}{}{}\n",
                         c.passed ? "ok" : c.informational ? "info" : "FAIL", c.section, c.margin,
                         c.informational ? " (informational)" : "", c.reason.empty() ? "" : ": " + c.reason);
  }
  for (const auto& w : report.warnings) out += "warning: " + w + "\n";
  for (const auto& t : report.tables) out += format_table_text(t);
  return out;
}

// table "limiting magnitude vs exposure":
//   detector.integration_time  target.magnitude [1]
//   1 s                                   21.83
std::string format_table_text(const TableOutcome& table) {
  std::vector<std::vector<std::string>> cells;  // header, then one row per value
  cells.push_back({table.spec.vary});
  for (const auto& c : table.columns) cells[0].push_back(c.display_unit == "1" ? c.name : c.name + " [" + c.display_unit + "]");
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    cells.push_back({table.spec.values_written[r]});
    for (std::size_t c = 0; c < table.columns.size(); ++c) cells.back().push_back(format_value(table.rows[r][c], table.columns[c]));
  }
  std::vector<std::size_t> width(cells[0].size(), 0);
  for (const auto& row : cells)
    for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
  std::string out = fmt::format("table \"{}\":\n", table.spec.name);
  for (std::size_t r = 0; r < cells.size(); ++r) {
    std::string line = fmt::format("  {:<{}}", cells[r][0], width[0]);
    for (std::size_t c = 1; c < cells[r].size(); ++c) line += fmt::format("  {:>{}}", cells[r][c], width[c]);
    if (r > 0 && !table.notes[r - 1].empty()) line += "  (" + table.notes[r - 1] + ")";
    out += line + "\n";
  }
  return out;
}

std::string format_report_json(const Report& report) {
  nlohmann::ordered_json j;
  j["sensor"] = report.sensor_name;
  j["file"] = report.sensor_file;
  auto& results = j["results"] = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < report.results.size(); ++i) {
    const auto& info = report.results[i];
    nlohmann::ordered_json r;
    r["name"] = info.name;
    r["value_si"] = std::isnan(report.values[i]) ? nlohmann::ordered_json() : nlohmann::ordered_json(report.values[i]);
    r["si_unit"] = info.si_unit;
    r["value"] = std::isnan(report.values[i]) ? nlohmann::ordered_json()
                                              : nlohmann::ordered_json(report.values[i] * info.display_factor);
    r["unit"] = info.display_unit;
    r["stage"] = info.stage;
    r["equation"] = info.equation;
    results.push_back(r);
  }
  auto& solves = j["solves"] = nlohmann::ordered_json::array();
  for (const auto& s : report.solves)
    solves.push_back({{"unknown", s.spec.unknown}, {"criteria", s.spec.criteria}, {"binding", s.binding}, {"value_si", s.value_si},
                      {"converged", s.converged}, {"evaluations", s.iterations}, {"method", s.method},
                      {"fallback", s.fallback}, {"message", s.message}});
  auto& expectations = j["expected"] = nlohmann::ordered_json::array();
  for (const auto& e : report.expectations)
    expectations.push_back({{"result", e.spec.result}, {"printed", e.spec.as_written}, {"printed_si", e.spec.value_si},
                            {"follows_si", e.spec.follows_si ? nlohmann::ordered_json(*e.spec.follows_si) : nlohmann::ordered_json()},
                            {"computed_si", e.computed_si}, {"tolerance_si", e.spec.tolerance_si},
                            {"rel_tolerance", e.spec.rel_tolerance}, {"passed", e.passed}, {"kind", e.spec.kind}, {"source", e.spec.source}});
  auto& tables = j["tables"] = nlohmann::ordered_json::array();
  for (const auto& t : report.tables) {
    nlohmann::ordered_json table{{"name", t.spec.name}, {"vary", t.spec.vary}, {"values", t.spec.values_written},
                                 {"values_si", t.spec.values_si}};
    auto& columns = table["columns"] = nlohmann::ordered_json::array();
    for (const auto& c : t.columns) columns.push_back({{"name", c.name}, {"unit", c.display_unit}, {"si_unit", c.si_unit}});
    auto& rows = table["rows_si"] = nlohmann::ordered_json::array();
    for (const auto& row : t.rows) {
      auto& out = rows.emplace_back(nlohmann::ordered_json::array());
      for (const double v : row) out.push_back(std::isnan(v) ? nlohmann::ordered_json() : nlohmann::ordered_json(v));
    }
    table["notes"] = t.notes;
    tables.push_back(std::move(table));
  }
  auto& criteria = j["criteria"] = nlohmann::ordered_json::array();
  for (const auto& c : report.criteria)
    criteria.push_back({{"section", c.section},
                        {"margin", std::isnan(c.margin) ? nlohmann::ordered_json() : nlohmann::ordered_json(c.margin)},
                        {"passed", c.passed}, {"informational", c.informational}, {"reason", c.reason}});
  j["warnings"] = report.warnings;
  j["passed"] = report.all_passed();
  return j.dump(2) + "\n";
}

}  // namespace radchain

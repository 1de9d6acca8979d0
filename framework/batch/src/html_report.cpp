// `radchain report`: the model of each sensor page (every number from the chain) and the folder written whole.
#include "html_report_model.hpp"

#include "radchain/atomic_file.hpp"
#include "radchain/batch/budget.hpp"
#include "radchain/batch/catalogue.hpp"
#include "radchain/batch/run_batch.hpp"
#include "radchain/batch/svg_plot.hpp"
#include "radchain/config.hpp"
#include "radchain/error.hpp"
#include "radchain/input_file.hpp"
#include "radchain/mtf_curves.hpp"
#include "radchain/physics/mtf_budget.hpp"
#include "radchain/report.hpp"
#include "radchain/vocabulary.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace radchain {
namespace fs = std::filesystem;

namespace html_detail {
namespace {

Json number_or_null(double v) { return std::isfinite(v) ? Json(v) : Json(); }

std::string unit_text(const std::string& unit) { return unit == "1" ? std::string() : unit; }

// "\"15 cm\"" → "15 cm": the TOML text of a value as a reader wrote it, without the string's quotes.
std::string unquoted(const std::string& toml) {
  if (toml.size() >= 2 && toml.front() == '"' && toml.back() == '"') return toml.substr(1, toml.size() - 2);
  return toml;
}

std::optional<double> parse_number(const std::string& text) {
  if (text.empty() || text == "nan") return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str()) return std::nullopt;
  return v;
}

const char* type_name(ParamType type) {
  switch (type) {
    case ParamType::quantity: return "quantity";
    case ParamType::number: return "number";
    case ParamType::integer: return "integer";
    case ParamType::text: return "text";
    case ParamType::choice: return "choice";
    case ParamType::flag: return "flag";
    case ParamType::spectrum: return "spectrum";
  }
  return "";
}

// [sensor]: what the instrument is. load_sensor keeps name and description; reference and notes are read from
// the same (already validated) table.
void describe_sensor(Json& d, const std::string& file, const Chain& chain) {
  d["name"] = chain.sensor_name;
  d["description"] = chain.description;
  d["reference"] = "";
  d["notes"] = "";
  const ConfigValue root = parse_toml_file(file);
  if (const ConfigValue* sensor = root.find("sensor"))
    for (const char* key : {"reference", "notes"})
      if (const ConfigValue* v = sensor->find(key); v && v->type == ConfigValue::Type::string) d[key] = v->string_value;
}

Json chain_json(const Chain& chain) {
  Json stages = Json::array();
  for (const auto& s : chain.stages)
    stages.push_back({{"section", s.section},
                      {"plugin", s.plugin},
                      {"summary", s.info && s.info->summary ? s.info->summary : ""},
                      {"reference", s.info && s.info->reference ? s.info->reference : ""},
                      {"informational", s.informational}});
  return stages;
}

// Every input present in the chain: as written (or its default, marked), its unit, where it comes from, the value
// in use (SI; a solved unknown's is its root).
Json inputs_json(const Chain& chain, const Report& report) {
  Json inputs = Json::array();
  for (const auto& s : chain.stages) {
    for (const auto& e : s.params->entries()) {
      if (!e.present) continue;
      const ParamSpec& spec = *e.spec;
      const std::string key = s.section + "." + spec.key;
      Json in;
      in["section"] = s.section;
      in["plugin"] = s.plugin;
      in["key"] = spec.key;
      in["type"] = type_name(spec.type);
      in["default"] = !e.given;
      in["written"] = e.given ? unquoted(e.as_written) : spec.default_value.value_or("");
      in["unit"] = spec.type == ParamType::quantity || spec.type == ParamType::spectrum ? unit_text(spec.si_unit) : "";
      std::string provenance = !e.given ? "default" : e.where.file == "--set" ? "--set" : fmt::format("line {}", e.where.line);
      Json value;
      const bool numeric = spec.type == ParamType::quantity || spec.type == ParamType::number || spec.type == ParamType::integer;
      if (numeric && spec.shape == ParamShape::scalar) value = number_or_null(e.number);
      if (numeric && spec.shape != ParamShape::scalar) {
        value = Json::array();
        for (double v : e.numbers) value.push_back(number_or_null(v));
      }
      if (spec.type == ParamType::flag) value = e.flag;
      bool solved = false;
      for (const auto& solve : report.solves)
        if (solve.spec.unknown == key) {
          solved = true;
          value = solve.converged ? number_or_null(solve.value_si) : Json();
          provenance += solve.converged ? "; solved by [[solve]] (the file's value is where it starts)" : "; its [[solve]] FAILED";
        }
      in["solved"] = solved;
      in["value_si"] = value;
      in["provenance"] = provenance;
      in["doc"] = spec.doc;
      inputs.push_back(std::move(in));
    }
  }
  return inputs;
}

Json results_json(const Report& report) {
  Json results = Json::array();
  for (std::size_t i = 0; i < report.results.size(); ++i) {
    const ResultInfo& info = report.results[i];
    const double v = report.values[i];
    results.push_back({{"name", info.name},
                       {"value_si", number_or_null(v)},
                       {"value", number_or_null(v * info.display_factor)},
                       {"unit", unit_text(info.display_unit)},
                       {"si_unit", info.si_unit},
                       {"stage", info.stage},
                       {"equation", info.equation}});
  }
  return results;
}

const ResultInfo* info_of(const Report& report, const std::string& name, std::size_t* index = nullptr) {
  for (std::size_t i = 0; i < report.results.size(); ++i)
    if (report.results[i].name == name) {
      if (index) *index = i;
      return &report.results[i];
    }
  return nullptr;
}

Json solves_json(const Report& report) {
  Json solves = Json::array();
  for (const auto& s : report.solves) {
    const ResultInfo* info = info_of(report, s.spec.unknown);
    const double factor = info ? info->display_factor : 1.0;
    Json roots = Json::array();
    for (const auto& [criterion, root] : s.roots)
      roots.push_back({{"criterion", criterion}, {"value_si", number_or_null(root)}, {"value", number_or_null(root * factor)}});
    solves.push_back({{"unknown", s.spec.unknown},
                      {"criteria", s.spec.criteria},
                      {"converged", s.converged},
                      {"value_si", s.converged ? number_or_null(s.value_si) : Json()},
                      {"value", s.converged ? number_or_null(s.value_si * factor) : Json()},
                      {"unit", info ? unit_text(info->display_unit) : ""},
                      {"iterations", s.iterations},
                      {"method", s.method},
                      {"fallback", s.fallback},
                      {"binding", s.binding},
                      {"message", s.message},
                      {"roots", roots}});
  }
  return solves;
}

// The [expected] checks and failed solves/criteria as `radchain catalogue` states them (catalogue_rows), with
// each [expected] entry's own text (reference as written, erratum, source) beside.
Json checks_json(const Report& report, const std::vector<std::vector<std::string>>& rows) {
  Json checks = Json::array();
  for (const auto& row : rows) {
    // Columns of catalogue_layout(): sensor, instrument, result, kind, computed, reference, tolerance, unit, delta,
    // delta_pct, check, note.
    const std::string& check = row[10];
    if (check != "ok" && check != "FAIL" && check != "info") continue;
    auto num = [&](std::size_t c) { return parse_number(row[c]) ? Json(*parse_number(row[c])) : Json(); };
    Json j{{"result", row[2]},    {"kind", row[3]}, {"computed", num(4)}, {"reference", num(5)}, {"tolerance", num(6)},
           {"unit", row[7]},      {"delta", num(8)}, {"delta_pct", num(9)}, {"status", check},   {"note", row[11]},
           {"written", ""},       {"follows", ""},  {"source", ""}};
    for (const auto& e : report.expectations)
      if (e.spec.result == row[2] && (row[3] == (e.spec.kind.empty() ? "unstated" : e.spec.kind))) {
        j["written"] = e.spec.as_written;
        j["follows"] = e.spec.follows_as_written;
        j["source"] = e.spec.source;
        j["line"] = e.spec.where.line;
      }
    checks.push_back(std::move(j));
  }
  return checks;
}

Json criteria_json(const Report& report) {
  Json criteria = Json::array();
  for (const auto& c : report.criteria)
    criteria.push_back({{"section", c.section},
                        {"margin", number_or_null(c.margin)},
                        {"status", c.passed ? "ok" : c.informational ? "info" : "FAIL"},
                        {"informational", c.informational},
                        {"reason", c.reason}});
  return criteria;
}

Json tables_json(const Report& report) {
  Json tables = Json::array();
  for (const auto& t : report.tables) {
    Json columns = Json::array(), rows = Json::array();
    for (const auto& c : t.columns) columns.push_back({{"name", c.name}, {"unit", unit_text(c.display_unit)}});
    for (const auto& r : t.rows) {
      Json row = Json::array();
      for (std::size_t c = 0; c < r.size(); ++c) row.push_back(number_or_null(r[c] * t.columns[c].display_factor));
      rows.push_back(std::move(row));
    }
    tables.push_back({{"name", t.spec.name}, {"vary", t.spec.vary}, {"values", t.spec.values_written},
                      {"values_si", t.spec.values_si}, {"columns", columns}, {"rows", rows}, {"notes", t.notes}});
  }
  return tables;
}

// The index's key results: each solved unknown, then each checked result (in the file's order), at most four,
// each pointing at its row of "results".
Json key_results_json(const Report& report) {
  Json keys = Json::array();
  std::vector<std::string> names;
  for (const auto& s : report.solves) names.push_back(s.spec.unknown);
  for (const auto& e : report.expectations)
    if (e.found) names.push_back(e.spec.result);
  std::set<std::string> seen;
  for (const auto& name : names) {
    if (keys.size() >= 4 || !seen.insert(name).second) continue;
    std::size_t i = 0;
    if (info_of(report, name, &i)) keys.push_back({{"name", name}, {"result", i}});
  }
  return keys;
}

// ---- plots ------------------------------------------------------------------------------------------------------

Json series_json(const svg::Series& s) { return Json{{"label", s.label}, {"x", s.x}, {"y", s.y}}; }

Json plot_json(const svg::LinePlot& p) {
  Json series = Json::array();
  for (const auto& s : p.series) series.push_back(series_json(s));
  for (auto& s : series)
    for (auto* axis : {&s["x"], &s["y"]})
      for (auto& v : *axis)
        if (v.is_number() && !std::isfinite(v.get<double>())) v = nullptr;
  return Json{{"x_label", p.x.label}, {"y_label", p.y.label}, {"x_log", p.x.log}, {"y_log", p.y.log}, {"series", series}};
}

std::vector<double> spaced(double lo, double hi, std::size_t n, bool log) {
  std::vector<double> v;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = n == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(n - 1);
    v.push_back(log ? lo * std::pow(hi / lo, t) : lo + t * (hi - lo));
  }
  if (log && n > 1) v.back() = hi;
  return v;
}

// The solved target magnitude vs integration time: the file's [[table]] on detector.integration_time, else the
// solves tabulated (Chain::tabulate) over a tenth to ten times the file's exposure.
std::optional<Figure> exposure_figure(Chain& chain, const Report& report, const HtmlReportOptions& options, Json& plots) {
  const std::string magnitude = "target.magnitude", exposure = "detector.integration_time";
  const SolveOutcome* solve = nullptr;
  for (const auto& s : report.solves)
    if (s.spec.unknown == magnitude) solve = &s;
  if (!solve) return std::nullopt;
  Figure f{"exposure", "Limiting magnitude vs exposure", "", ""};
  const ResultInfo* mag_info = info_of(report, magnitude);
  svg::LinePlot plot;
  plot.id = "plot-exposure";
  plot.x = {"integration time (s)", true};
  plot.y = {"limiting " + magnitude + (mag_info && unit_text(mag_info->display_unit).size() ? " (" + mag_info->display_unit + ")" : ""), false};
  plot.description = "limiting magnitude against integration time";
  const TableOutcome* from_file = nullptr;
  std::size_t column = 0;
  for (const auto& t : report.tables) {
    if (t.spec.vary != exposure) continue;
    for (std::size_t c = 0; c < t.columns.size(); ++c)
      if (t.columns[c].name == magnitude) from_file = &t, column = c;
    if (from_file) break;
  }
  svg::Series series;
  series.label = fmt::format("{} at {} (root of {})", magnitude, exposure, join(solve->spec.criteria));
  std::string source;
  if (from_file) {
    for (std::size_t r = 0; r < from_file->rows.size(); ++r) {
      series.x.push_back(from_file->spec.values_si[r]);
      series.y.push_back(from_file->rows[r][column] * from_file->columns[column].display_factor);
    }
    series.markers = true;
    source = fmt::format("the file's [[table]] \"{}\" ({} values; Chain::tabulate re-solves at each)", from_file->spec.name,
                         from_file->rows.size());
  } else {
    const auto t = report.value(exposure);
    ParameterRef ref;
    try {
      ref = chain.parameter(exposure);
    } catch (const std::exception&) {
      return std::nullopt;
    }
    if (!t || !(*t > 0)) {
      f.caption = fmt::format("Not drawn: {} is {} in this file, so there is no exposure to sweep about.", exposure,
                              t ? fmt::format("{:g} s", *t) : "not computed");
      plots["exposure"] = Json{{"skipped", f.caption}};
      return f;
    }
    TableSpec spec;
    spec.name = "limiting magnitude vs exposure (report sweep)";
    spec.vary = exposure;
    spec.results = {magnitude};
    spec.values_si = spaced(*t / 10, *t * 10, std::max<std::size_t>(options.sweep_points / 2, 5), true);
    for (double v : spec.values_si) spec.values_written.push_back(fmt::format("{:.6g} s", v));
    const TableOutcome out = chain.tabulate(spec);
    for (std::size_t r = 0; r < out.rows.size(); ++r) {
      series.x.push_back(spec.values_si[r]);
      series.y.push_back(out.rows[r][0] * out.columns[0].display_factor);
    }
    source = fmt::format("a sweep of {} log-spaced exposures from a tenth to ten times the file's {:.4g} s, the [[solve]] "
                         "re-run at each (Chain::tabulate)",
                         spec.values_si.size(), *t);
  }
  if (const auto t = report.value(exposure)) plot.x_marks.push_back({*t, fmt::format("file: {:.4g} s", *t)});
  plot.series.push_back(std::move(series));
  f.svg = svg::render_line_plot(plot);
  f.caption = "The limiting magnitude (the [[solve]] on " + magnitude + ") at each integration time, from " + source +
              ". The dashed line marks the file's own exposure.";
  plots["exposure"] = plot_json(plot);
  plots["exposure"]["source"] = from_file ? "table" : "sweep";
  return f;
}

// The budget's results: the solved unknowns, else the checked results, else the SNR (at most two).
std::vector<std::string> budget_results(const Report& report) {
  std::vector<std::string> names;
  auto add = [&](const std::string& name) {
    if (names.size() >= 2 || std::find(names.begin(), names.end(), name) != names.end()) return;
    if (const auto v = report.value(name); v && std::isfinite(*v)) names.push_back(name);
  };
  for (const auto& s : report.solves)
    if (s.converged) add(s.spec.unknown);
  if (names.empty())
    for (const auto& e : report.expectations)
      if (e.found) add(e.spec.result);
  if (names.empty()) add(std::string(vocabulary::detector_snr.name));
  return names;
}

constexpr std::size_t tornado_rows = 12;

std::vector<Figure> budget_figures(Chain& chain, const Report& report, Json& plots) {
  std::vector<Figure> figures;
  const std::vector<std::string> results = budget_results(report);
  if (results.empty()) return figures;
  BudgetOptions options;
  options.results = results;
  Budget budget;
  try {
    budget = compute_budget(chain, options);
  } catch (const std::exception& error) {
    Figure f{"tornado", "Sensitivity budget", fmt::format("Not drawn: the budget of {} could not be computed: {}", join(results), error.what()), ""};
    plots["tornado"] = Json{{"skipped", f.caption}};
    figures.push_back(f);
    return figures;
  }
  Json tornadoes = Json::array();
  for (std::size_t r = 0; r < budget.results.size(); ++r) {
    const std::string& result = budget.results[r];
    svg::TornadoPlot plot;
    plot.id = fmt::format("plot-tornado-{}", r);
    std::string unit;
    std::vector<std::string> no_effect;
    double largest = 0;
    for (const auto& e : budget.entries)
      if (e.result == result && e.ok) largest = std::max(largest, std::abs(e.elasticity));
    Json bars = Json::array();
    std::size_t shown = 0, hidden = 0;
    for (const auto& e : budget.entries) {
      if (e.result != result) continue;
      unit = unit_text(e.result_unit);
      const std::string label = e.parameter + (e.per_flux ? " (per ln flux)" : "");
      if (e.ok && std::abs(e.elasticity) <= 1e-12 * largest) {
        no_effect.push_back(e.parameter);
        continue;
      }
      if (e.ok && shown >= tornado_rows) {
        ++hidden;
        continue;
      }
      if (e.ok) ++shown;
      plot.bars.push_back({label, e.ok ? e.elasticity : NAN, e.ok ? "" : e.failure});
      bars.push_back({{"parameter", e.parameter}, {"label", label}, {"elasticity", e.ok ? Json(e.elasticity) : Json()},
                      {"log_elasticity", number_or_null(e.log_elasticity)}, {"rank", e.rank}, {"ok", e.ok},
                      {"failure", e.failure}, {"as_written", e.as_written}});
    }
    plot.x_label = fmt::format("∂ {} / ∂ ln x{}  (change for +1 % of x: 0.01 × bar)", result, unit.empty() ? "" : " (" + unit + ")");
    plot.description = "elasticities of " + result + " to the inputs";
    std::string caption = fmt::format(
        "Elasticity ∂r/∂ln x of {} to each numeric input (Ridders' derivatives{}): the change of the result for a relative "
        "change of the input, largest first.",
        result, budget.solved.empty() ? "" : ", the [[solve]] re-run at every perturbed point");
    if (hidden) caption += fmt::format(" {} smaller entries are in report.json and `radchain budget`.", hidden);
    if (!no_effect.empty()) caption += fmt::format(" No effect ({}): {}.", no_effect.size(), join(no_effect));
    Figure f{"tornado", "Sensitivity budget: " + result, caption, plot.bars.empty() ? "" : svg::render_tornado(plot)};
    tornadoes.push_back({{"result", result}, {"unit", unit}, {"nominal", number_or_null(budget.nominal[r])}, {"bars", bars},
                         {"no_effect", no_effect}, {"evaluations", budget.evaluations}});
    figures.push_back(std::move(f));
  }
  plots["tornado"] = tornadoes;
  return figures;
}

// "criteria.<name>" of the last criterion publishing `suffix` (".mtf_nyquist_system"), or "".
std::string criterion_with(const Report& report, const std::string& suffix) {
  std::string found;
  for (const auto& r : report.results)
    if (r.name.starts_with("criteria.") && r.name.ends_with(suffix)) found = r.name.substr(0, r.name.size() - suffix.size());
  return found;
}

// The MTF the chain designs to, read from the report as `radchain mtf` reads it (radchain/mtf_curves.hpp): an
// Earth-observation camera's budget (a giqe criterion), component by component, or Kolobrodov's design (an
// mtf_match criterion), his Fig. 2 curves.
std::optional<Figure> mtf_figure(const Report& report, Json& plots) {
  const MtfView view = mtf_view(report);
  if (view == MtfView::none) return std::nullopt;
  const bool budget = view == MtfView::budget;
  Figure f{"mtf", "MTF budget", "", ""};
  svg::LinePlot plot;
  plot.id = "plot-mtf";
  plot.x = {"spatial frequency at the focal plane (cycles/mm)", false, 0, NAN};
  plot.y = {"MTF", false, 0, 1};
  plot.description = "modulation transfer functions";
  try {
    if (!budget) {
      const MtfCurves c = mtf_curves(report);
      const std::string matched = criterion_with(report, ".required_quality");
      svg::Series diffraction{"diffraction-limited objective", {}, {}}, objective{"objective, eq. (7): linear model", {}, {}},
          detector{"detector element, eq. (8)", {}, {}}, system{"system, eq. (10)", {}, {}, true};
      for (std::size_t i = 0; i < c.frequency_per_m.size(); ++i) {
        for (auto* s : {&diffraction, &objective, &detector, &system}) s->x.push_back(c.frequency_per_m[i] * 1e-3);
        diffraction.y.push_back(c.diffraction[i]);
        objective.y.push_back(c.objective[i]);
        detector.y.push_back(c.detector[i]);
        system.y.push_back(c.system[i]);
      }
      plot.series = {diffraction, objective, detector, system};
      f.title = "MTF (Kolobrodov 1996, Fig. 2)";
      f.caption = fmt::format("The objective at the quality η = {:.3g} the design needs ({}), the detector element V_D = {:.4g} µm "
                              "and their product, at λ = {:.4g} µm and f/{:.3g}; to the element's first zero 1/V_D. The "
                              "same curves as `radchain mtf`.",
                              c.eta, matched, c.element_m * 1e6, c.wavelength_m * 1e6, c.f_number);
    } else {
      const MtfBudgetCurves c = mtf_budget_curves(report);
      const physics::MtfBudget& b = c.budget;
      const char* names[] = {"diffraction", "pixel", "jitter", "smear", "diffusion", "wavefront", "TDI", "atmosphere"};
      std::vector<svg::Series> components(8);
      svg::Series system{"system", {}, {}, true};
      for (std::size_t k = 0; k < 8; ++k) components[k].label = names[k];
      for (std::size_t i = 0; i < c.frequency_per_m.size(); ++i) {
        const double nu = c.frequency_per_m[i];
        const physics::MtfComponents& m = c.components[i];
        const double values[] = {m.diffraction, m.pixel, m.jitter, m.smear, m.diffusion, m.wavefront, m.tdi, m.atmosphere};
        for (std::size_t k = 0; k < 8; ++k) components[k].x.push_back(nu * 1e-3), components[k].y.push_back(values[k]);
        system.x.push_back(nu * 1e-3);
        system.y.push_back(m.system());
      }
      // A component equal to 1 at every frequency (no jitter, no TDI …) is named in the caption, not drawn over MTF = 1.
      std::vector<std::string> unity;
      for (auto& component : components) {
        const bool flat = std::all_of(component.y.begin(), component.y.end(), [](double v) { return std::abs(v - 1) < 1e-12; });
        if (flat) unity.push_back(component.label);
        else plot.series.push_back(std::move(component));
      }
      plot.series.push_back(std::move(system));
      const double nyquist = c.nyquist_per_m;
      const physics::MtfComponents at = physics::mtf_components(b, nyquist);
      plot.x_marks.push_back({nyquist * 1e-3, fmt::format("Nyquist {:.4g} /mm: system {:.3f}", nyquist * 1e-3, at.system())});
      f.caption = fmt::format("The MTF budget of {} (physics/mtf_budget.hpp, as `radchain mtf` draws it) from 0 to twice the "
                              "Nyquist frequency 1/(2p), p = {:.4g} µm, at λ = {:.4g} µm and f/{:.3g}; the system is the product "
                              "of the components.{}",
                              c.criterion, b.pitch_m * 1e6, b.wavelength_m * 1e6, b.f_number,
                              unity.empty() ? "" : " Equal to 1 throughout, so not drawn: " + join(unity) + ".");
      plots["mtf_nyquist"] = Json{{"frequency_per_mm", nyquist * 1e-3}, {"system", at.system()}};
    }
  } catch (const std::exception& error) {
    f.caption = std::string("Not drawn: ") + error.what();
    plots["mtf"] = Json{{"skipped", f.caption}};
    return f;
  }
  f.svg = svg::render_line_plot(plot);
  plots["mtf"] = plot_json(plot);
  return f;
}

// The target's brightness parameter: a magnitude, else a reflectance or contrast, else a size the signal scales with.
const Params::Entry* brightness_entry(const Chain& chain) {
  for (const auto& s : chain.stages) {
    if (s.section != "target") continue;
    const auto& entries = s.params->entries();
    auto find = [&](auto&& pred) -> const Params::Entry* {
      for (const auto& e : entries)
        if (e.present && e.spec->shape == ParamShape::scalar &&
            (e.spec->type == ParamType::number || e.spec->type == ParamType::quantity) && pred(e))
          return &e;
      return nullptr;
    };
    if (auto* e = find([](const Params::Entry& e) { return e.spec->scaling == Scaling::magnitude; })) return e;
    for (const char* key : {"reflectance", "contrast"})
      if (auto* e = find([&](const Params::Entry& e) { return e.spec->key == key; })) return e;
    if (auto* e = find([](const Params::Entry& e) { return e.spec->scaling == Scaling::power_law; })) return e;
  }
  return nullptr;
}

// SNR against the target's brightness, the design otherwise as solved: a forward sweep (Chain::set, evaluate).
std::optional<Figure> snr_figure(Chain& chain, const Report& report, const HtmlReportOptions& options, Json& plots) {
  const std::string snr = std::string(vocabulary::detector_snr.name);
  const auto snr_id = chain.results().find(snr);
  if (!snr_id) return std::nullopt;
  const Params::Entry* entry = brightness_entry(chain);
  if (!entry) return std::nullopt;
  const ParamSpec& spec = *entry->spec;
  const std::string key = "target." + spec.key;
  const bool magnitude = spec.scaling == Scaling::magnitude;
  Figure f{"snr", magnitude ? "SNR vs target magnitude" : "SNR vs target " + spec.key, "", ""};
  double centre = entry->number;
  for (const auto& s : report.solves)
    if (s.spec.unknown == key && s.converged) centre = s.value_si;
  double lo = magnitude ? centre - 5 : centre / 100, hi = magnitude ? centre + 5 : centre * 10;
  lo = std::max(lo, spec.min_exclusive && !magnitude ? std::max(spec.min, centre / 1e4) : spec.min);
  hi = std::min(hi, spec.max);
  if (!(hi > lo)) return std::nullopt;
  const std::vector<double> xs = spaced(lo, hi, options.sweep_points, !magnitude);

  chain.drop_solves();  // the other unknowns keep their solved values: the design as the file solves it
  const ParameterRef ref = chain.parameter(key);
  svg::Series series{"detector.snr", {}, {}, true};
  std::size_t failed = 0;
  for (double x : xs) {
    double y = NAN;
    try {
      chain.set(ref, x);
      chain.evaluate(Detail::full);
      y = chain.results().value(*snr_id);
    } catch (const std::exception&) {
      ++failed;
    }
    series.x.push_back(x);
    series.y.push_back(y);
  }
  svg::LinePlot plot;
  plot.id = "plot-snr";
  std::string unit = unit_text(spec.si_unit);
  plot.x = {key + (unit.empty() ? "" : " (" + unit + ")"), !magnitude};
  plot.y = {"SNR (detector.snr)", true};
  plot.description = "signal-to-noise ratio against the target's " + spec.key;
  for (const auto& r : report.results)
    if (vocabulary::criterion_threshold.matches(r.name))
      if (const auto t = report.value(r.name); t && *t > 0) plot.y_marks.push_back({*t, fmt::format("T = {:.3g} ({})", *t, r.name.substr(9, r.name.rfind('.') - 9))});
  const bool solved = centre != entry->number;
  plot.x_marks.push_back({centre, fmt::format("{} {:.4g}", solved ? "solved:" : "file:", centre)});
  plot.series.push_back(std::move(series));
  f.svg = svg::render_line_plot(plot);
  f.caption = fmt::format("A forward sweep of {} over {} points{} (Chain::set, then every stage re-evaluated), every other "
                          "input as {}; {} is the chain's own result at each point.{}",
                          key, xs.size(), magnitude ? " (brighter to the left)" : " on a log axis", report.solves.empty() ? "written" : "solved",
                          snr, failed ? fmt::format(" {} points could not be evaluated (crossed).", failed) : "");
  plots["snr"] = plot_json(plot);
  plots["snr"]["parameter"] = key;
  return f;
}

}  // namespace

SensorModel evaluate_sensor(const std::string& file, const std::string& page, const HtmlReportOptions& options) {
  SensorModel m;
  Json& d = m.data;
  d["file"] = file;
  d["stem"] = fs::path(file).stem().string();
  d["page"] = page;
  try {
    Chain chain = load_sensor(file, options.overrides);
    chain.solver = options.solver;
    const Report report = chain.run();
    describe_sensor(d, file, chain);
    d["status"] = report.all_passed() ? "ok" : "FAIL";
    d["error"] = "";
    d["chain"] = chain_json(chain);
    d["inputs"] = inputs_json(chain, report);
    d["results"] = results_json(report);
    d["key_results"] = key_results_json(report);
    d["solves"] = solves_json(report);
    m.catalogue_rows = catalogue_rows(file, report);
    d["checks"] = checks_json(report, m.catalogue_rows);
    d["criteria"] = criteria_json(report);
    d["warnings"] = report.warnings;
    d["tables"] = tables_json(report);
    Json uncertainty = Json::array();
    for (const auto& u : chain.uncertainties) uncertainty.push_back({{"key", u.key}, {"distribution", u.text}});
    d["uncertainty"] = uncertainty;
    Json& plots = d["plots"] = Json::object();
    // In this order: the sweeps that re-run the solves first, the forward sweep (which drops them) last.
    std::vector<Figure> figures;
    if (auto f = exposure_figure(chain, report, options, plots)) figures.push_back(*f);
    if (auto f = mtf_figure(report, plots)) figures.push_back(*f);
    std::vector<Figure> tornadoes;
    if (options.budget) tornadoes = budget_figures(chain, report, plots);
    std::optional<Figure> snr;
    try {
      snr = snr_figure(chain, report, options, plots);
    } catch (const std::exception& error) {
      snr = Figure{"snr", "SNR vs target brightness", std::string("Not drawn: ") + error.what(), ""};
    }
    if (snr) m.figures.push_back(*snr);
    for (auto& f : figures) m.figures.push_back(std::move(f));
    for (auto& f : tornadoes) m.figures.push_back(std::move(f));
  } catch (const InputError& error) {
    m.bad_input = true;
    m.error = error.what();
  } catch (const std::exception& error) {
    m.bad_input = true;
    m.error = fmt::format("{}: internal error: {}", file, error.what());
  } catch (...) {
    m.bad_input = true;
    m.error = fmt::format("{}: internal error: a plugin threw an exception that is not a std::exception", file);
  }
  if (m.bad_input) {
    Json keep{{"file", d["file"]}, {"stem", d["stem"]}, {"page", page}};
    d = keep;
    d["name"] = "";
    d["status"] = "ERROR";
    d["error"] = m.error;
    m.figures.clear();
    m.catalogue_rows = {catalogue_error_row(file, m.error)};
  }
  return m;
}

}  // namespace html_detail

// ---- the folder -------------------------------------------------------------------------------------------------

namespace {
using html_detail::Json;

constexpr const char* marker_generator = "radchain report";

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  return fs::equivalent(a, b, ec);
}

// An earlier report: report.json written by this command at the top of the folder.
bool is_earlier_report(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_regular_file(dir / "report.json", ec)) return false;
  try {
    const std::string text = read_input_file((dir / "report.json").string(), "earlier report", max_results_file_bytes);
    return Json::parse(text).value("generator", std::string()).starts_with(marker_generator);
  } catch (const std::exception&) {
    return false;
  }
}

// --out must not be an input, hold one, or be a folder of something else.
void check_out_folder(const fs::path& out, const std::vector<std::string>& files) {
  auto refuse = [&](const std::string& why) { throw InputError(SourceLocation{"--out", 0, 0}, "", out.string(), why); };
  std::error_code ec;
  const fs::path parent = fs::absolute(out, ec).parent_path();
  if (!fs::is_directory(parent, ec)) refuse("the folder it goes in does not exist: " + parent.string());
  const fs::path canonical_out = fs::weakly_canonical(fs::absolute(out), ec);
  for (const auto& f : files) {
    if (same_file(out, f)) refuse("is one of the inputs (" + f + ")");
    const fs::path canonical_in = fs::weakly_canonical(fs::absolute(f), ec);
    const auto [o, i] = std::mismatch(canonical_out.begin(), canonical_out.end(), canonical_in.begin(), canonical_in.end());
    if (o == canonical_out.end()) refuse("holds one of the inputs (" + f + "): the report would replace it");
  }
  if (!fs::exists(fs::symlink_status(out, ec))) return;
  if (!fs::is_directory(out, ec)) refuse("exists and is not a folder");
  if (fs::is_empty(out, ec) || is_earlier_report(out)) return;
  refuse("the folder exists and is not an earlier radchain report; name a new folder or remove this one");
}

void sync_path(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

// The report's files in a hidden folder beside --out, until it is complete.
class StagingFolder {
 public:
  explicit StagingFolder(const fs::path& out) : out_(fs::absolute(out)) {
    std::string pattern = (out_.parent_path() / ("." + out_.filename().string() + ".partial-XXXXXX")).string();
    if (!::mkdtemp(pattern.data()))
      throw InputError(SourceLocation{"--out", 0, 0}, "", out.string(),
                       fmt::format("cannot create a folder beside it: {}", std::strerror(errno)));
    ::chmod(pattern.c_str(), 0755);  // mkdtemp makes it 0700; the report is for reading
    path_ = pattern;
  }
  ~StagingFolder() {
    std::error_code ec;
    if (!path_.empty()) fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

  void write(const std::string& relative, const std::string& content) {
    const fs::path target = path_ / relative;
    std::error_code ec;
    fs::create_directories(target.parent_path(), ec);
    AtomicFile file(target.string(), "--out");
    file.stream() << content;
    file.commit();
  }

  // Renames the complete folder to --out; an earlier report there is exchanged with it atomically, then removed.
  void commit() {
    for (const auto& dir : {path_ / "sensors", path_}) sync_path(dir);
    std::error_code ec;
    if (fs::exists(fs::symlink_status(out_, ec))) {
      if (::renameat2(AT_FDCWD, path_.c_str(), AT_FDCWD, out_.c_str(), RENAME_EXCHANGE) != 0)
        throw WriteError(fmt::format("{}: cannot replace the earlier report: {}", out_.string(), std::strerror(errno)));
      // path_ now names the earlier report: the destructor removes it.
    } else {
      if (::rename(path_.c_str(), out_.c_str()) != 0)
        throw WriteError(fmt::format("{}: cannot rename the report into place: {}", out_.string(), std::strerror(errno)));
      path_.clear();
    }
    sync_path(out_.parent_path());
  }

 private:
  fs::path out_, path_;
};

// Page names: sensors/<stem>.html, made unique when two folders hold files of one stem.
std::vector<std::string> page_names(const std::vector<std::string>& files) {
  std::vector<std::string> pages;
  std::map<std::string, int> used;
  for (const auto& f : files) {
    std::string stem = fs::path(f).stem().string();
    for (char& c : stem)
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.')) c = '_';
    const int n = used[stem]++;
    pages.push_back("sensors/" + (n == 0 ? stem : fmt::format("{}-{}", stem, n + 1)) + ".html");
  }
  return pages;
}

}  // namespace

HtmlReportOutcome write_html_report(const std::vector<std::string>& files, const std::string& out_dir,
                                    const HtmlReportOptions& options) {
  check_out_folder(out_dir, files);
  const std::vector<std::string> pages = page_names(files);
  std::vector<html_detail::SensorModel> models(files.size());
  run_batch(
      files.size(), files.size(), 1,
      [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
          models[i] = html_detail::evaluate_sensor(files[i], pages[i], options);
          if (options.progress) options.progress->fetch_add(1, std::memory_order_relaxed);
        }
      },
      [](std::size_t) {});

  HtmlReportOutcome outcome;
  outcome.folder = out_dir;
  outcome.files = files.size();
  auto summary = catalogue_summary();
  std::size_t row_index = 0;
  Json report;
  report["generator"] = std::string(marker_generator) + (options.generator.empty() ? "" : " — " + options.generator);
  report["inputs"] = files;
  Json overrides = Json::array();
  for (const auto& o : options.overrides) overrides.push_back(o.key + "=" + o.value);
  report["overrides"] = overrides;
  Json& sensors = report["sensors"] = Json::array();
  for (auto& m : models) {
    for (const auto& row : m.catalogue_rows) {
      summary->row(row_index++, row);
      if (row[10] == "ok" || row[10] == "FAIL") ++outcome.checks;
      if (row[10] == "FAIL") ++outcome.failed;
      if (row[10] == "warning") ++outcome.warnings;
    }
    if (m.bad_input) {
      ++outcome.bad_files;
      outcome.errors.push_back(m.error);
    }
    sensors.push_back(m.data);
  }
  outcome.summary = summary->text(files.size());
  report["summary"] = outcome.summary;
  outcome.exit_code = outcome.bad_files ? 2 : outcome.failed ? 1 : 0;
  for (const auto& m : models)
    if (!m.bad_input && m.data.value("status", "") == "FAIL") outcome.exit_code = std::max(outcome.exit_code, 1);
  report["exit_code"] = outcome.exit_code;

  StagingFolder staging(out_dir);
  staging.write("index.html", html_detail::index_page(report));
  for (std::size_t i = 0; i < models.size(); ++i) {
    staging.write(pages[i], html_detail::sensor_page(report, i, models[i]));
    ++outcome.pages;
  }
  staging.write("report.json", report.dump(1, ' ', false, Json::error_handler_t::replace) + "\n");
  staging.commit();
  return outcome;
}

}  // namespace radchain

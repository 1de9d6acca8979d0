// `radchain catalogue`: many sensor files, one table of key results against their [expected] references.
#include "radchain/batch/catalogue.hpp"

#include "radchain/batch/run_batch.hpp"
#include "radchain/batch/shard.hpp"
#include "radchain/batch/table.hpp"
#include "radchain/batch/thread_pool.hpp"
#include "radchain/batch/uncertainty.hpp"
#include "radchain/error.hpp"
#include "radchain/plugin_host.hpp"
#include "radchain/units.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

namespace radchain {
namespace fs = std::filesystem;
namespace {

enum Column { sensor, instrument, result, kind, computed, reference, tolerance, unit, delta, delta_pct, check, note, column_count };

// A value to the last bit (the shortest text that reads back as the same double); text tables show 6 digits
// (catalogue_layout's text_digits).
std::string full_precision(double v) { return std::isnan(v) ? "nan" : fmt::format("{}", v); }

std::string unit_cell(const std::string& unit) { return unit == "1" ? std::string() : unit; }

std::vector<std::string> empty_row(const std::string& stem, const std::string& name) {
  std::vector<std::string> row(column_count);
  row[sensor] = stem;
  row[instrument] = name;
  return row;
}

class CatalogueSummary final : public TableSummary {
 public:
  void row(std::size_t, const std::vector<std::string>& cells) override {
    const std::string& c = cells[check];
    if (c == "ok" || c == "FAIL") {
      ++checks_;
      ++by_kind_[cells[kind]];
    }
    if (c == "FAIL") ++failed_;
    if (c == "ERROR") ++errors_;
    if (c == "warning") ++warnings_;
  }
  std::string text(std::size_t points) const override {
    // What the checks are worth: a published figure or a peer's computation is not an internal consistency check.
    std::vector<std::string> kinds;
    for (const char* k : {"published", "peer", "paper", "internal", "unstated", "solve", "criterion"})
      if (const auto it = by_kind_.find(k); it != by_kind_.end()) kinds.push_back(fmt::format("{} {}", it->second, k));
    std::string text = fmt::format("{} sensor file{}, {} check{}{}: ", points, points == 1 ? "" : "s", checks_,
                                   checks_ == 1 ? "" : "s", kinds.empty() ? "" : " (" + join(kinds) + ")");
    const std::string warned = warnings_ ? fmt::format(" ({} warning{})", warnings_, warnings_ == 1 ? "" : "s") : "";
    if (failed_ == 0 && errors_ == 0) return text + "all passed" + warned;
    std::vector<std::string> parts;
    if (failed_) parts.push_back(fmt::format("{} FAILED", failed_));
    if (errors_) parts.push_back(fmt::format("{} file{} with bad input", errors_, errors_ == 1 ? "" : "s"));
    return text + join(parts) + warned;
  }

 private:
  std::size_t checks_ = 0, failed_ = 0, errors_ = 0, warnings_ = 0;
  std::map<std::string, std::size_t> by_kind_;
};

}  // namespace

std::vector<std::string> catalogue_files(const std::vector<std::string>& inputs) {
  std::vector<std::string> files;
  for (const auto& input : inputs) {
    std::error_code ec;
    if (fs::is_directory(input, ec)) {
      // Sub-folders too: validation/ keeps each peer's cases in a folder of its own.
      std::vector<std::string> found;
      fs::recursive_directory_iterator it(input, ec), end;
      for (; !ec && it != end; it.increment(ec))
        if (it->is_regular_file() && it->path().extension() == ".toml") found.push_back(it->path().string());
      // A sub-folder that cannot be listed is the user's to fix, not an internal error.
      if (ec)
        throw InputError(SourceLocation{it != end ? it->path().string() : input, 0, 0}, "catalogue", "",
                         "cannot list the folder: " + ec.message());
      if (found.empty())
        throw InputError(SourceLocation{input, 0, 0}, "catalogue", "", "the folder holds no sensor files (*.toml)");
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else if (fs::exists(input, ec)) {
      files.push_back(input);
    } else {
      throw InputError(SourceLocation{input, 0, 0}, "catalogue", "", "no such file or folder");
    }
  }
  if (files.empty()) throw InputError(SourceLocation{"catalogue", 0, 0}, "", "", "no sensor files given");
  return files;
}

TableLayout catalogue_layout() {
  return TableLayout{"catalogue",
                     {"sensor", "instrument", "result", "kind", "computed", "reference", "tolerance", "unit", "delta",
                      "delta_pct", "check", "note"},
                     {false, false, false, false, true, true, true, false, true, true, false, false},
                     {0, 0, 0, 0, 6, 6, 3, 0, 0, 0, 0, 0},
                     // The text table fits 160 columns: the file stands for the instrument, the percentage for the
                     // delta, and the note is cut (--wide, CSV and JSON have all of them).
                     {false, true, false, false, false, false, false, false, true, false, false, false},
                     160};
}

std::vector<std::vector<std::string>> catalogue_rows(const std::string& file, const Report& report,
                                                     const std::vector<std::string>& extra_results) {
  const std::string stem = fs::path(file).stem().string(), &name = report.sensor_name;
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < report.results.size(); ++i) index.emplace(report.results[i].name, i);
  std::vector<std::vector<std::string>> rows;

  // [expected] checks: computed and reference in the unit the reference was written in.
  std::vector<std::string> checked;
  for (const auto& e : report.expectations) {
    auto row = empty_row(stem, name);
    row[result] = e.spec.result;
    checked.push_back(e.spec.result);
    const auto it = index.find(e.spec.result);
    double factor = 1;
    std::string shown_unit;
    if (it != index.end()) {
      const ResultInfo& info = report.results[it->second];
      factor = info.display_factor;
      shown_unit = info.display_unit;
      if (!e.spec.display_unit.empty()) {
        factor = 1.0 / units::conversion(e.spec.display_unit, info.si_unit).factor;
        shown_unit = e.spec.display_unit;
      }
    }
    const double ref = e.spec.value_si * factor;
    row[kind] = e.spec.kind.empty() ? "unstated" : e.spec.kind;
    row[reference] = full_precision(ref);
    // The deviation the check allows, in the row's unit: the larger of the absolute and the relative tolerance.
    const double checked = e.spec.follows_si.value_or(e.spec.value_si);
    row[tolerance] = full_precision(std::max(e.spec.tolerance_si, e.spec.rel_tolerance * std::abs(checked)) * factor);
    row[unit] = unit_cell(shown_unit);
    row[check] = e.passed ? "ok" : "FAIL";
    row[note] = e.spec.source;
    if (e.spec.follows_si)
      row[note] = fmt::format("erratum: the source's own inputs give {} (checked), not the printed value{}{}",
                              e.spec.follows_as_written, e.spec.source.empty() ? "" : "; ", e.spec.source);
    if (!e.found) {
      row[note] = "not computed by this sensor";
    } else {
      const double c = e.computed_si * factor;
      row[computed] = full_precision(c);
      row[delta] = fmt::format("{:+.4g}", c - ref);
      if (ref != 0) row[delta_pct] = fmt::format("{:+.3g}", 100.0 * (c - ref) / std::abs(ref));
    }
    rows.push_back(std::move(row));
  }

  // Solved unknowns: a key result each; a solve that failed is a failed check even when [expected] covers it.
  for (const auto& s : report.solves) {
    const bool covered = std::find(checked.begin(), checked.end(), s.spec.unknown) != checked.end();
    if (covered && s.converged) continue;
    auto row = empty_row(stem, name);
    row[result] = s.spec.unknown;
    row[kind] = "solve";
    if (const auto it = index.find(s.spec.unknown); it != index.end() && s.converged) {
      const ResultInfo& info = report.results[it->second];
      row[computed] = full_precision(s.value_si * info.display_factor);
      row[unit] = unit_cell(info.display_unit);
    }
    row[check] = s.converged ? "ok" : "FAIL";
    row[note] = s.converged ? fmt::format("[[solve]] root of {}", join(s.spec.criteria))
                            : "[[solve]] failed: " + s.message;
    rows.push_back(std::move(row));
  }

  // Criteria that do not hold (a saturated pixel, a NIIRS below its requirement): a failed check unless the file
  // marks the criterion informational; and the run's warnings, one row each.
  for (const auto& c : report.criteria) {
    if (c.passed) continue;
    auto row = empty_row(stem, name);
    row[result] = c.section == "detector" ? "detector.peak_pixel_fill" : c.section + ".margin";
    row[kind] = "criterion";
    if (!std::isnan(c.margin)) row[computed] = full_precision(c.margin);
    row[check] = c.informational ? "info" : "FAIL";
    row[note] = (c.informational ? "informational criterion: " : "criterion fails: ") + c.reason;
    rows.push_back(std::move(row));
  }
  for (const auto& w : report.warnings) {
    auto row = empty_row(stem, name);
    row[check] = "warning";
    row[note] = w;
    rows.push_back(std::move(row));
  }

  for (const auto& extra : extra_results) {
    auto row = empty_row(stem, name);
    row[result] = extra;
    if (const auto it = index.find(extra); it != index.end()) {
      const ResultInfo& info = report.results[it->second];
      row[computed] = full_precision(report.values[it->second] * info.display_factor);
      row[unit] = unit_cell(info.display_unit);
      row[note] = info.equation;
    } else {
      row[note] = "not computed by this sensor";
    }
    rows.push_back(std::move(row));
  }

  // [[table]] cells: "target.magnitude @ detector.integration_time = 30 s"; no check (a failed row says why).
  for (const auto& t : report.tables)
    for (std::size_t r = 0; r < t.rows.size(); ++r)
      for (std::size_t c = 0; c < t.columns.size(); ++c) {
        auto row = empty_row(stem, name);
        row[result] = fmt::format("{} @ {} = {}", t.columns[c].name, t.spec.vary, t.spec.values_written[r]);
        if (!std::isnan(t.rows[r][c])) row[computed] = full_precision(t.rows[r][c] * t.columns[c].display_factor);
        row[unit] = unit_cell(t.columns[c].display_unit);
        row[note] = t.notes[r].empty() ? "table \"" + t.spec.name + "\"" : "table \"" + t.spec.name + "\": " + t.notes[r];
        rows.push_back(std::move(row));
      }
  if (rows.empty()) {
    auto row = empty_row(stem, name);
    row[note] = "no [expected] references and no [[solve]] (add --results to show results)";
    rows.push_back(std::move(row));
  }
  return rows;
}

// --uncertainty N: the 5 % and 95 % points of each checked result and solved unknown under the file's
// [uncertainty] tolerances (Monte Carlo, seed 1, solves at every sample; batch/uncertainty.hpp).
static std::vector<std::vector<std::string>> uncertainty_rows(const std::string& file, const Chain& chain, const Report& report,
                                                       const CatalogueOptions& options) {
  UncertaintyOptions u;
  u.sensor_file = file;
  u.overrides = options.overrides;
  u.no_solve = options.no_solve;
  u.solver = options.solver;
  u.samples = options.uncertainty_samples;
  auto add = [&](const std::string& name) {
    if (std::find(u.results.begin(), u.results.end(), name) == u.results.end()) u.results.push_back(name);
  };
  for (const auto& s : report.solves) add(s.spec.unknown);
  for (const auto& e : report.expectations)
    if (e.found) add(e.spec.result);
  std::vector<std::vector<std::string>> rows;
  if (u.results.empty()) return rows;
  const Uncertainty mc = run_uncertainty(u);
  const std::string stem = fs::path(file).stem().string(), &name = report.sensor_name;
  std::vector<std::string> varied;
  for (const auto& v : mc.inputs) varied.push_back(v.key);
  for (const auto& s : mc.results) {
    const ResultInfo& info = chain.results().info(*chain.results().find(s.name));
    for (const auto& [label, value] : {std::pair{"5 %", s.p5}, std::pair{"95 %", s.p95}}) {
      auto row = empty_row(stem, name);
      row[result] = fmt::format("{} @ {}", s.name, label);
      if (!std::isnan(value)) row[computed] = full_precision(value * info.display_factor);
      row[unit] = unit_cell(info.display_unit);
      row[note] = fmt::format("Monte Carlo over [uncertainty] ({}): {} of {} samples used", join(varied), mc.used, mc.samples);
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

std::vector<std::string> catalogue_error_row(const std::string& file, const std::string& message) {
  auto row = empty_row(fs::path(file).stem().string(), "");
  row[check] = "ERROR";
  row[note] = message;
  return row;
}

void preload_plugins() {
  PluginHost& host = PluginHost::instance();
  for (const auto& file : host.discover()) {
    try {
      host.load_file(file.path);
    } catch (const std::exception&) {
      // A broken library is reported by the sensor file that asks for it.
    }
  }
}

int run_catalogue(const std::vector<std::string>& files, const CatalogueOptions& options, TableWriter& writer,
                  std::vector<std::string>* errors) {
  const PointRange points = shard_points(options.shard, files.size());
  struct Outcome {
    std::vector<std::vector<std::string>> rows;
    std::string error;
  };
  std::vector<Outcome> outcomes(points.count);
  bool failed = false, bad_input = false;
  // One file per task: files differ in cost by orders of magnitude (a spectral solve against a closed form).
  run_batch(
      points.count, points.count, 1,
      [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
          const std::string& file = files[points[i]];
          Outcome& out = outcomes[i];
          try {
            Chain chain = load_sensor(file, options.overrides,
                                      options.no_solve ? Solving::forward_only : Solving::as_written);
            if (!options.tables) chain.tables.clear();
            chain.solver = options.solver;
            const Report report = chain.run();
            out.rows = catalogue_rows(file, report, options.extra_results);
            if (options.uncertainty_samples > 0 && !chain.uncertainties.empty())
              for (auto& row : uncertainty_rows(file, chain, report, options)) out.rows.push_back(std::move(row));
          } catch (const InputError& error) {
            out.error = error.what();
          } catch (const std::exception& error) {
            out.error = fmt::format("{}: internal error: {}", file, error.what());
          } catch (...) {  // a plugin may throw anything: it fails its own file, not the catalogue
            out.error = fmt::format("{}: internal error: a plugin threw an exception that is not a std::exception", file);
          }
          if (!out.error.empty()) out.rows = {catalogue_error_row(file, out.error)};
          if (options.progress) options.progress->fetch_add(1, std::memory_order_relaxed);
        }
      },
      [&](std::size_t i) {
        for (const auto& row : outcomes[i].rows) {
          failed = failed || row[check] == "FAIL";
          writer.row(points[i], row);
        }
        if (!outcomes[i].error.empty()) {
          bad_input = true;
          if (errors) errors->push_back(outcomes[i].error);
        }
      });
  return bad_input ? 2 : failed ? 1 : 0;
}

std::string catalogue_job(const std::vector<std::string>& files, const CatalogueOptions& options) {
  std::string job = "catalogue\n";
  for (const auto& f : files) job += "file " + f + "\n";
  for (const auto& o : options.overrides) job += "set " + o.key + "=" + o.value + "\n";
  for (const auto& r : options.extra_results) job += "result " + r + "\n";
  if (options.no_solve) job += "no-solve\n";
  if (options.tables) job += "tables\n";
  if (options.uncertainty_samples > 0) job += fmt::format("uncertainty {}\n", options.uncertainty_samples);
  if (options.solver == SolverChoice::root) job += "solver root\n";
  return job;
}

std::unique_ptr<TableSummary> catalogue_summary() { return std::make_unique<CatalogueSummary>(); }

}  // namespace radchain

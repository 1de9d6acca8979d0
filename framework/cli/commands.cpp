// The subcommands: option structs in, framework calls, exit code out.
#include "commands.hpp"

#include "progress.hpp"
#include "radchain/catalogue.hpp"
#include "radchain/chain.hpp"
#include "radchain/compare.hpp"
#include "radchain/mtf_curves.hpp"
#include "radchain/error.hpp"
#include "radchain/plugin_host.hpp"
#include "radchain/report.hpp"
#include "radchain/shard.hpp"
#include "radchain/sweep.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <memory>

namespace radchain::cli {
namespace {

// --set key=value; the value may be quoted for the shell's sake: optics.aperture="20 cm".
Override parse_override(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(SourceLocation{"--set", 0, 0}, "", text, "expected <section>.<key>=<value>, e.g. optics.aperture=\"20 cm\"");
  return Override{text.substr(0, eq), text.substr(eq + 1)};
}


std::string unquoted(std::string text) {
  if (text.size() >= 2 && text.front() == '"' && text.back() == '"') text = text.substr(1, text.size() - 2);
  return text;
}

// The stream a command writes to: --out file, or stdout.
class Sink {
 public:
  explicit Sink(const std::string& path) {
    if (path.empty()) return;
    file_.open(path, std::ios::binary);
    if (!file_) throw InputError(SourceLocation{"--out", 0, 0}, "", path, "cannot be written (missing folder or no permission)");
  }
  std::ostream& stream() { return file_.is_open() ? static_cast<std::ostream&>(file_) : std::cout; }

 private:
  std::ofstream file_;
};

TableFormat format_of(const Output& output, TableFormat fallback) {
  if (!output.format.empty()) return parse_table_format(output.format);
  if (!output.out.empty())
    if (auto f = table_format_of_path(output.out)) return *f;
  return fallback;
}

ShardSpec shard_of(const Batch& batch) {
  if (batch.shard.empty()) {
    if (batch.shard_order != "block" && batch.shard_order != "round-robin")
      throw InputError(SourceLocation{"--shard-order", 0, 0}, "", batch.shard_order, "expected block or round-robin");
    return {};
  }
  return parse_shard(batch.shard, batch.shard_order);
}

std::string kind_section_example(Kind kind) { return kind == Kind::criterion ? "criteria.<name>" : to_string(kind); }

void print_description(const PluginInfo& info, const std::string& path) {
  fmt::print("{} — {} plugin (framework {}, ABI {})\n", info.name, to_string(info.kind), info.framework_version, info.abi_version);
  fmt::print("  {}\n", info.summary);
  fmt::print("  physics: {}\n", info.reference);
  fmt::print("  file: {}\n\nkeys:\n", path);
  const Schema& schema = info.schema();
  std::size_t width = 6;
  for (const auto& p : schema) width = std::max(width, p.key.size());
  for (const auto& p : schema) {
    std::string kind;
    switch (p.type) {
      case ParamType::quantity: kind = "quantity [" + p.si_unit + "]"; break;
      case ParamType::number: kind = "number"; break;
      case ParamType::integer: kind = "integer"; break;
      case ParamType::text: kind = "string"; break;
      case ParamType::choice: kind = "choice"; break;
      case ParamType::flag: kind = "boolean"; break;
      case ParamType::spectrum: kind = "spectrum CSV [" + p.si_unit + "]"; break;
    }
    const std::string status = p.required ? "required" : p.default_value ? "default " + *p.default_value : "optional";
    fmt::print("  {:<{}}  {:<24} {:<22} {}\n", p.key, width, kind, status, p.doc);
    const std::string range = p.range_text();
    if (!range.empty()) fmt::print("  {:<{}}  {:<24} accepted: {}\n", "", width, "", range);
  }
  fmt::print("\nexample:\n[{}]\nplugin = \"{}\"\n", kind_section_example(info.kind), info.name);
  for (const auto& p : schema) {
    const std::string value = p.required || !p.default_value ? p.example
                              : (p.type == ParamType::quantity || p.type == ParamType::choice || p.type == ParamType::text ||
                                 p.type == ParamType::spectrum)
                                  ? "\"" + *p.default_value + "\""
                                  : *p.default_value;
    const std::string line = fmt::format("{}{} = {}", p.required || p.default_value ? "" : "# ", p.key, value);
    fmt::print("{:<40} # {}{}\n", line, p.required ? "required: " : p.default_value ? "" : "optional: ", p.doc);
  }
}

}  // namespace

std::vector<Override> parse_overrides(const std::vector<std::string>& sets) {
  std::vector<Override> out;
  for (const auto& s : sets) out.push_back(parse_override(s));
  return out;
}

int run(const RunOptions& options) {
  Chain chain = load_sensor(options.sensor, parse_overrides(options.sets));
  const Report report = chain.run();
  std::cout << (options.format == "json" ? format_report_json(report) : format_report_text(report));
  return report.all_passed() ? 0 : 1;
}

int catalogue(const CatalogueCommand& command) {
  CatalogueOptions options;
  options.overrides = parse_overrides(command.sets);
  options.extra_results = command.results;
  options.shard = shard_of(command.batch);
  const TableFormat format = format_of(command.output, TableFormat::text);
  const std::vector<std::string> files = catalogue_files(command.inputs);
  limit_threads(command.batch.threads);

  Progress progress("catalogue");
  options.progress = progress.counter();
  Sink sink(command.output.out);
  TableWriter writer(sink.stream(), format, catalogue_layout(), files.size(), options.shard,
                     catalogue_job(files, options));
  progress.start(shard_points(options.shard, files.size()).count);
  std::vector<std::string> errors;
  const int code = run_catalogue(files, options, writer, &errors);
  progress.stop();
  writer.finish(code);
  for (const auto& e : errors) std::cerr << e << "\n";
  return code;
}

int compare(const CompareCommand& command) {
  std::optional<double> tolerance;
  if (!command.tolerance.empty()) tolerance = parse_tolerance(command.tolerance);
  const TableFormat format = format_of(command.output, TableFormat::text);
  const auto overrides = parse_overrides(command.sets);
  const CompareInput a = load_compare_input(command.a, overrides);
  const CompareInput b = load_compare_input(command.b, overrides);
  const Comparison comparison = radchain::compare(a, b);
  Sink sink(command.output.out);
  write_comparison(comparison, format, sink.stream(), tolerance);
  return tolerance && count_exceeding(comparison, *tolerance) > 0 ? 1 : 0;
}

int sweep(const SweepCommand& command) {
  SweepOptions options;
  options.sensor_file = command.sensor;
  for (const auto& s : command.sets) {
    Override o = parse_override(s);
    if (is_sweep_range(unquoted(o.value)))
      options.axes.emplace_back(o.key, unquoted(o.value));
    else
      options.overrides.push_back(o);
  }
  if (options.axes.empty())
    throw InputError(SourceLocation{"sweep", 0, 0}, "", "",
                     "no axis: give at least one --set <section>.<key>=from:to:steps, e.g. --set optics.aperture=\"15 cm:30 cm:16\"");
  options.results = command.results;
  options.shard = shard_of(command.batch);
  const TableFormat format = format_of(command.output, TableFormat::csv);
  if (!command.plot.empty() && options.axes.size() != 1)
    throw InputError(SourceLocation{"--plot", 0, 0}, "", command.plot,
                     fmt::format("plots are drawn for 1-D sweeps; this sweep has {} axes (plot the CSV instead)", options.axes.size()));
  if (!command.plot.empty() && options.shard.active())
    throw InputError(SourceLocation{"--plot", 0, 0}, "", command.plot, "a shard has part of the sweep: plot the merged output");
  limit_threads(command.batch.threads);

  Progress progress("sweep");
  options.progress = progress.counter();
  Sweep sweep(options);

  // The plotted series: --results, else the solved unknowns, else the SNR, else the first result.
  std::vector<std::size_t> plotted;
  if (!command.plot.empty()) {
    const auto& names = sweep.results();
    auto index_of = [&](const std::string& name) {
      return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
    };
    if (!command.results.empty()) {
      for (std::size_t i = 0; i < names.size(); ++i) plotted.push_back(i);
    } else {
      Chain chain = load_sensor(options.sensor_file, options.overrides);
      for (const auto& s : chain.solves)
        if (index_of(s.unknown) < names.size()) plotted.push_back(index_of(s.unknown));
      if (plotted.empty() && index_of("detector.snr") < names.size()) plotted.push_back(index_of("detector.snr"));
      if (plotted.empty() && !names.empty()) plotted.push_back(0);
    }
  }
  std::vector<double> x;
  std::vector<PlotSeries> series;
  for (std::size_t i : plotted) series.push_back(PlotSeries{sweep.results()[i], sweep.result_units()[i], {}});
  auto observer = [&](std::size_t, const double* values) {
    x.push_back(values[0]);
    for (std::size_t s = 0; s < plotted.size(); ++s) series[s].y.push_back(values[sweep.axes().size() + plotted[s]]);
  };

  Sink sink(command.output.out);
  TableWriter writer(sink.stream(), format, sweep.layout(), sweep.points(), options.shard, sweep.job());
  progress.start(shard_points(options.shard, sweep.points()).count);
  std::string failure;
  const int code = sweep.run(writer, &failure, plotted.empty() ? std::function<void(std::size_t, const double*)>() : observer);
  progress.stop();
  writer.finish(code);
  if (code != 0) std::cerr << "radchain sweep: " << failure << "\n";
  if (!command.plot.empty()) {
    const SweepAxis& axis = sweep.axes().front();
    const std::string x_label = axis.unit.empty() ? axis.key : axis.key + " [" + axis.unit + "]";
    try {
      Chain chain = load_sensor(options.sensor_file, options.overrides);
      plot_sweep(command.plot, chain.sensor_name + " — " + options.sensor_file, x_label, x, series);
    } catch (const std::runtime_error& error) {
      if (dynamic_cast<const InputError*>(&error)) throw;
      throw InputError(SourceLocation{"--plot", 0, 0}, "", command.plot, error.what());
    }
  }
  return code;
}

int merge(const MergeCommand& command) {
  std::optional<TableFormat> format;
  if (!command.output.format.empty())
    format = parse_table_format(command.output.format);
  else if (!command.output.out.empty())
    format = table_format_of_path(command.output.out);
  Sink sink(command.output.out);
  return merge_shards(command.shards, sink.stream(), format);
}

int plugins() {
  const auto found = PluginHost::instance().discover();
  fmt::print("{:<20} {:<11} {:<8} {}\n", "name", "kind", "version", "file");
  for (const auto& f : found) {
    const PluginInfo& info = PluginHost::instance().load_file(f.path);
    fmt::print("{:<20} {:<11} {:<8} {}\n", info.name, to_string(info.kind), info.framework_version, f.path);
  }
  fmt::print("{} plugins (search path: {})\n", found.size(), join(PluginHost::instance().search_path(), ":"));
  return 0;
}

int describe(const std::string& name) {
  if (name.find('/') != std::string::npos) {
    print_description(PluginHost::instance().load_file(name), name);
    return 0;
  }
  for (const auto& f : PluginHost::instance().discover())
    if (f.name == name) {
      print_description(PluginHost::instance().load_file(f.path), f.path);
      return 0;
    }
  std::vector<std::string> names;
  for (const auto& f : PluginHost::instance().discover()) names.push_back(f.name);
  const std::string near = nearest_match(name, names);
  throw InputError({}, "describe", name,
                   fmt::format("unknown plugin{}; available: {}", near.empty() ? "" : " (did you mean \"" + near + "\"?)",
                               join(names)));
}

int mtf(const MtfCommand& options) {
  Chain chain = load_sensor(options.sensor, parse_overrides(options.sets));
  const Report report = chain.run();
  const MtfCurves curves = mtf_curves(report);
  const std::string csv = mtf_curves_csv(curves);
  if (options.out.empty()) {
    std::cout << csv;
  } else {
    std::ofstream file(options.out);
    if (!(file << csv)) throw InputError(SourceLocation{options.out, 0, 0}, "mtf", "--out", "cannot be written");
  }
  if (!options.plot.empty()) {
    std::vector<double> frequency_mm;
    for (double nu : curves.frequency_per_m) frequency_mm.push_back(nu * 1e-3);
    plot_sweep(options.plot,
               fmt::format("{}: MTF at {:.3g} um, f/{:.3g}, eta = {:.3g}", report.sensor_name, curves.wavelength_m * 1e6,
                           curves.f_number, curves.eta),
               "spatial frequency (mm-1)", frequency_mm,
               {{"diffraction-limited objective", "", curves.diffraction},
                {"objective, eq. (7)", "", curves.objective},
                {"detector element, eq. (8)", "", curves.detector},
                {"system, eq. (10)", "", curves.system}});
  }
  return report.all_passed() ? 0 : 1;
}

}  // namespace radchain::cli

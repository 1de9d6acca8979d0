// radchain: the command-line host. Subcommands: run, catalogue, plugins, describe.
// Exit codes: 0 ok, 1 a failed check ([expected] or a solve), 2 bad input.
#include "radchain/chain.hpp"
#include "radchain/error.hpp"
#include "radchain/plugin_host.hpp"
#include "radchain/report.hpp"
#include "radchain/units.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>

namespace fs = std::filesystem;
using namespace radchain;

namespace {

std::vector<Override> parse_overrides(const std::vector<std::string>& sets) {
  std::vector<Override> out;
  for (const auto& s : sets) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError(SourceLocation{"--set", 0, 0}, "", s, "expected <section>.<key>=<value>, e.g. optics.aperture=\"20 cm\"");
    out.push_back(Override{s.substr(0, eq), s.substr(eq + 1)});
  }
  return out;
}

std::string kind_section_example(Kind kind) {
  return kind == Kind::criterion ? "criteria.<name>" : to_string(kind);
}

void describe(const PluginInfo& info, const std::string& path) {
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

std::vector<std::string> sensor_files(const std::vector<std::string>& inputs) {
  std::vector<std::string> files;
  for (const auto& input : inputs) {
    if (fs::is_directory(input)) {
      std::vector<std::string> found;
      for (const auto& e : fs::directory_iterator(input))
        if (e.is_regular_file() && e.path().extension() == ".toml") found.push_back(e.path().string());
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else {
      files.push_back(input);
    }
  }
  return files;
}

int catalogue(const std::vector<std::string>& inputs, const std::vector<Override>& overrides) {
  const auto files = sensor_files(inputs);
  bool all_passed = true;
  fmt::print("{:<34} {:<38} {:>16} {:>16} {:>12} {}\n", "sensor", "result", "computed", "printed", "delta", "check");
  for (const auto& file : files) {
    Chain chain = load_sensor(file, overrides);
    const Report report = chain.run();
    const std::string name = fs::path(file).stem().string();
    for (const auto& s : report.solves)
      if (!s.converged) {
        all_passed = false;
        fmt::print("{:<34} solve {} FAILED: {}\n", name, s.spec.unknown, s.message);
      }
    for (const auto& e : report.expectations) {
      const ResultInfo* info = nullptr;
      for (const auto& r : report.results)
        if (r.name == e.spec.result) info = &r;
      // Show the computed value in the unit the printed reference was written in.
      double factor = info->display_factor;
      std::string unit = info->display_unit == "1" ? "" : info->display_unit;
      if (!e.spec.display_unit.empty()) {
        factor = 1.0 / units::conversion(e.spec.display_unit, info->si_unit).factor;
        unit = e.spec.display_unit;
      }
      const double rel = e.spec.value_si != 0 ? (e.computed_si - e.spec.value_si) / std::abs(e.spec.value_si) : 0.0;
      fmt::print("{:<34} {:<38} {:>16} {:>16} {:>11.2f}% {}\n", name, e.spec.result,
                 fmt::format("{:.5g} {}", e.computed_si * factor, unit), e.spec.as_written, 100 * rel,
                 e.passed ? "ok" : "FAIL");
      all_passed = all_passed && e.passed;
    }
  }
  fmt::print("{} sensor files, {}\n", files.size(), all_passed ? "all checks passed" : "SOME CHECKS FAILED");
  return all_passed ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"radchain — end-to-end radiometry of electro-optical sensors"};
  app.require_subcommand(1);
  std::vector<std::string> plugin_path;
  app.add_option("--plugin-path", plugin_path, "extra plugin folders (searched first; colon-separated allowed)");

  auto* run = app.add_subcommand("run", "evaluate one sensor file forward, perform its solves, check [expected]");
  std::string run_file, format = "text";
  std::vector<std::string> run_sets;
  run->add_option("sensor", run_file, "sensor TOML file")->required();
  run->add_option("--set", run_sets, "override a key: section.key=value (repeatable)");
  run->add_option("--format", format, "text or json")->check(CLI::IsMember({"text", "json"}));

  auto* cat = app.add_subcommand("catalogue", "run many sensor files and print computed vs published values");
  std::vector<std::string> cat_inputs;
  std::vector<std::string> cat_sets;
  cat->add_option("inputs", cat_inputs, "sensor files or folders")->required();
  cat->add_option("--set", cat_sets, "override a key in every file: section.key=value (repeatable)");

  auto* plugins = app.add_subcommand("plugins", "list the plugins found on the search path");
  auto* desc = app.add_subcommand("describe", "show a plugin's keys, units, defaults, ranges and a TOML example");
  std::string describe_name;
  desc->add_option("plugin", describe_name, "plugin name (or path to a plugin .so)")->required();

  CLI11_PARSE(app, argc, argv);
  try {
    PluginHost::instance().configure(plugin_path);
    if (*run) {
      Chain chain = load_sensor(run_file, parse_overrides(run_sets));
      const Report report = chain.run();
      std::cout << (format == "json" ? format_report_json(report) : format_report_text(report));
      return report.all_passed() ? 0 : 1;
    }
    if (*cat) return catalogue(cat_inputs, parse_overrides(cat_sets));
    if (*plugins) {
      const auto found = PluginHost::instance().discover();
      fmt::print("{:<20} {:<11} {:<8} {}\n", "name", "kind", "version", "file");
      for (const auto& f : found) {
        const PluginInfo& info = PluginHost::instance().load_file(f.path);
        fmt::print("{:<20} {:<11} {:<8} {}\n", info.name, to_string(info.kind), info.framework_version, f.path);
      }
      fmt::print("{} plugins (search path: {})\n", found.size(), join(PluginHost::instance().search_path(), ":"));
      return 0;
    }
    if (*desc) {
      if (describe_name.find('/') != std::string::npos) {
        describe(PluginHost::instance().load_file(describe_name), describe_name);
        return 0;
      }
      for (const auto& f : PluginHost::instance().discover())
        if (f.name == describe_name) {
          describe(PluginHost::instance().load_file(f.path), f.path);
          return 0;
        }
      std::vector<std::string> names;
      for (const auto& f : PluginHost::instance().discover()) names.push_back(f.name);
      const std::string near = nearest_match(describe_name, names);
      throw InputError({}, "describe", describe_name,
                       fmt::format("unknown plugin{}; available: {}", near.empty() ? "" : " (did you mean \"" + near + "\"?)",
                                   join(names)));
    }
  } catch (const InputError& error) {
    std::cerr << error.what() << "\n";
    return static_cast<int>(ExitCode::bad_input);
  } catch (const std::exception& error) {
    std::cerr << "radchain: internal error: " << error.what() << "\n";
    return 3;
  }
  return 0;
}

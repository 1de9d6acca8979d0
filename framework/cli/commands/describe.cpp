// `radchain describe <plugin>`: a plugin's keys, units, defaults, ranges and a TOML example.
#include "../common.hpp"
#include "radchain/chain.hpp"
#include "radchain/error.hpp"
#include "radchain/plugin_host.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <iostream>

namespace radchain::cli {

namespace {

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

}  // namespace radchain::cli

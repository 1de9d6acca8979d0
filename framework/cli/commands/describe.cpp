// `radchain describe <plugin>`: a plugin's keys, units, defaults, ranges, the results it publishes and needs
// (its contract with the other stages, radchain/vocabulary.hpp), and a TOML example.
// `radchain describe <kind>` ("criterion", or its section "criteria"): the plugins of that kind, one line each.
// `radchain describe sensor | solve | expected | table | render | validate`: a sensor file's own tables, an imaging command's options.
#include "../commands.hpp"
#include "../option_schema.hpp"

#include "radchain/error.hpp"
#include "radchain/plugin_host.hpp"
#include "radchain/sensor_file.hpp"
#include "radchain/schema.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <utility>
#include <vector>

namespace radchain::cli {

namespace {

std::string kind_section_example(Kind kind) { return kind == Kind::criterion ? "criteria.<name>" : to_string(kind); }

// "criteria.*.margin" reads as the criterion section a user writes.
std::string shown_name(const Term& term) {
  return term.per_criterion() ? term.in_criterion("<name>") : std::string(term.name);
}

void print_terms(const char* heading, const std::vector<std::pair<Term, std::string>>& terms) {
  fmt::print("\n{}\n", heading);
  if (terms.empty()) fmt::print("  (none)\n");
  std::size_t width = 0, unit_width = 0;
  for (const auto& [term, note] : terms)
    width = std::max(width, shown_name(term).size()), unit_width = std::max(unit_width, term.unit.size() + 2);
  for (const auto& [term, note] : terms)
    fmt::print("  {:<{}}  {:<{}}  {}{}\n", shown_name(term), width, fmt::format("[{}]", term.unit), unit_width, term.meaning,
               note);
}

void print_contract(const PluginInfo& info) {
  std::vector<std::pair<Term, std::string>> publishes, needs;
  for (const Term& t : info.publishes) publishes.emplace_back(t, "");
  for (const Need& n : info.needs) needs.emplace_back(n.term, n.optional ? " (read if an earlier stage publishes it)" : "");
  print_terms("publishes:", publishes);
  print_terms("needs:", needs);
}

// The keys of a schema: name, type (with unit), required / default, doc, accepted range.
void print_keys(const Schema& schema) {
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
    if (p.shape == ParamShape::list) kind += ", or a list";
    if (p.shape == ParamShape::pair) kind = "[low, high] " + kind;
    const std::string status = p.required ? "required" : p.default_value ? "default " + *p.default_value : "optional";
    fmt::print("  {:<{}}  {:<24} {:<22} {}\n", p.key, width, kind, status, p.doc);
    const std::string range = p.range_text();
    if (!range.empty()) fmt::print("  {:<{}}  {:<24} accepted: {}\n", "", width, "", range);
    if (!p.former_keys.empty()) fmt::print("  {:<{}}  {:<24} formerly: {}\n", "", width, "", join(p.former_keys));
  }
}

void print_description(const PluginInfo& info, const std::string& path) {
  fmt::print("{} — {} plugin (framework {}, ABI {})\n", info.name, to_string(info.kind), info.framework_version, info.abi_version);
  fmt::print("  {}\n", info.summary);
  fmt::print("  physics: {}\n", info.reference);
  fmt::print("  file: {}\n\nkeys:\n", path);
  const Schema& schema = info.schema();
  print_keys(schema);
  print_contract(info);
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

// The sensor file's own tables, `radchain describe sensor | solve | expected | table` (radchain/sensor_file.hpp), and the
// options of the imaging commands, `radchain describe render | validate` (option_schema.hpp).
bool print_file_table(const std::string& name) {
  if (name == "sensor") {
    fmt::print("[sensor] — the instrument's identity (every key optional)\n\nkeys:\n");
    print_keys(sensor_table_schema());
  } else if (name == "solve") {
    fmt::print("[[solve]] — a parameter the chain solves for, one entry per unknown\n\nkeys:\n");
    print_keys(solve_entry_schema());
    fmt::print("\nexample:\n[[solve]]\nunknown = \"optics.aperture\"\ncriterion = [\"energy\", \"matching\"]\n"
               "bracket = [\"1 cm\", \"2 m\"]          # in the unknown's unit\n");
  } else if (name == "expected") {
    fmt::print("[expected] — a published value of a result, checked by run and catalogue (one entry per result)\n\nkeys:\n");
    print_keys(expected_entry_schema());
    fmt::print("\nexample:\n[expected]\n\"optics.focal_length\" = {{ value = \"832 mm\", tolerance = \"1 mm\", "
               "source = \"Kolobrodov 1996, p. 4\" }}   # value, follows, tolerance in the result's unit\n");
  } else if (name == "table") {
    fmt::print("[[table]] — the [[solve]] entries (or named results) again at each value of one parameter, printed by run and "
               "catalogue --tables\n\nkeys:\n");
    print_keys(table_entry_schema());
    fmt::print("\nexample:\n[[table]]\nname = \"limiting magnitude vs exposure\"\nvary = \"detector.integration_time\"\n"
               "values = [\"1 s\", \"10 s\", \"30 s\", \"100 s\"]   # in the varied parameter's unit\n");
  } else if (name == "render" || name == "validate") {
    fmt::print("radchain {} — options with units, limits or fixed choices (validated like a sensor file's keys)\n\noptions:\n", name);
    print_keys(name == "render" ? render_option_schema() : validate_option_schema());
  } else {
    return false;
  }
  return true;
}

void print_kind(Kind kind) {
  const KindInfo& k = *std::find_if(kinds.begin(), kinds.end(), [&](const KindInfo& i) { return i.kind == kind; });
  fmt::print("{} plugins (section [{}]):\n", k.name, kind_section_example(kind));
  std::vector<const PluginInfo*> found;
  std::size_t width = 0;
  for (const auto& f : PluginHost::instance().discover())
    if (f.kind == kind) {
      found.push_back(&PluginHost::instance().load_file(f.path));
      width = std::max(width, f.name.size());
    }
  for (const PluginInfo* info : found) fmt::print("  {:<{}}  {}\n", info->name, width, info->summary);
  if (found.empty()) fmt::print("  (none on the search path)\n");
}

std::optional<Kind> kind_named(const std::string& name) {
  if (auto kind = kind_from_name(name)) return kind;
  for (const KindInfo& k : kinds)
    if (k.section == name) return k.kind;
  return std::nullopt;
}

}  // namespace

int describe(const std::string& name) {
  if (print_file_table(name)) return 0;
  if (auto kind = kind_named(name)) {
    print_kind(*kind);
    return 0;
  }
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
  std::vector<std::string> kind_names;
  for (const KindInfo& k : kinds) kind_names.emplace_back(k.name);
  const std::vector<std::string> tables = {"sensor", "solve", "expected", "table", "render", "validate"};
  std::vector<std::string> candidates = names;
  candidates.insert(candidates.end(), kind_names.begin(), kind_names.end());
  candidates.insert(candidates.end(), tables.begin(), tables.end());
  throw InputError({}, "describe", name,
                   fmt::format("unknown plugin, kind, table or command{}; plugins: {}; kinds: {}; tables and commands: {}",
                               did_you_mean(name, candidates), join(names), join(kind_names),
                               join(tables)));
}

}  // namespace radchain::cli

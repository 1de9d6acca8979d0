// The describe model (radchain/batch/describe.hpp): plugins from the plugin host, the sensor file's own tables
// from the schemas that validate them (radchain/sensor_file.hpp), the imaging commands' options from theirs
// (radchain/command_options.hpp).
#include "radchain/batch/describe.hpp"

#include "radchain/command_options.hpp"
#include "radchain/error.hpp"
#include "radchain/plugin_host.hpp"
#include "radchain/schema.hpp"
#include "radchain/sensor_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <optional>

namespace radchain {
namespace {

std::string type_name(ParamType type) {
  switch (type) {
    case ParamType::quantity: return "quantity";
    case ParamType::number: return "number";
    case ParamType::integer: return "integer";
    case ParamType::text: return "string";
    case ParamType::choice: return "choice";
    case ParamType::flag: return "boolean";
    case ParamType::spectrum: return "spectrum";
  }
  return "?";
}

std::vector<KeyDescription> keys_of(const Schema& schema) {
  std::vector<KeyDescription> keys;
  for (const ParamSpec& p : schema) keys.push_back(describe_key(p));
  return keys;
}

TermDescription term_of(const Term& term, bool optional = false) {
  // "criteria.*.margin" reads as the criterion section a user writes
  return {term.per_criterion() ? term.in_criterion("<name>") : std::string(term.name), std::string(term.unit),
          std::string(term.meaning), optional};
}

std::string kind_section_example(Kind kind) { return kind == Kind::criterion ? "criteria.<name>" : std::string(to_string(kind)); }

// A plugin's section with every key: required ones with their example, defaults as they are, optional ones commented.
std::string plugin_example(const PluginInfo& info) {
  std::string text = fmt::format("[{}]\nplugin = \"{}\"\n", kind_section_example(info.kind), info.name);
  for (const ParamSpec& p : info.schema()) {
    const bool quoted = p.type == ParamType::quantity || p.type == ParamType::choice || p.type == ParamType::text ||
                        p.type == ParamType::spectrum;
    const std::string value = p.required || !p.default_value ? p.example : quoted ? "\"" + *p.default_value + "\"" : *p.default_value;
    const std::string line = fmt::format("{}{} = {}", p.required || p.default_value ? "" : "# ", p.key, value);
    text += fmt::format("{:<40} # {}{}\n", line, p.required ? "required: " : p.default_value ? "" : "optional: ", p.doc);
  }
  return text;
}

Description describe_plugin(const PluginInfo& info, const std::string& path) {
  Description d;
  d.what = Description::What::plugin;
  d.name = info.name;
  d.kind = to_string(info.kind);
  d.title = fmt::format("{} — {} plugin (framework {}, ABI {})", info.name, d.kind, info.framework_version, info.abi_version);
  d.summary = info.summary;
  d.reference = info.reference;
  d.file = path;
  d.framework_version = info.framework_version;
  d.abi_version = info.abi_version;
  d.keys = keys_of(info.schema());
  for (const Term& t : info.publishes) d.publishes.push_back(term_of(t));
  for (const Need& n : info.needs) d.needs.push_back(term_of(n.term, n.optional));
  d.example = plugin_example(info);
  return d;
}

// The sensor file's own tables and the imaging commands' options.
std::optional<Description> describe_table_or_command(const std::string& name) {
  Description d;
  d.name = name;
  d.what = Description::What::table;
  if (name == "sensor") {
    d.title = "[sensor] — the instrument's identity (every key optional)";
    d.keys = keys_of(sensor_table_schema());
  } else if (name == "solve") {
    d.title = "[[solve]] — a parameter the chain solves for, one entry per unknown";
    d.keys = keys_of(solve_entry_schema());
    d.example = "[[solve]]\nunknown = \"optics.aperture\"\ncriterion = [\"energy\", \"matching\"]\n"
                "bracket = [\"1 cm\", \"2 m\"]          # in the unknown's unit\n";
  } else if (name == "expected") {
    d.title = "[expected] — a published value of a result, checked by run and catalogue (one entry per result)";
    d.keys = keys_of(expected_entry_schema());
    d.example = "[expected]\n\"optics.focal_length\" = { value = \"832 mm\", tolerance = \"1 mm\", "
                "source = \"Kolobrodov 1996, p. 4\" }   # value, follows, tolerance in the result's unit\n";
  } else if (name == "table") {
    d.title = "[[table]] — the [[solve]] entries (or named results) again at each value of one parameter, printed by run "
              "and catalogue --tables";
    d.keys = keys_of(table_entry_schema());
    d.example = "[[table]]\nname = \"limiting magnitude vs exposure\"\nvary = \"detector.integration_time\"\n"
                "values = [\"1 s\", \"10 s\", \"30 s\", \"100 s\"]   # in the varied parameter's unit\n";
  } else if (name == "render" || name == "validate") {
    d.what = Description::What::command;
    d.title = "radchain " + name + " — options with units, limits or fixed choices (validated like a sensor file's keys)";
    d.keys = keys_of(name == "render" ? render_option_schema() : validate_option_schema());
  } else {
    return std::nullopt;
  }
  return d;
}

std::optional<Kind> kind_named(const std::string& name) {
  if (auto kind = kind_from_name(name)) return kind;
  for (const KindInfo& k : kinds)
    if (k.section == name) return k.kind;
  return std::nullopt;
}

Description describe_kind(Kind kind) {
  const KindInfo& k = *std::find_if(kinds.begin(), kinds.end(), [&](const KindInfo& i) { return i.kind == kind; });
  Description d;
  d.what = Description::What::kind;
  d.name = k.name;
  d.section = kind_section_example(kind);
  d.title = fmt::format("{} plugins (section [{}])", k.name, d.section);
  for (const auto& f : PluginHost::instance().discover())
    if (f.kind == kind) {
      const PluginInfo& info = PluginHost::instance().load_file(f.path);
      d.plugins.push_back({info.name, info.summary, f.path});
    }
  return d;
}

}  // namespace

const char* to_string(Description::What what) {
  switch (what) {
    case Description::What::plugin: return "plugin";
    case Description::What::kind: return "kind";
    case Description::What::table: return "table";
    case Description::What::command: return "command";
  }
  return "?";
}

KeyDescription describe_key(const ParamSpec& p) {
  KeyDescription k;
  k.key = p.key;
  k.type = type_name(p.type);
  if (p.type == ParamType::quantity || p.type == ParamType::spectrum) k.si_unit = p.si_unit;
  k.shape = p.shape == ParamShape::list ? "list" : p.shape == ParamShape::pair ? "pair" : "scalar";
  k.required = p.required;
  k.default_value = p.default_value;
  k.example = p.example;
  k.doc = p.doc;
  k.accepted = p.range_text();
  k.formerly = p.former_keys;
  k.spectral = p.spectral;
  return k;
}

Description describe(const std::string& name) {
  if (auto table = describe_table_or_command(name)) return *table;
  if (auto kind = kind_named(name)) return describe_kind(*kind);
  if (name.find('/') != std::string::npos) return describe_plugin(PluginHost::instance().load_file(name), name);
  std::vector<std::string> names;
  for (const auto& f : PluginHost::instance().discover()) {
    if (f.name == name) return describe_plugin(PluginHost::instance().load_file(f.path), f.path);
    names.push_back(f.name);
  }
  std::vector<std::string> kind_names;
  for (const KindInfo& k : kinds) kind_names.emplace_back(k.name);
  const std::vector<std::string> tables = {"sensor", "solve", "expected", "table", "render", "validate"};
  std::vector<std::string> candidates = names;
  candidates.insert(candidates.end(), kind_names.begin(), kind_names.end());
  candidates.insert(candidates.end(), tables.begin(), tables.end());
  throw InputError({}, "describe", name,
                   fmt::format("unknown plugin, kind, table or command{}; plugins: {}; kinds: {}; tables and commands: {}",
                               did_you_mean(name, candidates), join(names), join(kind_names), join(tables)));
}

}  // namespace radchain

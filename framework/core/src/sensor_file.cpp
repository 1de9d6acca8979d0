// Sensor file -> Chain: parse, apply --set overrides, load one plugin per section, validate every key
// against the plugin's schema, then read [[solve]] and [expected].
#include "radchain/chain.hpp"
#include "radchain/error.hpp"
#include "radchain/plugin_host.hpp"
#include "radchain/units.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace radchain {
namespace {

// Evaluation order. The atmosphere precedes the target: it attenuates the illumination on the way down
// (ground scenes) and hands the target the up-path transmittance for what leaves it.
const std::vector<std::string> stage_sections = {"source", "atmosphere", "target", "optics", "detector"};
const std::vector<std::string> top_level_keys = {"sensor", "platform", "source", "target", "atmosphere", "optics",
                                                 "detector", "criteria", "solve", "expected"};
const std::vector<std::string> sensor_keys = {"name", "description", "reference", "notes"};

Kind kind_of_section(const std::string& section) {
  if (section == "platform") return Kind::platform;
  if (section == "source") return Kind::source;
  if (section == "target") return Kind::target;
  if (section == "atmosphere") return Kind::atmosphere;
  if (section == "optics") return Kind::optics;
  if (section == "detector") return Kind::detector;
  return Kind::criterion;
}

void apply_override(ConfigValue& root, const Override& o) {
  const SourceLocation where{"--set", 0, 0};
  std::vector<std::string> path;
  std::size_t start = 0;
  for (std::size_t dot; (dot = o.key.find('.', start)) != std::string::npos; start = dot + 1)
    path.push_back(o.key.substr(start, dot - start));
  path.push_back(o.key.substr(start));
  if (path.size() < 2) throw InputError(where, "", o.key, "expected <section>.<key>=<value>, e.g. optics.aperture=\"20 cm\"");
  ConfigValue* table = &root;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    ConfigValue* next = table->find(path[i]);
    if (!next || next->type != ConfigValue::Type::table) {
      std::vector<std::string> sections;
      for (const auto& [name, member] : table->members)
        if (member.type == ConfigValue::Type::table) sections.push_back(name);
      const std::string near = nearest_match(path[i], sections);
      throw InputError(SourceLocation{"--set " + o.key, 0, 0}, "", "",
                       fmt::format("the sensor file has no section \"{}\"{}", path[i],
                                   near.empty() ? "" : " (did you mean \"" + near + "\"?)"));
    }
    table = next;
  }
  ConfigValue value = parse_toml_value(o.value, "--set " + o.key);
  if (ConfigValue* existing = table->find(path.back())) {
    *existing = value;
  } else {
    table->members.emplace_back(path.back(), value);
  }
}

void require_table(const ConfigValue& value, const std::string& name) {
  if (value.type != ConfigValue::Type::table)
    throw InputError(value.where, name, "", "expected a table ([" + name + "]), found " + value.type_name());
}

std::string display_unit_of_example(const ParamSpec& spec) {
  if (spec.type != ParamType::quantity) return {};
  std::string example = spec.example;  // written as a TOML string: "\"15 cm\""
  if (example.size() >= 2 && example.front() == '"' && example.back() == '"') example = example.substr(1, example.size() - 2);
  try {
    return units::split_quantity(example).unit;
  } catch (...) {
    return {};
  }
}

// A quantity or number written for a parameter (solve bracket) or a result (expected value), in `si_unit`.
double scalar_in(const ConfigValue& value, const std::string& si_unit, const std::string& context,
                 const std::string& subject, std::string* unit_written = nullptr) {
  const bool dimensionless = units::dimension_of(si_unit) == "1";
  const std::string expected = dimensionless ? std::string("expected a plain number (the result has no unit)")
                                             : fmt::format("expected {} (a unit convertible to {})",
                                                           units::dimension_name(si_unit), si_unit);
  if (value.is_number()) {
    if (!dimensionless)
      throw InputError(value.where, context, subject + " = " + value.as_toml(),
                       fmt::format("a bare number has no unit: expected {}", units::dimension_name(si_unit)));
    return value.number();
  }
  if (value.type != ConfigValue::Type::string)
    throw InputError(value.where, context, subject + " = " + value.as_toml(), "expected a number with its unit, e.g. \"832 mm\"");
  auto fail = [&](const std::string& problem) {
    return InputError(value.where, context, subject + " = " + value.as_toml(), problem);
  };
  units::ParsedQuantity q;
  try {
    q = units::split_quantity(value.string_value);
  } catch (const std::invalid_argument&) {
    throw fail("does not start with a number: " + expected);
  }
  if (unit_written) *unit_written = q.unit;
  try {
    return q.number * units::conversion(q.unit.empty() ? "1" : q.unit, si_unit).factor;
  } catch (const std::invalid_argument&) {
    throw fail(fmt::format("unknown unit \"{}\": {}", q.unit, expected));
  } catch (const std::domain_error&) {
    throw fail(expected);
  }
}

// Why "<section>.<key>" is no solvable parameter: the section's numeric keys (and the nearest), or the sections.
std::string numeric_parameters_text(Chain& chain, const std::string& qualified_key) {
  const auto dot = qualified_key.rfind('.');
  if (dot == std::string::npos) return "expected <section>.<key>, e.g. \"target.magnitude\" or \"optics.aperture\"";
  const std::string section = qualified_key.substr(0, dot);
  const std::string key = qualified_key.substr(dot + 1);
  std::vector<std::string> sections;
  for (const auto& slot : chain.stages) {
    if (slot.section != section) {
      sections.push_back(slot.section);
      continue;
    }
    std::vector<std::string> keys;
    for (const auto& entry : slot.params->entries()) {
      const ParamType type = entry.spec->type;
      if (type == ParamType::quantity || type == ParamType::number || type == ParamType::integer) keys.push_back(entry.spec->key);
    }
    const std::string near = nearest_match(key, keys);
    return fmt::format("{} has no numeric parameter \"{}\"{}; its numeric parameters: {}", section, key,
                       near.empty() ? "" : " (did you mean \"" + near + "\"?)", keys.empty() ? "none" : join(keys));
  }
  const std::string near = nearest_match(section, sections);
  return fmt::format("no section \"{}\"{}; sections: {}", section, near.empty() ? "" : " (did you mean \"" + near + "\"?)",
                     join(sections));
}

void build_stage(Chain& chain, const std::string& section, const ConfigValue& table, const std::string& file) {
  require_table(table, section);
  const ConfigValue* plugin = table.find("plugin");
  const Kind kind = kind_of_section(section);
  if (!plugin) {
    std::vector<std::string> available;
    for (const auto& file : PluginHost::instance().discover())
      if (file.kind == kind) available.push_back("\"" + file.name + "\"");
    throw InputError(table.where, section, "plugin",
                     fmt::format("missing required key: which {} plugin, one of {}", to_string(kind),
                                 available.empty() ? "(none found)" : join(available)));
  }
  if (plugin->type != ConfigValue::Type::string)
    throw InputError(plugin->where, section, "plugin = " + plugin->as_toml(), "expected a plugin name string");
  const PluginInfo* info = nullptr;
  try {
    info = &PluginHost::instance().load(kind, plugin->string_value);
  } catch (const InputError& error) {
    // A broken library names its file (where); an unknown name has no file, and the subject says the name.
    const bool names_a_file = !error.where().file.empty();
    throw InputError(plugin->where, section, "plugin = " + plugin->as_toml(), names_a_file ? error.what() : error.problem());
  }
  StageSlot slot;
  slot.section = section;
  slot.info = info;
  slot.plugin = info->name;
  ValidationContext context{file, section, info->name};
  slot.params = std::make_unique<Params>(validate_section(info->schema(), table, context));
  slot.stage = info->create(*slot.params);
  chain.stages.push_back(std::move(slot));
}

}  // namespace

Chain load_sensor(const std::string& path, const std::vector<Override>& overrides) {
  ConfigValue root = parse_toml_file(path);
  for (const auto& o : overrides) apply_override(root, o);

  for (const auto& [key, value] : root.members) {
    bool known = false;
    for (const auto& k : top_level_keys) known = known || k == key;
    if (!known) {
      const std::string near = nearest_match(key, top_level_keys);
      throw InputError(value.where, "sensor file", "[" + key + "]",
                       fmt::format("unknown section{}; accepted: {}", near.empty() ? "" : " (did you mean \"" + near + "\"?)",
                                   join(top_level_keys)));
    }
  }

  Chain chain;
  chain.sensor_file = path;
  if (const ConfigValue* sensor = root.find("sensor")) {
    require_table(*sensor, "sensor");
    for (const auto& [key, value] : sensor->members) {
      bool known = false;
      for (const auto& k : sensor_keys) known = known || k == key;
      if (!known) {
        const std::string near = nearest_match(key, sensor_keys);
        throw InputError(value.where, "sensor", key,
                         fmt::format("unknown key{}; accepted keys: {}", near.empty() ? "" : " (did you mean \"" + near + "\"?)",
                                     join(sensor_keys)));
      }
      if (value.type != ConfigValue::Type::string)
        throw InputError(value.where, "sensor", key + " = " + value.as_toml(), "expected a string");
    }
    if (const ConfigValue* name = sensor->find("name")) chain.sensor_name = name->string_value;
    if (const ConfigValue* description = sensor->find("description")) chain.description = description->string_value;
  }
  if (chain.sensor_name.empty()) chain.sensor_name = path;

  // The platform (altitude, ground speed) is optional: space-to-space sensors need none.
  if (const ConfigValue* platform = root.find("platform")) build_stage(chain, "platform", *platform, path);
  for (const auto& section : stage_sections) {
    const ConfigValue* table = root.find(section);
    if (!table)
      throw InputError(SourceLocation{path, 0, 0}, "sensor file", "[" + section + "]",
                       fmt::format("missing section: every sensor has {}", join(stage_sections)));
    build_stage(chain, section, *table, path);
  }
  std::vector<std::string> criteria;
  if (const ConfigValue* table = root.find("criteria")) {
    require_table(*table, "criteria");
    for (const auto& [name, criterion] : table->members) {
      build_stage(chain, "criteria." + name, criterion, path);
      criteria.push_back(name);
    }
  }

  // Solves. Their unknowns are reported as results of the section that owns the parameter.
  std::vector<std::pair<std::string, std::string>> solved_units;  // unknown, display unit
  if (const ConfigValue* solves = root.find("solve")) {
    if (solves->type != ConfigValue::Type::array)
      throw InputError(solves->where, "[[solve]]", "", "expected [[solve]] entries (an array of tables)");
    for (const auto& entry : solves->items) {
      if (entry.type != ConfigValue::Type::table)
        throw InputError(entry.where, "[[solve]]", "", "expected a table of unknown, criterion and bracket, found " + entry.type_name());
      SolveSpec spec;
      spec.where = entry.where;
      for (const auto& [key, value] : entry.members) {
        if (key != "unknown" && key != "criterion" && key != "bracket")
          throw InputError(value.where, "[[solve]]", key, "unknown key; accepted keys: unknown, criterion, bracket");
      }
      const ConfigValue* unknown = entry.find("unknown");
      if (!unknown || unknown->type != ConfigValue::Type::string)
        throw InputError(entry.where, "[[solve]]", "unknown", "missing required key: the parameter to solve for, e.g. \"optics.aperture\"");
      spec.unknown = unknown->string_value;
      try {
        (void)chain.parameter(spec.unknown);
      } catch (const std::logic_error&) {  // no such section or key (std::out_of_range), or not numeric
        throw InputError(unknown->where, "[[solve]]", "unknown = " + unknown->as_toml(),
                         numeric_parameters_text(chain, spec.unknown));
      }
      // criterion = "energy", or several: criterion = ["energy", "matching"] (the value satisfying all binds).
      const ConfigValue* criterion = entry.find("criterion");
      std::vector<const ConfigValue*> names;
      if (criterion && criterion->type == ConfigValue::Type::string) names.push_back(criterion);
      if (criterion && criterion->type == ConfigValue::Type::array)
        for (const auto& item : criterion->items) names.push_back(&item);
      if (!criterion || names.empty())
        throw InputError(criterion ? criterion->where : entry.where, "[[solve]]", "criterion",
                         fmt::format("missing required key: one of the [criteria.*] names, or a list of them: {}",
                                     criteria.empty() ? "none defined" : join(criteria)));
      for (const ConfigValue* name : names) {
        if (name->type != ConfigValue::Type::string || std::find(criteria.begin(), criteria.end(), name->string_value) == criteria.end()) {
          const std::string near = nearest_match(name->string_value, criteria);
          throw InputError(name->where, "[[solve]]", "criterion = " + criterion->as_toml(),
                           fmt::format("no such criterion{}; defined: {}", near.empty() ? "" : " (did you mean \"" + near + "\"?)",
                                       criteria.empty() ? "none" : join(criteria)));
        }
        spec.criteria.push_back(name->string_value);
      }
      const auto dot = spec.unknown.rfind('.');
      const Params::Entry& parameter = chain.slot(spec.unknown.substr(0, dot)).params->entry(spec.unknown.substr(dot + 1));
      const ParamSpec& pspec = *parameter.spec;
      spec.lo = pspec.min, spec.hi = pspec.max;
      if (pspec.min_exclusive) spec.lo = std::nextafter(pspec.min, pspec.max);
      if (pspec.max_exclusive) spec.hi = std::nextafter(pspec.max, pspec.min);
      if (const ConfigValue* bracket = entry.find("bracket")) {
        if (bracket->type != ConfigValue::Type::array || bracket->items.size() != 2)
          throw InputError(bracket->where, "[[solve]]", "bracket = " + bracket->as_toml(), "expected two values, e.g. [\"1 cm\", \"2 m\"]");
        spec.lo = scalar_in(bracket->items[0], pspec.si_unit, "[[solve]]", "bracket");
        spec.hi = scalar_in(bracket->items[1], pspec.si_unit, "[[solve]]", "bracket");
      }
      if (!std::isfinite(spec.lo) || !std::isfinite(spec.hi) || !(spec.hi > spec.lo))
        throw InputError(entry.where, "[[solve]]", spec.unknown,
                         "needs a bracket = [low, high] (the parameter's range is open): e.g. bracket = [\"1 cm\", \"2 m\"]");
      solved_units.emplace_back(spec.unknown, display_unit_of_example(pspec));
      chain.solves.push_back(spec);
    }
  }

  // The spectral phase declares every result; [expected] is checked against those names.
  chain.evaluate();
  // (Solved unknowns become results too.)
  {
    std::vector<ResultId> ids;
    for (const auto& [unknown, display] : solved_units) {
      const auto dot = unknown.rfind('.');
      const ParamSpec& pspec = *chain.slot(unknown.substr(0, dot)).params->entry(unknown.substr(dot + 1)).spec;
      ids.push_back(chain.results().declare(unknown, pspec.si_unit, chain.slot(unknown.substr(0, dot)).info->name,
                                            "[[solve]] root of criteria margin", display));
    }
    chain.resolve_solves(ids);
  }

  if (const ConfigValue* expected = root.find("expected")) {
    require_table(*expected, "expected");
    std::vector<std::string> names;
    for (std::size_t i = 0; i < chain.results().size(); ++i) names.push_back(chain.results().info(i).name);
    for (const auto& [name, spec] : expected->members) {
      const auto id = chain.results().find(name);
      if (!id) {
        const std::string near = nearest_match(name, names);
        throw InputError(spec.where, "[expected]", name,
                         fmt::format("no such result{}; see `radchain run` for the names", near.empty() ? "" : " (did you mean \"" + near + "\"?)"));
      }
      const ResultInfo& info = chain.results().info(*id);
      Expectation e;
      e.result = name;
      e.where = spec.where;
      const std::string context = "[expected]";
      if (spec.type != ConfigValue::Type::table)
        throw InputError(spec.where, context, name,
                         "expected { value = ..., tolerance = ... } (or rel_tolerance), with units where the result has one");
      for (const auto& [key, value] : spec.members)
        if (key != "value" && key != "follows" && key != "tolerance" && key != "rel_tolerance" && key != "source")
          throw InputError(value.where, context, name + "." + key, "unknown key; accepted keys: value, follows, tolerance, rel_tolerance, source");
      const ConfigValue* value = spec.find("value");
      if (!value) throw InputError(spec.where, context, name, "missing required key: value");
      e.value_si = scalar_in(*value, info.si_unit, context, name + ".value", &e.display_unit);
      e.as_written = value->type == ConfigValue::Type::string ? value->string_value : value->as_toml();
      const ConfigValue* tolerance = spec.find("tolerance");
      const ConfigValue* rel = spec.find("rel_tolerance");
      if (!tolerance && !rel) throw InputError(spec.where, context, name, "missing required key: tolerance or rel_tolerance");
      if (tolerance) e.tolerance_si = std::abs(scalar_in(*tolerance, info.si_unit, context, name + ".tolerance"));
      if (rel) {
        if (!rel->is_number()) throw InputError(rel->where, context, name + ".rel_tolerance", "expected a number, e.g. 0.01");
        e.rel_tolerance = std::abs(rel->number());
      }
      if (const ConfigValue* follows = spec.find("follows")) {
        e.follows_si = scalar_in(*follows, info.si_unit, context, name + ".follows");
        e.follows_as_written = follows->type == ConfigValue::Type::string ? follows->string_value : follows->as_toml();
      }
      if (const ConfigValue* source = spec.find("source")) e.source = source->string_value;
      chain.expected.push_back(e);
    }
  }
  return chain;
}

}  // namespace radchain

// Sensor file -> Chain: parse, apply --set overrides, load one plugin per section, validate every key
// against the plugin's schema, then read [[solve]] and [expected].
#include "radchain/chain.hpp"
#include "radchain/distribution.hpp"
#include "radchain/error.hpp"
#include "radchain/plugin_host.hpp"
#include "radchain/sensor_file.hpp"
#include "radchain/units.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace radchain {
namespace {

// Evaluation order. The atmosphere precedes the target: it attenuates the illumination on the way down
// (ground scenes) and hands the target the up-path transmittance for what leaves it.
const std::vector<std::string> stage_sections = {"source", "atmosphere", "target", "optics", "detector"};
// The light comes from these three together; a geometry-only file (GSD, swath, MTF, NIIRS at a given SNR) has
// none of them, and a stage that needs light then refuses, located at its own section.
const std::vector<std::string> light_sections = {"source", "atmosphere", "target"};
const std::vector<std::string> top_level_keys = {"sensor", "platform", "source", "target", "atmosphere", "optics",
                                                 "detector", "criteria", "solve", "expected", "table",
                                                 "uncertainty"};

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
      throw InputError(SourceLocation{"--set " + o.key, 0, 0}, "", "",
                       fmt::format("the sensor file has no section \"{}\"{}", path[i],
                                   did_you_mean(path[i], sections)));
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
    return fmt::format("{} has no numeric parameter \"{}\"{}; its numeric parameters: {}", section, key,
                       did_you_mean(key, keys), keys.empty() ? "none" : join(keys));
  }
  return fmt::format("no section \"{}\"{}; sections: {}", section, did_you_mean(section, sections),
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
  // `informational = true` on any criterion (a key of the file, not of the plugin): its failure is reported, and the
  // run still passes. Taken out before the plugin's schema sees the table.
  const ConfigValue* informational = kind == Kind::criterion ? table.find("informational") : nullptr;
  if (informational) {
    if (informational->type != ConfigValue::Type::boolean)
      throw InputError(informational->where, section + " (plugin \"" + info->name + "\")",
                       "informational = " + informational->as_toml(), "expected true or false");
    slot.informational = informational->boolean_value;
    ConfigValue rest = table;
    std::erase_if(rest.members, [](const auto& member) { return member.first == "informational"; });
    slot.params = std::make_unique<Params>(validate_section(info->schema(), rest, context));
  } else {
    slot.params = std::make_unique<Params>(validate_section(info->schema(), table, context));
  }
  slot.stage = info->create(*slot.params);
  chain.stages.push_back(std::move(slot));
}

}  // namespace

// The sensor file as parsed (a file or text named `path`) -> Chain: what load_sensor and load_sensor_text share.
static Chain build_sensor(ConfigValue root, const std::string& path, const std::vector<Override>& overrides,
                          Solving solving);

namespace {

// How a value reads in a message: as written, or its default (SI).
std::string written_or_default(const Params& params, const std::string& key) {
  const Params::Entry& e = params.entry(key);
  if (e.given && !e.as_written.empty()) return e.as_written;
  const std::string unit = e.spec->type == ParamType::quantity && e.spec->si_unit != "1" ? " " + e.spec->si_unit : "";
  return fmt::format("{:g}{} (its default)", e.number, unit);
}

// "detector (plugin "emva1288") at sensors/x.toml:35:1": where a value is stated (its section's line for a default).
std::string where_of(const Params& params, const std::string& key) {
  const std::string at = params.entry(key).where.str();
  return at.empty() ? params.context() : params.context() + " at " + at;
}

// A quantity two stages read is stated once. A criterion that repeats one of the detector's keys (the pixel pitch
// of the GSD, the TDI stages of the MTF) with another value would compute its geometry or MTF for another camera
// than the radiometry's; a GIQE wavelength outside the detector's band evaluates diffraction where no light is
// counted. Refused with both places.
void check_stated_once(const Chain& chain) {
  const Params *detector = nullptr, *source = nullptr, *atmosphere = nullptr, *target = nullptr;
  for (const StageSlot& slot : chain.stages) {
    if (slot.section == "detector") detector = slot.params.get();
    if (slot.section == "source") source = slot.params.get();
    if (slot.section == "atmosphere") atmosphere = slot.params.get();
    if (slot.section == "target") target = slot.params.get();
  }
  auto gives = [](const Params* params, const std::string& key) {
    if (!params) return false;
    for (const ParamSpec& spec : params->schema())
      if (spec.key == key) return params->given(key);
    return false;
  };
  // The Sun's zenith and the down path's airmass: an airmass_lut atmosphere runs before the target, so a zenith
  // given on the target never reaches it, and its down path took the Sun at the view's airmass (+23 % signal at
  // 60° with a 30° Sun).
  if (atmosphere && atmosphere->plugin() == "airmass_lut" && atmosphere->flag("down_path") &&
      !gives(atmosphere, "sun_airmass") && !gives(source, "solar_zenith"))
    for (const char* key : {"solar_zenith", "latitude"})
      if (gives(target, key))
        target->reject(key, fmt::format("the atmosphere's down path ({}, down_path) runs before the target and took the Sun at "
                                        "the line of sight's airmass: give solar_zenith to the source (plugin "
                                        "\"sun\"), which sets the Sun for the whole chain, or sun_airmass to the "
                                        "atmosphere",
                                        where_of(*atmosphere, "down_path")));
  if (!detector) return;
  auto detector_has = [&](const std::string& key) {
    for (const ParamSpec& spec : detector->schema())
      if (spec.key == key) return detector->has(key);
    return false;
  };
  for (const StageSlot& slot : chain.stages) {
    if (slot.section.rfind("criteria.", 0) != 0) continue;
    const Params& criterion = *slot.params;
    auto criterion_gives = [&](const std::string& key) {
      for (const ParamSpec& spec : criterion.schema())
        if (spec.key == key) return criterion.given(key);
      return false;
    };
    for (const char* key : {"pixel_pitch", "tdi_stages"}) {
      if (!criterion_gives(key) || !detector_has(key)) continue;
      const double mine = criterion.get(key), theirs = detector->get(key);
      if (std::abs(mine - theirs) <= 1e-9 * std::max(std::abs(mine), std::abs(theirs))) continue;
      criterion.reject(key, fmt::format("{} has {} = {}: state it once, in [detector] (this criterion then reads the "
                                        "detector's)",
                                        where_of(*detector, key), key, written_or_default(*detector, key)));
    }
    if (criterion_gives("wavelength") && detector_has("band_min") && detector_has("band_max")) {
      const double wavelength = criterion.get("wavelength");
      const double lo = detector->get("band_min"), hi = detector->get("band_max");
      if (wavelength < lo * (1 - 1e-9) || wavelength > hi * (1 + 1e-9))
        criterion.reject("wavelength", fmt::format("lies outside the detector's band {} ({} has band_min = {}, band_max = "
                                                   "{}): the MTF would be evaluated where no light is counted",
                                                   nm_range(lo, hi), where_of(*detector, "band_min"),
                                                   written_or_default(*detector, "band_min"),
                                                   written_or_default(*detector, "band_max")));
    }
  }
}

}  // namespace
static void read_tables(Chain& chain, const ConfigValue& tables, const std::string& path);

Chain load_sensor(const std::string& path, const std::vector<Override>& overrides, Solving solving) {
  return build_sensor(parse_toml_file(path), path, overrides, solving);
}

Chain load_sensor_text(const std::string& text, const std::string& path, const std::vector<Override>& overrides,
                       Solving solving) {
  return build_sensor(parse_toml_text(text, path), path, overrides, solving);
}

static Chain build_sensor(ConfigValue root, const std::string& path, const std::vector<Override>& overrides,
                          Solving solving) {
  for (const auto& o : overrides) apply_override(root, o);

  for (const auto& [key, value] : root.members) {
    bool known = false;
    for (const auto& k : top_level_keys) known = known || k == key;
    if (!known) {
      throw InputError(value.where, "sensor file", "[" + key + "]",
                       fmt::format("unknown section{}; accepted: {}", did_you_mean(key, top_level_keys),
                                   join(top_level_keys)));
    }
  }

  Chain chain;
  chain.sensor_file = path;
  if (const ConfigValue* sensor = root.find("sensor")) {
    require_table(*sensor, "sensor");
    const Params params = validate_section(sensor_table_schema(), *sensor, ValidationContext{path, "sensor", ""});
    chain.sensor_name = params.text("name");
    chain.description = params.text("description");
  }
  if (chain.sensor_name.empty()) chain.sensor_name = path;

  std::vector<std::pair<std::string, SourceLocation>> section_lines;  // to locate a stage's refusal below
  // The platform (altitude, ground speed) is optional: space-to-space sensors need none.
  if (const ConfigValue* platform = root.find("platform")) {
    build_stage(chain, "platform", *platform, path);
    section_lines.emplace_back("platform", platform->where);
  }
  bool has_light = false;
  for (const auto& section : light_sections) has_light = has_light || root.find(section);
  for (const auto& section : stage_sections) {
    const ConfigValue* table = root.find(section);
    const bool light = std::find(light_sections.begin(), light_sections.end(), section) != light_sections.end();
    if (!table && light && !has_light) continue;
    // A target that shines by itself (point_source with its own SED) needs no [source]; a target that reflects
    // one refuses without it (Context::refuse_form), so leaving it out is never a silent zero.
    if (!table && section == "source") continue;
    if (!table)
      throw InputError(SourceLocation{path, 0, 0}, "sensor file", "[" + section + "]",
                       light ? std::string("missing section: a file with light has atmosphere, target (and source when "
                                           "the target reflects it; a geometry-only file has none of them)")
                             : std::string("missing section: every sensor has optics, detector"));
    build_stage(chain, section, *table, path);
    section_lines.emplace_back(section, table->where);
  }
  std::vector<std::string> criteria;
  if (const ConfigValue* table = root.find("criteria")) {
    require_table(*table, "criteria");
    for (const auto& [name, criterion] : table->members) {
      build_stage(chain, "criteria." + name, criterion, path);
      section_lines.emplace_back("criteria." + name, criterion.where);
      criteria.push_back(name);
    }
  }
  check_stated_once(chain);

  // Solves. Their unknowns are reported as results of the section that owns the parameter.
  std::vector<std::pair<std::string, std::string>> solved_units;  // unknown, display unit
  if (const ConfigValue* solves = root.find("solve")) {
    if (solves->type != ConfigValue::Type::array)
      throw InputError(solves->where, "[[solve]]", "", "expected [[solve]] entries (an array of tables)");
    for (const auto& entry : solves->items) {
      if (entry.type != ConfigValue::Type::table)
        throw InputError(entry.where, "[[solve]]", "", "expected a table of unknown, criterion and bracket, found " + entry.type_name());
      const ValidationContext context{path, "[[solve]]", ""};
      // The bracket's unit is the unknown's: find the unknown first, then validate the entry against its schema.
      const ConfigValue* unknown = entry.find("unknown");
      if (!unknown || unknown->type != ConfigValue::Type::string) {
        const Schema plain = solve_entry_schema();
        const ParamSpec& spec_of_unknown = plain.front();
        throw InputError(unknown ? unknown->where : entry.where, "[[solve]]", unknown ? "unknown = " + unknown->as_toml() : "unknown",
                         fmt::format("{}{} ({})", unknown ? "" : "missing required key: ", spec_of_unknown.expected_text(),
                                     spec_of_unknown.doc));
      }
      SolveSpec spec;
      spec.where = entry.where;
      spec.unknown = unknown->string_value;
      try {
        (void)chain.parameter(spec.unknown);
      } catch (const std::logic_error&) {  // no such section or key (std::out_of_range), or not numeric
        throw InputError(unknown->where, "[[solve]]", "unknown = " + unknown->as_toml(), numeric_parameters_text(chain, spec.unknown));
      }
      const auto dot = spec.unknown.rfind('.');
      const ParamSpec& pspec = *chain.slot(spec.unknown.substr(0, dot)).params->entry(spec.unknown.substr(dot + 1)).spec;
      const Schema schema = solve_entry_schema(&pspec);
      const Params params = validate_section(schema, entry, context);
      // criterion = "energy", or several: criterion = ["energy", "matching"] (the value satisfying all binds).
      const Params::Entry& criterion = params.entry("criterion");
      for (const std::string& name : criterion.texts) {
        if (std::find(criteria.begin(), criteria.end(), name) == criteria.end()) {
          throw InputError(criterion.where, "[[solve]]", "criterion = " + criterion.as_written,
                           fmt::format("no such criterion{}; defined: {}", did_you_mean(name, criteria),
                                       criteria.empty() ? "none" : join(criteria)));
        }
        spec.criteria.push_back(name);
      }
      spec.lo = pspec.min, spec.hi = pspec.max;
      if (pspec.min_exclusive) spec.lo = std::nextafter(pspec.min, pspec.max);
      if (pspec.max_exclusive) spec.hi = std::nextafter(pspec.max, pspec.min);
      if (params.has("bracket")) {
        const Params::Entry& bracket = params.entry("bracket");
        spec.lo = bracket.numbers[0], spec.hi = bracket.numbers[1];
        // The solver evaluates the chain at both ends: each must be a value the parameter accepts (f' = 0 is not).
        for (const double end : bracket.numbers)
          if (!pspec.in_range(end))
            throw InputError(bracket.where, "[[solve]]", "bracket = " + bracket.as_written,
                             fmt::format("an end is out of range for {}: accepted {}", spec.unknown, pspec.range_text()));
      }
      if (!std::isfinite(spec.lo) || !std::isfinite(spec.hi) || !(spec.hi > spec.lo))
        throw InputError(entry.where, "[[solve]]", spec.unknown,
                         "needs a bracket = [low, high] with low < high (the parameter's range is open): e.g. bracket = [\"1 cm\", \"2 m\"]");
      // One unknown, one [[solve]]: a second would overwrite the first's root, which would then be reported as
      // converged at a margin that no longer holds. Several criteria for one unknown go in one entry's list.
      for (const SolveSpec& earlier : chain.solves)
        if (earlier.unknown == spec.unknown)
          throw InputError(unknown->where, "[[solve]]", "unknown = " + unknown->as_toml(),
                           fmt::format("is solved already by the [[solve]] at {}: give one entry, with criterion = [\"{}\", "
                                       "...] to keep the criterion that binds",
                                       earlier.where.str(), earlier.criteria.empty() ? "" : earlier.criteria.front()));
      solved_units.emplace_back(spec.unknown, display_unit_of_example(pspec));
      chain.solves.push_back(spec);
    }
  }

  // The spectral phase declares every result; [expected] is checked against those names. A stage's refusal
  // there (a chain that does not fit, no light) names its section; the file's line of that section locates it.
  try {
    chain.evaluate();
  } catch (const InputError& error) {
    if (!error.where().file.empty()) throw;
    for (const auto& [section, where] : section_lines)
      if (error.context().starts_with(section + " (")) throw error.with_location(where);
    throw;
  }
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
      if (!id) {  // the entry's name, not a key in it: the results of this chain are the accepted names
        throw InputError(spec.where, "[expected]", name,
                         fmt::format("no such result{}; see `radchain run` for the names", did_you_mean(name, names)));
      }
      const ResultInfo& info = chain.results().info(*id);
      if (spec.type != ConfigValue::Type::table)
        throw InputError(spec.where, "[expected]", name,
                         "expected { value = ..., tolerance = ... } (or rel_tolerance), with units where the result has one");
      const Schema schema = expected_entry_schema(info.si_unit);
      const Params params = validate_section(schema, spec, ValidationContext{path, "[expected] " + name, ""});
      if (!params.has("tolerance") && !params.has("rel_tolerance"))
        throw InputError(spec.where, "[expected] " + name, "tolerance", "missing required key: tolerance or rel_tolerance");
      Expectation e;
      e.result = name;
      e.where = spec.where;
      e.value_si = params.get("value");
      const Params::Entry& value = params.entry("value");
      e.as_written = value.as_written.size() >= 2 && value.as_written.front() == '"'
                         ? value.as_written.substr(1, value.as_written.size() - 2) : value.as_written;
      if (units::dimension_of(info.si_unit) != "1") e.display_unit = units::split_quantity(e.as_written).unit;
      e.tolerance_si = params.maybe("tolerance").value_or(0.0);
      e.rel_tolerance = params.maybe("rel_tolerance").value_or(0.0);
      if (params.has("follows")) {
        e.follows_si = params.get("follows");
        const std::string& written = params.entry("follows").as_written;
        e.follows_as_written = written.size() >= 2 && written.front() == '"' ? written.substr(1, written.size() - 2) : written;
      }
      if (params.has("kind")) e.kind = params.text("kind");
      e.source = params.text("source");
      chain.expected.push_back(e);
    }
  }

  if (const ConfigValue* tables = root.find("table")) read_tables(chain, *tables, path);

  // [uncertainty]: "<section>.<key>" = "<distribution>", each parsed now so that a bad one is refused where it is.
  if (const ConfigValue* tolerances = root.find("uncertainty")) {
    require_table(*tolerances, "uncertainty");
    for (const auto& [key, value] : tolerances->members) {
      if (value.type != ConfigValue::Type::string)
        throw InputError(value.where, "[uncertainty]", key + " = " + value.as_toml(),
                         "expected a distribution as a string, e.g. \"normal(0.56, 0.02)\" or \"uniform(9 e-, 11 e-)\"");
      (void)parse_varied_input(chain, key, value.string_value, value.where, "[uncertainty]");
      chain.uncertainties.push_back(UncertaintySpec{key, value.string_value, value.where});
    }
  }
  if (solving == Solving::forward_only) chain.drop_solves();
  return chain;
}

// [[table]] entries: validated after the spectral phase, when every result name is known.
static void read_tables(Chain& chain, const ConfigValue& tables, const std::string& path) {
  constexpr std::size_t max_rows = 1000;  // a table is read by people; a grid belongs to `radchain sweep`
  if (tables.type != ConfigValue::Type::array)
    throw InputError(tables.where, "[[table]]", "", "expected [[table]] entries (an array of tables)");
  std::vector<std::string> names;
  for (std::size_t i = 0; i < chain.results().size(); ++i) names.push_back(chain.results().info(i).name);
  for (const auto& entry : tables.items) {
    if (entry.type != ConfigValue::Type::table)
      throw InputError(entry.where, "[[table]]", "", "expected a table of vary, values and results, found " + entry.type_name());
    // The values' unit is the varied parameter's: find it first, then validate the entry against its schema.
    const ConfigValue* vary = entry.find("vary");
    if (!vary || vary->type != ConfigValue::Type::string) {
      const Schema entry_schema = table_entry_schema();  // kept: a reference into the temporary would dangle
      const ParamSpec& spec_of_vary = entry_schema[1];
      throw InputError(vary ? vary->where : entry.where, "[[table]]", vary ? "vary = " + vary->as_toml() : "vary",
                       fmt::format("{}{} ({})", vary ? "" : "missing required key: ", spec_of_vary.expected_text(), spec_of_vary.doc));
    }
    TableSpec table;
    table.where = entry.where;
    table.vary = vary->string_value;
    try {
      (void)chain.parameter(table.vary);
    } catch (const std::logic_error&) {
      throw InputError(vary->where, "[[table]]", "vary = " + vary->as_toml(), numeric_parameters_text(chain, table.vary));
    }
    for (const SolveSpec& solve : chain.solves)
      if (solve.unknown == table.vary)
        throw InputError(vary->where, "[[table]]", "vary = " + vary->as_toml(),
                         "is a [[solve]] unknown: the solve would overwrite every value of the table");
    const auto dot = table.vary.rfind('.');
    const ParamSpec& pspec = *chain.slot(table.vary.substr(0, dot)).params->entry(table.vary.substr(dot + 1)).spec;
    const Schema schema = table_entry_schema(&pspec);  // outlives params, which point into it
    const Params params = validate_section(schema, entry, ValidationContext{path, "[[table]]", ""});
    const Params::Entry& values = params.entry("values");
    if (values.numbers.size() > max_rows)
      throw InputError(values.where, "[[table]]", "values",
                       fmt::format("{} values: at most {} rows (a grid belongs to `radchain sweep`)", values.numbers.size(), max_rows));
    const ConfigValue& written = *entry.find("values");
    for (std::size_t i = 0; i < values.numbers.size(); ++i) {
      const ConfigValue& item = written.type == ConfigValue::Type::array ? written.items[i] : written;
      const std::string text = item.type == ConfigValue::Type::string ? item.string_value : item.as_toml();
      if (!pspec.in_range(values.numbers[i]))
        throw InputError(item.where, "[[table]]", "values = " + item.as_toml(),
                         fmt::format("out of range for {}: accepted {}", table.vary, pspec.range_text()));
      table.values_si.push_back(values.numbers[i]);
      table.values_written.push_back(text);
    }
    if (params.has("results")) {
      const Params::Entry& results = params.entry("results");
      for (const std::string& name : results.texts) {
        if (!chain.results().find(name)) {
          throw InputError(results.where, "[[table]]", "results = " + results.as_written,
                           fmt::format("no such result \"{}\"{}; see `radchain run` for the names", name,
                                       did_you_mean(name, names)));
        }
        table.results.push_back(name);
      }
    } else {
      for (const SolveSpec& solve : chain.solves) table.results.push_back(solve.unknown);
      if (table.results.empty())
        throw InputError(entry.where, "[[table]]", "results",
                         "missing required key: the file solves nothing, so name the results to tabulate");
    }
    table.name = params.has("name") ? params.text("name") : join(table.results) + " vs " + table.vary;
    chain.tables.push_back(std::move(table));
  }
}

const Schema& sensor_table_schema() {
  static const Schema schema = {
      text("name", "MSX SBV (Pan 2010, Table 1)").described("the instrument's name in reports (default: the file path)"),
      text("description", "space-based visible surveillance camera").described("one line on what it is"),
      text("reference", "Pan et al. 2010, Tables 1-2").described("where its parameters come from"),
      text("notes", "aperture from Table 1").described("anything else a reader should know"),
  };
  return schema;
}

Schema solve_entry_schema(const ParamSpec* unknown) {
  ParamSpec bracket = unknown ? quantity_or_number("bracket", unknown->si_unit, "1") : number("bracket", "1");
  if (unknown && unknown->type == ParamType::quantity) bracket.example = "\"1 " + unknown->si_unit + "\"";
  return {
      text("unknown", "optics.aperture").needed().described("the numeric parameter to solve for: <section>.<key>"),
      text("criterion", "energy").as_list().needed()
          .described("the [criteria.<name>] whose margin is driven to 0, or a list of them (the one that binds is kept)"),
      std::move(bracket).as_pair().finite()
          .described("[low, high] in the unknown's unit (default: the parameter's accepted range)"),
  };
}

Schema table_entry_schema(const ParamSpec* varied) {
  ParamSpec values = varied ? quantity_or_number("values", varied->si_unit, "1") : number("values", "1");
  if (varied && varied->type == ParamType::quantity) values.example = "\"1 " + varied->si_unit + "\"";
  return {
      text("name", "limiting magnitude vs exposure").described("the table's title (default: \"<results> vs <vary>\")"),
      text("vary", "detector.integration_time").needed().described("the numeric parameter that takes each value: <section>.<key>"),
      std::move(values).as_list().needed().finite().described("the values, in the varied parameter's unit (at most 1000)"),
      text("results", "target.magnitude").as_list()
          .described("the results tabulated at each value (default: the [[solve]] unknowns)"),
  };
}

Schema expected_entry_schema(const std::string& si_unit) {
  return {
      quantity_or_number("value", si_unit, "832").needed().finite().described("the published value, in the result's unit"),
      quantity_or_number("follows", si_unit, "833.1").finite()
          .described("an erratum: what the source's own formula and inputs give (checked instead of value; docs/ explain)"),
      quantity_or_number("tolerance", si_unit, "1").at_least(0).finite().described("absolute tolerance"),
      number("rel_tolerance", "0.01").at_least(0).finite().described("relative tolerance (either or both)"),
      choice("kind", {"published", "peer", "paper", "internal"})
          .described("what the reference is: the instrument's published figure, a peer tool's computation, a paper's "
                     "worked example, or radchain against itself"),
      text("source", "Kolobrodov 1996, p. 4").described("where the value is published (document, table or page)"),
  };
}

}  // namespace radchain

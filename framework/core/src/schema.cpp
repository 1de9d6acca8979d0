#include "radchain/schema.hpp"

#include "radchain/error.hpp"
#include "radchain/spectrum_csv.hpp"
#include "radchain/units.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <sstream>
#include <stdexcept>

namespace radchain {
namespace fs = std::filesystem;

ParamSpec quantity(std::string key, std::string si_unit, std::string example) {
  ParamSpec p;
  // Stored as written in a sensor file (a TOML string), like the other kinds' examples: "\"15 cm\"".
  p.key = std::move(key), p.type = ParamType::quantity, p.si_unit = std::move(si_unit);
  p.example = "\"" + example + "\"";
  return p;
}
ParamSpec number(std::string key, std::string example) {
  ParamSpec p;
  p.key = std::move(key), p.type = ParamType::number, p.si_unit = "1", p.example = std::move(example);
  return p;
}
ParamSpec integer(std::string key, std::string example) {
  ParamSpec p;
  p.key = std::move(key), p.type = ParamType::integer, p.si_unit = "1", p.example = std::move(example);
  return p;
}
ParamSpec text(std::string key, std::string example) {
  ParamSpec p;
  p.key = std::move(key), p.type = ParamType::text, p.example = "\"" + example + "\"";
  return p;
}
ParamSpec choice(std::string key, std::vector<std::string> choices) {
  ParamSpec p;
  p.key = std::move(key), p.type = ParamType::choice, p.example = "\"" + choices.front() + "\"";
  p.choices = std::move(choices);
  return p;
}
ParamSpec flag(std::string key) {
  ParamSpec p;
  p.key = std::move(key), p.type = ParamType::flag, p.example = "false";
  return p;
}
ParamSpec spectrum_file(std::string key, std::string si_unit, std::string example) {
  ParamSpec p;
  p.key = std::move(key), p.type = ParamType::spectrum, p.si_unit = std::move(si_unit);
  p.example = "\"" + example + "\"";
  p.spectral = true;
  return p;
}

ParamSpec quantity_or_number(std::string key, const std::string& si_unit, std::string example_number) {
  if (units::dimension_of(si_unit) == "1") return number(std::move(key), std::move(example_number));
  return quantity(std::move(key), si_unit, example_number + " " + si_unit);
}

static std::string number_text(double v) { return fmt::format("{:g}", v); }

std::string ParamSpec::range_text() const {
  if (type == ParamType::choice) return "one of " + join(choices);
  const std::string unit = (type == ParamType::quantity && si_unit != "1") ? " " + si_unit : "";
  const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
  if (finite_only && !has_min && !has_max) return "a finite value";
  const std::string finite_note = finite_only ? ", finite" : "";
  if (has_min && has_max)
    return fmt::format("in {}{}, {}{}{}", min_exclusive ? "(" : "[", number_text(min), number_text(max),
                       max_exclusive ? ")" : "]", unit);
  if (has_min) return fmt::format("{} {}{}{}", min_exclusive ? ">" : ">=", number_text(min), unit, finite_note);
  if (has_max) return fmt::format("{} {}{}{}", max_exclusive ? "<" : "<=", number_text(max), unit, finite_note);
  return {};
}

std::string ParamSpec::expected_text() const {
  switch (type) {
    case ParamType::quantity: return fmt::format("expected {}, e.g. {}", units::dimension_name(si_unit), example);
    case ParamType::number: return fmt::format("expected a number, e.g. {}", example);
    case ParamType::integer: return fmt::format("expected an integer, e.g. {}", example);
    case ParamType::text: return fmt::format("expected a string, e.g. {}", example);
    case ParamType::choice: return "expected one of " + join(choices);
    case ParamType::flag: return "expected true or false";
    case ParamType::spectrum: return fmt::format("expected the name of a spectrum CSV file, e.g. {}", example);
  }
  return {};
}

bool ParamSpec::in_range(double v) const {
  if (std::isnan(v) || (finite_only && !std::isfinite(v))) return false;
  if (min_exclusive ? !(v > min) : !(v >= min)) return false;
  if (max_exclusive ? !(v < max) : !(v <= max)) return false;
  return true;
}

Params::Params(std::string section, std::string plugin, const Schema* schema)
    : section_(std::move(section)), plugin_(std::move(plugin)), schema_(schema) {
  entries_.resize(schema_->size());
  key_tags_.reserve(schema_->size());
  for (std::size_t i = 0; i < schema_->size(); ++i) entries_[i].spec = &(*schema_)[i], key_tags_.emplace_back((*schema_)[i].key);
}

Params::KeyTag::KeyTag(std::string_view key) : size(key.size()) {
  const std::size_t n = std::min<std::size_t>(key.size(), 8);
  std::memcpy(&head, key.data(), n);
  std::memcpy(&tail, key.data() + key.size() - n, n);
}

std::string Params::context() const {
  return plugin_.empty() ? section_ : fmt::format("{} (plugin \"{}\")", section_, plugin_);
}

const Params::Entry& Params::entry(std::string_view key) const {
  const KeyTag tag(key);
  for (std::size_t i = 0; i < key_tags_.size(); ++i)
    if (key_tags_[i] == tag && (key.size() <= 16 || entries_[i].spec->key == key)) return entries_[i];
  throw std::logic_error("plugin \"" + plugin_ + "\" asked for \"" + std::string(key) + "\", which is not in its schema");
}
Params::Entry& Params::entry(std::string_view key) {
  return const_cast<Entry&>(static_cast<const Params&>(*this).entry(key));
}

bool Params::has(std::string_view key) const { return entry(key).present; }
bool Params::given(std::string_view key) const { return entry(key).given; }

double Params::get(std::string_view key) const {
  const Entry& e = entry(key);
  if (!e.present) throw std::logic_error("parameter \"" + std::string(key) + "\" of \"" + plugin_ + "\" has no value");
  return e.number;
}
std::optional<double> Params::maybe(std::string_view key) const {
  const Entry& e = entry(key);
  return e.present ? std::optional<double>(e.number) : std::nullopt;
}
const double* Params::handle(std::string_view key) const { return &entry(key).number; }
std::int64_t Params::integer(std::string_view key) const { return static_cast<std::int64_t>(get(key)); }
const std::string& Params::text(std::string_view key) const { return entry(key).text; }
bool Params::flag(std::string_view key) const { return entry(key).flag; }
const Spectrum& Params::spectrum(std::string_view key) const {
  const Entry& e = entry(key);
  if (!e.spectrum) throw std::logic_error("parameter \"" + std::string(key) + "\" of \"" + plugin_ + "\" has no spectrum");
  return *e.spectrum;
}

void Params::reject(const std::string& key, const std::string& text) const { throw problem(key, text); }

InputError Params::problem(const std::string& key, const std::string& problem) const {
  const Entry& e = entry(key);
  // A value a sweep or a solve set has no text as written: its number then, in SI.
  const bool numeric = e.spec->type == ParamType::quantity || e.spec->type == ParamType::number || e.spec->type == ParamType::integer;
  const std::string unit = e.spec->type == ParamType::quantity && e.spec->si_unit != "1" ? " " + e.spec->si_unit : "";
  const std::string value = !e.as_written.empty() || !numeric ? e.as_written : fmt::format("{:g}{}", e.number, unit);
  return InputError(e.where, context(), key + " = " + value, problem);
}

std::optional<std::string> resolve_data_file(const std::string& name, const std::string& sensor_file) {
  const fs::path given(name);
  std::vector<fs::path> candidates;
  if (given.is_absolute()) {
    candidates.push_back(given);
  } else {
    candidates.push_back(fs::path(sensor_file).parent_path() / given);
    if (const char* env = std::getenv("RADCHAIN_DATA_PATH")) {
      std::stringstream dirs(env);
      std::string dir;
      while (std::getline(dirs, dir, ':'))
        if (!dir.empty()) candidates.push_back(fs::path(dir) / given);
    }
#ifdef RADCHAIN_SOURCE_SPECTRA_DIR
    candidates.push_back(fs::path(RADCHAIN_SOURCE_SPECTRA_DIR) / given);
#endif
#ifdef RADCHAIN_INSTALL_SPECTRA_DIR
    candidates.push_back(fs::path(RADCHAIN_INSTALL_SPECTRA_DIR) / given);
#endif
  }
  for (const auto& candidate : candidates) {
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec)) return candidate.lexically_normal().string();
  }
  return std::nullopt;
}

namespace {

// One value of a key: the whole value of a scalar key, one item of a list or pair.
void assign_one(Params& params, Params::Entry& entry, const ConfigValue& value, const ValidationContext& context,
                const std::string& subject) {
  const ParamSpec& spec = *entry.spec;
  auto fail = [&](const std::string& problem) {
    return InputError(value.where, params.context(), subject, problem);
  };
  auto check_range = [&](double v) {
    if (!spec.in_range(v)) throw fail("out of range: accepted " + spec.range_text());
  };
  switch (spec.type) {
    case ParamType::quantity: {
      if (value.is_number())
        throw fail(fmt::format("a bare number has no unit: {}", spec.expected_text()));
      if (value.type != ConfigValue::Type::string) throw fail(spec.expected_text());
      units::ParsedQuantity q;
      try {
        q = units::split_quantity(value.string_value);
      } catch (const std::invalid_argument&) {
        throw fail("does not start with a number: " + spec.expected_text());
      }
      if (q.unit.empty() && units::dimension_of(spec.si_unit) != "1")
        throw fail(fmt::format("no unit: {}", spec.expected_text()));
      double factor = 1.0;
      try {
        factor = units::conversion(q.unit.empty() ? "1" : q.unit, spec.si_unit).factor;
      } catch (const std::invalid_argument&) {
        throw fail(fmt::format("unknown unit \"{}\": {}", q.unit, spec.expected_text()));
      } catch (const std::domain_error&) {
        const auto reciprocal = units::reciprocal_conversion(q.unit, spec.si_unit);
        if (!reciprocal) throw fail(spec.expected_text());
        const double given = units::to_si(q, *reciprocal);
        if (!(given > 0) || !std::isfinite(1.0 / given))
          throw fail(fmt::format("\"{}\" has no finite reciprocal: {}", value.string_value, spec.expected_text()));
        entry.number = 1.0 / given;  // e-/DN → DN/e-
        check_range(entry.number);
        break;
      }
      entry.number = units::to_si(q, factor);
      check_range(entry.number);
      break;
    }
    case ParamType::number:
      if (!value.is_number()) throw fail(spec.expected_text());
      entry.number = value.number();
      check_range(entry.number);
      break;
    case ParamType::integer:
      if (value.type != ConfigValue::Type::integer) throw fail(spec.expected_text());
      entry.number = static_cast<double>(value.integer_value);
      check_range(entry.number);
      break;
    case ParamType::text:
      if (value.type != ConfigValue::Type::string) throw fail(spec.expected_text());
      entry.text = value.string_value;
      break;
    case ParamType::choice: {
      if (value.type != ConfigValue::Type::string) throw fail(spec.expected_text());
      bool ok = false;
      for (const auto& c : spec.choices) ok = ok || c == value.string_value;
      if (!ok) {
        throw fail(spec.expected_text() + did_you_mean(value.string_value, spec.choices));
      }
      entry.text = value.string_value;
      break;
    }
    case ParamType::flag:
      if (value.type != ConfigValue::Type::boolean) throw fail(spec.expected_text());
      entry.flag = value.boolean_value;
      break;
    case ParamType::spectrum: {
      if (value.type != ConfigValue::Type::string) throw fail(spec.expected_text());
      const auto path = resolve_data_file(value.string_value, context.sensor_file);
      if (!path)  // in a list, which item
        throw fail((spec.shape == ParamShape::scalar ? "" : "\"" + value.string_value + "\": ") +
                   "file not found (looked beside the sensor file, in RADCHAIN_DATA_PATH and in spectra/)");
      try {
        entry.spectrum = std::make_shared<const Spectrum>(cached_spectrum_csv(*path, spec.si_unit).spectrum);
      } catch (const InputError& error) {
        throw fail(error.what());
      }
      entry.text = *path;
      break;
    }
  }
}

}  // namespace

void assign_param(Params& params, Params::Entry& entry, const ConfigValue& value, const ValidationContext& context) {
  const ParamSpec& spec = *entry.spec;
  entry.where = value.where;
  entry.as_written = value.as_toml();
  const std::string subject = spec.key + " = " + entry.as_written;
  if (spec.shape == ParamShape::scalar) {
    assign_one(params, entry, value, context, subject);
  } else {
    const bool array = value.type == ConfigValue::Type::array;
    if (spec.shape == ParamShape::pair && (!array || value.items.size() != 2))
      throw InputError(value.where, params.context(), subject, "expected two values: [low, high]");
    if (array && value.items.empty())
      throw InputError(value.where, params.context(), subject, fmt::format("expected one or more values, e.g. [{}]", spec.example));
    entry.numbers.clear(), entry.texts.clear();
    std::shared_ptr<const Spectrum> product;  // a list of spectra: their product (components of one stage)
    for (const ConfigValue& item : array ? value.items : std::vector<ConfigValue>{value}) {
      assign_one(params, entry, item, context, subject);
      entry.numbers.push_back(entry.number);
      entry.texts.push_back(entry.text);
      if (spec.type == ParamType::spectrum) {
        // Tables that share no wavelength multiply to nothing: a wrong file in the list, the user's to fix.
        if (product && !(std::min(product->max_wavelength_m(), entry.spectrum->max_wavelength_m()) >
                         std::max(product->min_wavelength_m(), entry.spectrum->min_wavelength_m())))
          throw InputError(item.where, params.context(), subject,
                           fmt::format("{} ({:.5g}-{:.5g} nm) shares no wavelength with the tables before it in the list "
                                       "({:.5g}-{:.5g} nm): their product is zero everywhere",
                                       item.as_toml(), 1e9 * entry.spectrum->min_wavelength_m(),
                                       1e9 * entry.spectrum->max_wavelength_m(), 1e9 * product->min_wavelength_m(),
                                       1e9 * product->max_wavelength_m()));
        product = product ? std::make_shared<const Spectrum>(product->product(*entry.spectrum, spec.si_unit)) : entry.spectrum;
      }
    }
    if (product) entry.spectrum = product;
  }
  entry.present = true;
}

Params validate_section(const Schema& schema, const ConfigValue& table, const ValidationContext& context) {
  Params params(context.section, context.plugin, &schema);
  std::vector<std::string> accepted;
  for (const auto& spec : schema) accepted.push_back(spec.key);
  for (const auto& [key, value] : table.members) {
    if (key == "plugin" && !context.plugin.empty()) continue;  // a stage's plugin key was read by the host
    bool known = false;
    for (auto& entry : params.entries()) {
      const ParamSpec& spec = *entry.spec;
      const bool former = spec.key != key && std::find(spec.former_keys.begin(), spec.former_keys.end(), key) != spec.former_keys.end();
      if (spec.key != key && !former) continue;
      known = true;
      // The same parameter under its new and its former name: a --set of one overrides the file's other; both in
      // the file (or both set) is refused.
      const ConfigValue* other = nullptr;
      for (const auto& name : former ? std::vector<std::string>{spec.key} : spec.former_keys)
        if (const ConfigValue* v = table.find(name)) other = v;
      if (other) {
        auto is_set = [](const ConfigValue& v) { return v.where.file.rfind("--set ", 0) == 0; };
        if (is_set(*other) && !is_set(value)) continue;  // the --set one is assigned when its turn comes
        if (is_set(value) == is_set(*other))
          throw InputError(value.where, params.context(), key,
                           former ? fmt::format("the former name of {}, which is given too: keep {}", spec.key, spec.key)
                                  : fmt::format("given under its former name too: keep {}", spec.key));
      }
      if (former)
        params.note_renamed(InputError(value.where, params.context(), key,
                                       fmt::format("renamed {} (one name in every plugin); the old name is accepted "
                                                   "for now", spec.key)).what());
      assign_param(params, entry, value, context);
      entry.given = true;
    }
    if (!known) {
      throw InputError(value.where, params.context(), key,
                       fmt::format("unknown key{}; accepted keys: {}", did_you_mean(key, accepted),
                                   accepted.empty() ? "(none)" : join(accepted)));
    }
  }
  for (auto& entry : params.entries()) {
    if (entry.present) continue;
    const ParamSpec& spec = *entry.spec;
    if (spec.required)
      throw InputError(table.where, params.context(), spec.key,
                       fmt::format("missing required key: {} ({})", spec.expected_text(), spec.doc));
    if (spec.default_value) {
      // A default is a schema constant: parsed by toml++ once per thread, not once per file (a seventh of a
      // catalogue's time went there). Bounded by the plugins' schemas.
      thread_local std::map<std::string, ConfigValue> parsed_defaults;
      auto parsed = parsed_defaults.find(*spec.default_value);
      if (parsed == parsed_defaults.end())
        parsed = parsed_defaults.emplace(*spec.default_value, parse_toml_value(*spec.default_value, "default")).first;
      ConfigValue fallback = parsed->second;
      fallback.where = table.where;
      assign_param(params, entry, fallback, context);
    }
  }
  return params;
}

}  // namespace radchain

#pragma once
// A plugin's parameter schema: key, kind, SI unit, default or required, range or allowed values, one-line
// doc. It drives validation, the error texts, `radchain describe` and the generated reference page.
#include "radchain/config.hpp"
#include "radchain/error.hpp"
#include "radchain/spectrum.hpp"

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace radchain {

enum class ParamType {
  quantity,  // dimensional number with a unit: "15 cm"; a bare number is refused
  number,    // dimensionless real: 0.56
  integer,   // dimensionless integer: 12
  text,      // free string
  choice,    // one of `choices`
  flag,      // true / false
  spectrum,  // a CSV spectrum file (see spectrum_csv.hpp), loaded and unit-checked during validation
};

// How a parameter acts downstream, declared by the stage that owns it, for the closed-form inversion of a
// [[solve]] (solver.cpp): the stage's results that change with it are power laws of x (power_law: D², f'⁻¹, t) or
// of the flux ratio 10^(−0.4 x) (magnitude). none: only the bracketing root-finder solves for it.
enum class Scaling { none, power_law, magnitude };

// How many values a key takes: one (every plugin key), a list of one or more (criterion = ["energy", "matching"]
// also accepts a single string), or exactly two (bracket = ["1 cm", "2 m"]).
enum class ParamShape { scalar, list, pair };

struct ParamSpec {
  std::string key;
  ParamType type = ParamType::number;
  ParamShape shape = ParamShape::scalar;
  std::string si_unit;  // quantity: SI unit of the stored value ("m"); spectrum: unit of its values ("1")
  std::string example;  // a valid value as TOML text in a sensor file, quotes included: "\"15 cm\"", 0.27
  std::optional<std::string> default_value;  // the value without TOML quotes ("0 e-/s"); none + !required = optional
  bool required = false;
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false, max_exclusive = false;
  std::vector<std::string> choices;
  std::string doc;
  bool spectral = false;  // changing it re-runs the chain's spectral phase
  bool finite_only = false;  // ±inf refused (NaN always is)
  Scaling scaling = Scaling::none;
  // Names the key had before one vocabulary was agreed across plugins: accepted, with a located warning.
  std::vector<std::string> former_keys;

  // Fluent setters, so a schema reads like a table.
  ParamSpec&& fallback(std::string value) && { default_value = std::move(value); return std::move(*this); }
  ParamSpec&& needed() && { required = true; return std::move(*this); }
  ParamSpec&& at_least(double v) && { min = v; min_exclusive = false; return std::move(*this); }
  ParamSpec&& above(double v) && { min = v; min_exclusive = true; return std::move(*this); }
  ParamSpec&& at_most(double v) && { max = v; max_exclusive = false; return std::move(*this); }
  ParamSpec&& below(double v) && { max = v; max_exclusive = true; return std::move(*this); }
  ParamSpec&& described(std::string text) && { doc = std::move(text); return std::move(*this); }
  ParamSpec&& affects_spectrum() && { spectral = true; return std::move(*this); }
  ParamSpec&& as_list() && { shape = ParamShape::list; return std::move(*this); }
  ParamSpec&& as_pair() && { shape = ParamShape::pair; return std::move(*this); }
  // Refuses ±infinity (and NaN): a tolerance of inf would let a check pass anything.
  ParamSpec&& finite() && { finite_only = true; return std::move(*this); }
  ParamSpec&& scales(Scaling how) && { scaling = how; return std::move(*this); }
  ParamSpec&& formerly(std::string key) && { former_keys.push_back(std::move(key)); return std::move(*this); }

  std::string range_text() const;     // "> 0 m", "in [0, 1]", "one of e490, wehrli"
  std::string expected_text() const;  // what the error line says is expected
  bool in_range(double si_value) const;
};

ParamSpec quantity(std::string key, std::string si_unit, std::string example);
ParamSpec number(std::string key, std::string example);
ParamSpec integer(std::string key, std::string example);
ParamSpec text(std::string key, std::string example);
ParamSpec choice(std::string key, std::vector<std::string> choices);
ParamSpec flag(std::string key);
ParamSpec spectrum_file(std::string key, std::string si_unit, std::string example);

using Schema = std::vector<ParamSpec>;

// Validated values of one section, in SI. Scalars live at stable addresses (handle()), so a solver or a
// sweep can change one value and re-evaluate without rebuilding the plugin.
class Params {
 public:
  struct Entry {
    const ParamSpec* spec = nullptr;
    bool given = false;         // written in the file (or --set), not defaulted
    bool present = false;       // given or defaulted
    double number = 0.0;        // quantity / number / integer, SI
    std::string text;           // text / choice / spectrum path as written
    std::vector<double> numbers;      // list / pair shapes of numbers and quantities (SI)
    std::vector<std::string> texts;   // list / pair shapes of texts and choices
    bool flag = false;
    std::shared_ptr<const Spectrum> spectrum;
    SourceLocation where;
    std::string as_written;     // the TOML text, for messages
  };

  Params(std::string section, std::string plugin, const Schema* schema);

  const std::string& section() const { return section_; }
  const std::string& plugin() const { return plugin_; }
  std::string context() const;  // `optics (plugin "telescope")`

  bool has(std::string_view key) const;    // given or defaulted
  bool given(std::string_view key) const;  // written in the file
  double get(std::string_view key) const;  // quantity / number / integer (SI)
  std::optional<double> maybe(std::string_view key) const;
  const double* handle(std::string_view key) const;
  std::int64_t integer(std::string_view key) const;
  const std::string& text(std::string_view key) const;
  bool flag(std::string_view key) const;
  const Spectrum& spectrum(std::string_view key) const;
  const Entry& entry(std::string_view key) const;
  Entry& entry(std::string_view key);
  const Schema& schema() const { return *schema_; }

  // A plugin's own consistency rule failed for `key` (e.g. element size larger than pitch).
  [[noreturn]] void reject(const std::string& key, const std::string& problem) const;
  // The same located line, not thrown: for a warning (Context::warn).
  InputError problem(const std::string& key, const std::string& problem) const;

  std::vector<Entry>& entries() { return entries_; }
  const std::vector<Entry>& entries() const { return entries_; }

  // Keys written under a former name (accepted): a located warning line each, which the run reports.
  const std::vector<std::string>& renamed() const { return renamed_; }
  void note_renamed(std::string line) { renamed_.push_back(std::move(line)); }

 private:
  std::string section_, plugin_;
  std::vector<std::string> renamed_;
  const Schema* schema_;
  std::vector<Entry> entries_;  // one per schema entry, never resized after construction
  // entries_[i].spec->key as its size and first and last 8 bytes, side by side: a look-up by key (a stage's prepare
  // makes a dozen) compares words in a few cache lines instead of following each entry's spec pointer to its text.
  // A key of up to 16 bytes is its tag; a longer one is compared whole once its tag matches.
  struct KeyTag {
    std::uint64_t size = 0, head = 0, tail = 0;
    explicit KeyTag(std::string_view key);
    bool operator==(const KeyTag&) const = default;
  };
  std::vector<KeyTag> key_tags_;
};

// Everything validation needs besides the section table.
struct ValidationContext {
  std::string sensor_file;            // for messages and relative spectrum paths
  std::string section;                // "optics", "criteria.detection"; "[[solve]]", "[expected]" for the file's own tables
  std::string plugin;                 // "telescope"; "" for the file's own tables (the section alone names them)
};

// A quantity for a dimensional SI unit, else a plain number: the schema entry for a value whose unit is known only
// when the file is read (a [[solve]] bracket takes the unit of its unknown, an [expected] value that of its result).
ParamSpec quantity_or_number(std::string key, const std::string& si_unit, std::string example_number);

// Validates one section table against a schema (the `plugin` key itself is skipped). Throws InputError.
Params validate_section(const Schema& schema, const ConfigValue& table, const ValidationContext& context);

// Sets one entry from a TOML value (used by validation and by --set / sweeps). Throws InputError.
void assign_param(Params& params, Params::Entry& entry, const ConfigValue& value, const ValidationContext& context);

// Finds a data file: as given (absolute, or relative to the sensor file's folder), then in
// RADCHAIN_DATA_PATH (colon-separated), the source tree's spectra/ and the installed share/radchain/spectra.
std::optional<std::string> resolve_data_file(const std::string& name, const std::string& sensor_file);

}  // namespace radchain

#pragma once
// The framework-owned view of a TOML document. toml++ stays private to config.cpp: plugins and the rest
// of the framework see only ConfigValue, with the source location of every value.
#include "radchain/error.hpp"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace radchain {

struct ConfigValue {
  enum class Type { string, integer, floating, boolean, array, table, other };
  Type type = Type::table;
  std::string string_value;
  std::int64_t integer_value = 0;
  double floating_value = 0.0;
  bool boolean_value = false;
  std::vector<ConfigValue> items;                             // array
  std::vector<std::pair<std::string, ConfigValue>> members;  // table, in file order
  SourceLocation where;

  // Defined after the class: clang with libstdc++ 12 otherwise checks pair<string, ConfigValue> for completeness
  // while ConfigValue is still incomplete, and refuses the implicit constructor.
  ConfigValue();
  bool is_number() const { return type == Type::integer || type == Type::floating; }
  double number() const { return type == Type::integer ? static_cast<double>(integer_value) : floating_value; }
  const ConfigValue* find(const std::string& key) const;
  ConfigValue* find(const std::string& key);
  // How the value reads in TOML: "\"15 kg\"", 15, true, [..], {..}
  std::string as_toml() const;
  std::string type_name() const;  // "a string", "a number", ...
};
inline ConfigValue::ConfigValue() = default;

// Parses a TOML file; a syntax error becomes InputError("file:line:col: TOML syntax: ...").
ConfigValue parse_toml_file(const std::string& path);
ConfigValue parse_toml_text(const std::string& text, const std::string& name_for_messages);
// One TOML value written on a command line (`--set optics.aperture="20 cm"`); bare words that are not
// TOML (20 cm) are taken as strings so shells need no extra quoting.
ConfigValue parse_toml_value(const std::string& text, const std::string& name_for_messages);

}  // namespace radchain

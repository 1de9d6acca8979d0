#pragma once
// What `radchain describe NAME` and radchain.describe(NAME) show, as data: a plugin (its keys, the results it
// publishes and needs, an example section), a kind (its plugins), a sensor file's own table (sensor, solve,
// expected, table) or an imaging command's options (render, validate). One model: the command line prints it,
// Python turns it into dicts, so the two cannot drift apart.
#include <optional>
#include <string>
#include <vector>

namespace radchain {

struct ParamSpec;

// One key of a schema.
struct KeyDescription {
  std::string key;
  std::string type;     // quantity, number, integer, string, choice, boolean, spectrum
  std::string si_unit;  // quantities and spectra
  std::string shape;    // scalar, list (one value or a list), pair ([low, high])
  bool required = false;
  std::optional<std::string> default_value;
  std::string example;                // a value as a sensor file writes it
  std::string doc;
  std::string accepted;               // the accepted range or choices, as the validation message says them
  std::vector<std::string> formerly;  // former names still accepted
  bool spectral = false;              // changing it re-runs the chain's spectral phase
};

// A result name of the vocabulary, as a plugin publishes or needs it.
struct TermDescription {
  std::string name;  // per-criterion terms as "criteria.<name>.margin"
  std::string unit;
  std::string meaning;
  bool optional = false;  // needs: read only if an earlier stage publishes it
};

struct PluginSummary {
  std::string name, summary, file;
};

struct Description {
  enum class What { plugin, kind, table, command };
  What what = What::plugin;
  std::string name;   // the plugin's, the kind's, the table's or the command's
  std::string title;  // one line: what it is ("[[solve]] — a parameter the chain solves for, …")
  std::vector<KeyDescription> keys;
  std::string example;  // a TOML example (plugins and tables; commands have none)

  // plugins
  std::string kind, summary, reference, file, framework_version;
  int abi_version = 0;
  std::vector<TermDescription> publishes, needs;

  // kinds
  std::string section;  // the sensor file's section ("criteria.<name>")
  std::vector<PluginSummary> plugins;
};

const char* to_string(Description::What what);  // "plugin", "kind", "table", "command"

KeyDescription describe_key(const ParamSpec& spec);

// NAME: a plugin's name or file path, a kind or its section ("criterion", "criteria"), a table (sensor, solve,
// expected, table) or a command (render, validate). Throws InputError naming the nearest of them.
Description describe(const std::string& name);

}  // namespace radchain

// CLI11 options made from a command's option schema (radchain/command_options.hpp).
#include "option_schema.hpp"

#include <CLI/CLI.hpp>

namespace radchain::cli {

void add_schema_options(CLI::App* command, const Schema& schema, OptionValues& values) {
  for (const ParamSpec& spec : schema) {
    std::string help = spec.doc;
    if (spec.type == ParamType::quantity) help += " [" + spec.si_unit + "], e.g. " + spec.example;
    if (spec.type == ParamType::choice) help += ": " + join(spec.choices);
    if (spec.default_value && spec.type != ParamType::flag) help += " (default " + *spec.default_value + ")";
    const std::string key = spec.key;
    if (spec.type == ParamType::flag)
      command->add_flag_callback(key, [&values, key] { values.given.emplace_back(key, "true"); }, help);
    else
      command->add_option_function<std::string>(key, [&values, key](const std::string& text) { values.given.emplace_back(key, text); },
                                                help);
  }
}

}  // namespace radchain::cli

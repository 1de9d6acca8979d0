#pragma once
// The values that render and validate take on the command line (quantities with units, counts with limits, fixed
// choices) as Schemas like a plugin's, declared once: CLI11 options are made from them, the same validation as a
// sensor file checks them (units, ranges, "did you mean"), and `radchain describe render|validate` prints them.
// File paths (--out, --png, --scene), --target, --seed and --set stay plain CLI11 options.
#include "radchain/schema.hpp"

#include <string>
#include <utility>
#include <vector>

namespace CLI {
class App;
}

namespace radchain::cli {

// The schema options as typed, in command-line order: key ("--width") → text ("640"). Flags record "true".
struct OptionValues {
  std::vector<std::pair<std::string, std::string>> given;
};

const Schema& render_option_schema();
const Schema& validate_option_schema();

// One CLI11 option per schema entry; its help is the entry's doc, unit and default.
void add_schema_options(CLI::App* command, const Schema& schema, OptionValues& values);

// The options validated (defaults filled in, SI units) for `command` ("radchain render"). Throws InputError:
// "radchain render: --width = 0: out of range: accepted in [1, 16384]".
Params validated_options(const Schema& schema, const OptionValues& values, const std::string& command);

}  // namespace radchain::cli

#pragma once
// The command line's side of a command's option schema (radchain/command_options.hpp): one CLI11 option per entry,
// whose text is collected for validated_options().
#include "radchain/command_options.hpp"

namespace CLI {
class App;
}

namespace radchain::cli {

// One CLI11 option per schema entry; its help is the entry's doc, unit and default.
void add_schema_options(CLI::App* command, const Schema& schema, OptionValues& values);

}  // namespace radchain::cli

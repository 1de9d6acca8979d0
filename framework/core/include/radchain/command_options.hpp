#pragma once
// The values that `radchain render` and `radchain validate` (and radchain.render in Python) take besides the sensor
// file: quantities with units, counts with limits, fixed choices. Declared once as Schemas like a plugin's: the
// command line makes its options from them, Python passes keyword arguments through them, both are validated the
// way a sensor file is (units, ranges, "did you mean"), and describe lists them. File paths, targets, seeds and
// overrides stay plain arguments of each front end.
#include "radchain/schema.hpp"

#include <string>
#include <utility>
#include <vector>

namespace radchain {

// The options as typed, in the order given: key ("--width") → text ("640"). Flags record "true".
struct OptionValues {
  std::vector<std::pair<std::string, std::string>> given;
};

const Schema& render_option_schema();
const Schema& validate_option_schema();

// The options validated (defaults filled in, SI units) for `command` ("radchain render"), the last of a repeated key
// winning and list options (--no-noise shot,dark) collected. Throws InputError:
// "radchain render: --width = 0: out of range: accepted in [1, 16384]".
Params validated_options(const Schema& schema, const OptionValues& values, const std::string& command);

}  // namespace radchain

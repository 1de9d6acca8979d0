#pragma once
// `--set section.key=value` and loading the sensor a command names: shared by the executable and the imaging
// module (both link radchain_cli_support).
#include "options.hpp"

#include "radchain/chain.hpp"

#include <ostream>
#include <string>
#include <vector>

namespace radchain::cli {

// --set key=value; the value may be quoted for the shell's sake: optics.aperture="20 cm". One clear error
// line (InputError) for a malformed one.
Override parse_override(const std::string& text);
std::vector<Override> parse_overrides(const std::vector<std::string>& sets);

// One warning line per override of a key that a [[solve]] overwrites ("radchain: warning: ..."): the value
// set is only the solver's business then, which is rarely what was meant.
void warn_about_solved_overrides(const std::vector<SolveSpec>& solves, const std::vector<Override>& overrides,
                                 std::ostream& err);

// The sensor with its --set overrides; --no-solve drops the [[solve]] entries, otherwise the overrides of solved
// unknowns are warned about on stderr.
Chain load_sensor_of(const SensorArgs& args);

}  // namespace radchain::cli

#pragma once
// Text from files (sensor and criterion names, keys, values quoted in messages) must not drive a terminal: an
// escape sequence in a sensor name could erase lines, hide text or retitle the window. When standard output or
// error is a terminal, control characters written through std::cout / std::cerr are shown escaped (\x1b, \u009b)
// instead; newlines and tabs pass. Files and pipes get the bytes unchanged (a CSV, an .npy on stdout).
namespace radchain::cli {

void escape_control_characters_on_terminals();

}  // namespace radchain::cli

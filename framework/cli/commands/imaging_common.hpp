#pragma once
// The imaging module's commands, and the refusal of an option value they share.
#include "../options.hpp"

#include <string>

namespace radchain::cli {

[[noreturn]] void bad_option(const std::string& option, const std::string& value, const std::string& problem);

// The imaging commands (the module's entry points wrap them, imaging_module.cpp).
int render_command(const RenderCommand& command);
int validate_command(const ValidateCommand& command);
int mtf_command(const MtfCommand& command);

}  // namespace radchain::cli

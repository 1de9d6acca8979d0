// The entry points of radchain-imaging-commands.so (imaging_module.hpp). Everything else in the module is
// hidden; exceptions (InputError) travel to the executable's main like those of its own commands.
#include "imaging_common.hpp"
#include "../imaging_module.hpp"

#define RADCHAIN_MODULE_EXPORT extern "C" __attribute__((visibility("default")))

RADCHAIN_MODULE_EXPORT const char* radchain_imaging_module_build() {
  static const std::string build = radchain::cli::imaging_module_build();
  return build.c_str();
}

RADCHAIN_MODULE_EXPORT int radchain_render(const radchain::cli::RenderCommand& options) {
  return radchain::cli::render_command(options);
}

RADCHAIN_MODULE_EXPORT int radchain_validate(const radchain::cli::ValidateCommand& options) {
  return radchain::cli::validate_command(options);
}

RADCHAIN_MODULE_EXPORT int radchain_mtf(const radchain::cli::MtfCommand& options) {
  return radchain::cli::mtf_command(options);
}

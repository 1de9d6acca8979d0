#pragma once
// What render and validate share inside the imaging module: the frame geometry options and which kind of sensor
// a chain is.
#include "../options.hpp"

#include "radchain/chain.hpp"
#include "radchain/imaging/space_frame.hpp"

#include <optional>
#include <string>

namespace radchain::cli {

[[noreturn]] void bad_option(const std::string& option, const std::string& value, const std::string& problem);

// --focal-length, --pixel-pitch, --psf, --psf-wavelength, --psf-fwhm (validated options) into the renderer's options.
void apply_frame_geometry(render::SpaceFrameOptions& options, const Params& values);

// A point-target sensor (ccd_frame: signal and noise electrons, a target magnitude), else a pushbroom one.
bool is_point_target_sensor(Chain& chain);

// The imaging commands (the module's entry points wrap them, imaging_module.cpp).
int render_command(const RenderCommand& command);
int validate_command(const ValidateCommand& command);
int mtf_command(const MtfCommand& command);

}  // namespace radchain::cli

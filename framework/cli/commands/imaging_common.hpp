#pragma once
// What render and validate share inside the imaging module: quantities with units from option text, the frame
// geometry options, and which kind of sensor a chain is.
#include "../options.hpp"

#include "radchain/chain.hpp"
#include "radchain/imaging/space_frame.hpp"

#include <optional>
#include <string>

namespace radchain::cli {

[[noreturn]] void bad_option(const std::string& option, const std::string& value, const std::string& problem);

// "45 cm" → metres (si_unit "m"); a bare number only for dimensionless options; nullopt for "".
std::optional<double> quantity(const std::string& option, const std::string& text, const std::string& si_unit,
                               const std::string& example);

// --focal-length, --pixel-pitch, --psf, --psf-wavelength, --psf-fwhm into the renderer's options.
void apply_frame_geometry(render::SpaceFrameOptions& options, const FrameGeometry& geometry);

// A point-target sensor (ccd_frame: signal and noise electrons, a target magnitude), else a pushbroom one.
bool is_point_target_sensor(Chain& chain);

// The imaging commands (the module's entry points wrap them, imaging_module.cpp).
int render_command(const RenderCommand& command);
int validate_command(const ValidateCommand& command);
int mtf_command(const MtfCommand& command);

}  // namespace radchain::cli

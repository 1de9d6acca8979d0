#include "imaging_common.hpp"

#include "radchain/error.hpp"
#include "radchain/vocabulary.hpp"

namespace radchain::cli {

void bad_option(const std::string& option, const std::string& value, const std::string& problem) {
  throw InputError(SourceLocation{option, 0, 0}, "", value, problem);
}

void apply_frame_geometry(render::SpaceFrameOptions& o, const Params& values) {
  o.focal_length_m = values.maybe("--focal-length");
  o.pixel_pitch_m = values.maybe("--pixel-pitch");
  o.psf_wavelength_m = values.maybe("--psf-wavelength");
  o.gaussian_fwhm_m = values.maybe("--psf-fwhm");
  if (values.has("--psf")) o.psf = render::psf_model_from_string(values.text("--psf"));
}

bool is_point_target_sensor(Chain& chain) {
  if (!chain.results().find(vocabulary::detector_signal_electrons.name) ||
      !chain.results().find(vocabulary::detector_noise_electrons.name))
    return false;
  try {
    chain.parameter("target.magnitude");
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace radchain::cli

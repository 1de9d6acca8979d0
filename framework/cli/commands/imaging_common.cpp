#include "imaging_common.hpp"

#include "radchain/error.hpp"
#include "radchain/units.hpp"
#include "radchain/vocabulary.hpp"

namespace radchain::cli {

void bad_option(const std::string& option, const std::string& value, const std::string& problem) {
  throw InputError(SourceLocation{option, 0, 0}, "", value, problem);
}

std::optional<double> quantity(const std::string& option, const std::string& text, const std::string& si_unit,
                               const std::string& example) {
  if (text.empty()) return std::nullopt;
  try {
    const units::ParsedQuantity q = units::split_quantity(text);
    if (q.unit.empty()) {
      if (si_unit == "1") return q.number;
      bad_option(option, text, "expected " + units::dimension_name(si_unit) + " with its unit, e.g. \"" + example + "\"");
    }
    return q.number * units::conversion(q.unit, si_unit).factor;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception&) {
    bad_option(option, text, "expected " + units::dimension_name(si_unit) + ", e.g. \"" + example + "\"");
  }
}

void apply_frame_geometry(render::SpaceFrameOptions& o, const FrameGeometry& g) {
  o.focal_length_m = quantity("--focal-length", g.focal_length, "m", "45 cm");
  o.pixel_pitch_m = quantity("--pixel-pitch", g.pixel_pitch, "m", "27 um");
  o.psf_wavelength_m = quantity("--psf-wavelength", g.psf_wavelength, "m", "0.6 um");
  o.gaussian_fwhm_m = quantity("--psf-fwhm", g.psf_fwhm, "m", "20 um");
  if (!g.psf.empty()) {
    o.psf = render::psf_model_from_string(g.psf);
    if (!o.psf) bad_option("--psf", g.psf, "expected pixel, airy or gaussian");
  }
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

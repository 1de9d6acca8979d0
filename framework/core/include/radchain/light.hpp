#pragma once
// What flows from stage to stage: radiation as a spectral shape (set in the spectral phase) times a scalar
// (set in the scalar phase). The split is what makes solves and sweeps cheap: a change of aperture,
// magnitude or integration time touches only `scale`.
#include "radchain/spectrum.hpp"

#include <string>
#include <vector>

namespace radchain {

enum class RadiationForm {
  none,
  pupil_irradiance,   // point object: spectral irradiance at the entrance pupil, W m^-2 m^-1
  scene_radiance,     // extended scene: spectral radiance at the entrance pupil, W m^-2 sr^-1 m^-1
  focal_power,        // point object after the optics: spectral power in the image, W m^-1
  focal_irradiance,   // extended scene after the optics: spectral irradiance on the focal plane, W m^-2 m^-1
};
std::string to_string(RadiationForm form);

struct Radiation {
  RadiationForm form = RadiationForm::none;
  Spectrum spectrum;  // per unit scale, in the form's unit
  double scale = 1.0;
};

// A table (0 outside it) that a stage multiplied into the light: an SED, a source's spectrum, an atmosphere's
// transmittance table, an optics transmittance curve. `what` names it as messages do:
// `transmittance_curve = "m1.csv" of optics (plugin "telescope")`.
struct SpectralTable {
  double min_m = 0.0, max_m = 0.0;
  bool zero_at_min = false, zero_at_max = false;  // the table itself falls to 0 at that end (a filter's edge)
  std::string what;
};

struct Light {
  // The source's spectral irradiance at the target (W m^-2 m^-1), per unit `illumination_scale`.
  Spectrum illumination;
  double illumination_scale = 1.0;
  // The object of interest (point target, or the ground contrast ΔM of an extended scene).
  Radiation signal;
  // Light that is present whether or not the object is (sky, ground background); form none when absent.
  Radiation background;
  // Set by the atmosphere for the target: transmittance from the target to the sensor (spectral shape, empty
  // = 1, times a scalar) and path radiance (W m^-2 sr^-1 m^-1, empty = none).
  Spectrum up_path_transmittance;
  double up_path_scale = 1.0;
  Spectrum path_radiance;
  // Every table the light went through so far (spectral_limits.hpp): a detector band that reaches past one of them
  // is refused by its name, since the light there is unknown, not dark.
  std::vector<SpectralTable> tables;
  // The working band in which in-band totals are reported (E's, E0, ΔM); 0 = not set.
  double report_band_min_m = 0.0, report_band_max_m = 0.0;
  bool has_report_band() const { return report_band_max_m > report_band_min_m; }
};

}  // namespace radchain

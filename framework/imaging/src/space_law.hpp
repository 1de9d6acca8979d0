#pragma once
// The law of one pixel of a point-target frame (private to framework/src/render; the model is in
// space_frame.hpp): used by the renderer and by the closed-loop check's exact prediction.
#include "noise_law.hpp"
#include "radchain/imaging/space_frame.hpp"

#include <cmath>

namespace radchain::render::detail {

inline PixelLaw pixel_law(const SpaceFrameSetup& s, double source_electrons) {
  const double light = source_electrons + s.sky_electrons + s.flat_field_electrons;
  PixelLaw l;
  l.poisson_mean = (s.noise.shot ? light : 0.0) + (s.noise.dark ? s.dark_electrons : 0.0);
  l.constant = (s.noise.shot ? 0.0 : light) + (s.noise.dark ? 0.0 : s.dark_electrons);
  if (s.noise.saturation) l.full_well = s.full_well_electrons;
  l.read_sigma = s.noise.read ? s.read_noise_electrons : 0.0;
  l.gain = s.gain_e_per_dn;
  l.offset_dn = s.offset_dn;
  l.max_dn = std::exp2(s.adc_bits) - 1.0;
  return l;
}

}  // namespace radchain::render::detail

#pragma once
// The MTF budget of an Earth-observation camera as one cascade: a linear shift-invariant chain, so the system MTF
// is the product of its components (Goodman 2005 ch. 6; Fiete 2010 ch. 5-6; Holst 2008 ch. 10). What the giqe
// criterion integrates for RER and what `radchain mtf` draws: one definition for both.
#include "radchain/physics/mtf.hpp"

namespace radchain::physics {

struct MtfBudget {
  double wavelength_m = 0, f_number = 0, obscuration = 0, pitch_m = 0;
  double jitter_rms_m = 0, smear_m = 0, diffusion_rms_m = 0, wavefront_error_waves = 0;
  double tdi_stages = 1, tdi_mismatch = 0;
  double focal_length_m = 0, fried_parameter_m = 0;  // atmospheric turbulence (r₀ = 0: none)
};

struct MtfComponents {
  double diffraction = 1, pixel = 1, jitter = 1, smear = 1, diffusion = 1, wavefront = 1, tdi = 1, atmosphere = 1;
  double others() const { return jitter * smear * diffusion * wavefront * tdi * atmosphere; }
  double system() const { return diffraction * pixel * others(); }
};

// Every component at focal-plane frequency ν (cycles/m): annular-pupil diffraction (O'Neill 1956), the pixel
// aperture |sinc(π p ν)|, Gaussian jitter and diffusion, linear smear, wavefront error (Shannon's ATF), TDI
// synchronisation and long-exposure atmospheric turbulence (physics/mtf.hpp gives each one's source).
inline MtfComponents mtf_components(const MtfBudget& b, double nu) {
  MtfComponents m;
  m.diffraction = diffraction_mtf(nu, b.wavelength_m, b.f_number, b.obscuration);
  m.pixel = detector_pixel_mtf(nu, b.pitch_m);
  m.jitter = jitter_mtf(nu, b.jitter_rms_m);
  m.smear = linear_smear_mtf(nu, b.smear_m);
  m.diffusion = diffusion_mtf(nu, b.diffusion_rms_m);
  m.wavefront = wavefront_error_mtf(nu, b.wavelength_m, b.f_number, b.wavefront_error_waves);
  m.tdi = tdi_synchronisation_mtf(nu, b.tdi_stages, b.tdi_mismatch, b.pitch_m);
  m.atmosphere = turbulence_mtf(nu, b.wavelength_m, b.focal_length_m, b.fried_parameter_m);
  return m;
}

}  // namespace radchain::physics

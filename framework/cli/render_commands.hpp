#pragma once
// `radchain render` and `radchain validate` (issue 7): option structs filled by main.cpp's CLI11 parser, and the
// commands, which call the framework's renderer (radchain/render.hpp). Exit codes as elsewhere: 0 ok, 1 a failed
// check (validate), 2 bad input (thrown as InputError: quantities are checked here, with their units).
#include <cstdint>
#include <string>
#include <vector>

namespace radchain::cli {

// radchain render SENSOR [options]: a point-target sensor (ccd_frame) renders a detector frame, a pushbroom
// sensor (ccd_line) an Earth scene. Writes the data as FITS (--out) and/or a display-stretched preview
// (--preview .png/.tif); prints what it rendered.
struct RenderCommand {
  std::string sensor;
  std::vector<std::string> sets;   // --set section.key=value (as `radchain run`)
  std::string out;                 // --out frame.fits
  std::string preview;             // --preview frame.png | frame.tif
  std::string fits_type = "auto";  // --fits-type auto|float|int16|int32 (auto: integers when the ADC is on)
  std::uint64_t seed = 1;          // --seed (noise)
  std::vector<std::string> no_noise;  // --no-noise shot,dark,read,saturation,adc | all (Earth scenes: the NEE noise
                                      // goes with shot+dark+read, i.e. "all" or all three)

  // point-target frame
  int width = 512, height = 512;       // --size W[xH]
  std::vector<std::string> targets;    // --target "x,y,mag" (pixels, row 0 at the top) or "mag" (centre); mag may be
                                       // "limit"; none given: one at the limiting magnitude in the centre
  int stars = 0;                       // --stars N
  std::string star_magnitudes;         // --star-magnitudes bright:faint (default 8:limit+1)
  double star_slope = 0.4;             // --star-slope d log N/dm
  std::uint64_t star_seed = 1;         // --star-seed
  std::string focal_length, pixel_pitch;          // --focal-length "45 cm", --pixel-pitch "27 um" (when the sensor lacks them)
  std::string psf;                                // --psf pixel|airy|gaussian
  std::string psf_wavelength, psf_fwhm, obscuration;  // --psf-wavelength "0.6 um", --psf-fwhm "20 um", --obscuration 0.3
  std::string sky;                     // --sky "40 e-" per pixel and frame
  int oversampling = 8;                // --oversampling (PSF phases per pixel)
  double offset_dn = 0;                // --offset (ADC pedestal, DN)

  // Earth scene
  std::string scene;           // --scene map.png (reflectance 0..1; default: the built-in test scene)
  std::string scene_sampling;  // --scene-sampling "1.25 m" (ground size of one map pixel; required with --scene)
  std::string gsd;             // --gsd "5 m" (output sampling; default criteria.<name>.ground_element)
  std::string optics_mtf = "diffraction";  // --optics-mtf diffraction|eq7|none
  std::string wavelength;      // --wavelength "0.76 um" (MTF; default the mtf_match criterion's)
  bool no_detector_mtf = false;  // --no-detector-mtf
  int adc_bits = 12;           // --adc-bits (the ccd_line detector has no ADC of its own)

  // preview
  std::string stretch;            // --stretch asinh|linear (default: asinh for frames, linear for scenes)
  int upscale = 1;                // --upscale (nearest neighbour, small frames)
};
int render_command(const RenderCommand& command);

// radchain validate SENSOR [options]: the closed-loop checks at full size. Point-target sensors: detection
// Monte Carlo at the limiting magnitude and a flat field; pushbroom sensors: slanted-edge MTF and flat fields.
// Prints measured vs predicted; exit 1 when a check fails.
struct ValidateCommand {
  std::string sensor;
  std::vector<std::string> sets;
  long trials = 20000;       // --trials (detection frames)
  int size = 512;            // --size (flat fields, pixels)
  std::uint64_t seed = 1;    // --seed
  double threshold_sigma = 2.3263478740408408;  // --threshold γ in noise units (default z(0.99): P_fa = 1 %)
  double max_z = 4.0;        // --max-z: binomial sigmas allowed
  // frame geometry for point-target sensors that lack it (as render)
  std::string focal_length, pixel_pitch, psf, psf_wavelength, psf_fwhm;
};
int validate_command(const ValidateCommand& command);

}  // namespace radchain::cli

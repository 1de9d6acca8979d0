#pragma once
// What a sensor gives as an image, and the image of one request: the one place that decides, for `radchain render`,
// `radchain validate` and radchain.render in Python, whether a chain is seen as a point-target frame or an Earth
// scene, which closed-loop check applies, and which pixels a request draws. The front ends parse their arguments,
// call these and write or return the result, so the same request gives the same pixels everywhere.
#include "radchain/chain.hpp"
#include "radchain/imaging/image.hpp"
#include "radchain/imaging/space_frame.hpp"
#include "radchain/report.hpp"
#include "radchain/schema.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace radchain::render {

enum class SensorImage {
  point_frame,  // a detector frame of point targets: signal and noise electrons and a target magnitude (ccd_frame, emva1288)
  earth_scene,  // a pushbroom image of a reflectance map
};

// How `validate` checks a point-target frame: the photometry the chain's detection criterion models.
enum class PointCheck {
  window_detection,  // a square window, P_d and P_fa of the threshold detector
  psf_photometry,    // PSF-weighted (matched-filter) photometry of a still target
  streak,            // PSF-weighted photometry along a moving target's streak
};

struct SensorView {
  SensorImage image = SensorImage::earth_scene;
  PointCheck point_check = PointCheck::window_detection;  // point frames only
  // The frame's mean level (dark + sky) and read noise per pixel [e-] and the system gain [DN/e-], from the report.
  double level_electrons = 0, read_noise_electrons = 0, gain_dn_per_electron = 0;

  // A frame rendered without an ADC pedestal whose mean level lies within 3σ of the ADC's lowest step (−½ DN): its
  // noise is clipped at 0 DN, which none of the renderer's noise laws model.
  bool clipped_at_zero(double offset_dn) const;
};

SensorView sensor_view(Chain& chain, const Report& report);

// A render besides the sensor: the options validated against render_option_schema() (radchain/command_options.hpp),
// and the plain arguments.
struct RenderRequest {
  Params options;
  std::vector<std::string> targets;  // "x,y,mag" (pixels, row 0 at the top) or "mag" (centre); mag may be "limit"
  std::string scene;                 // Earth scenes: a reflectance map (empty: the built-in test scene)
  std::uint64_t seed = 1;            // noise
  std::uint64_t star_seed = 1;       // field stars
};

struct RenderedImage {
  Image image;
  Header header;
  SensorImage kind = SensorImage::point_frame;
  std::vector<std::string> summary;  // what the image is, line by line (the command prints them)
};

// Throws InputError, located at the option, for a request the chain cannot render (bad targets, sizes, a sensor
// without what it needs, an unreadable scene).
RenderedImage render_image(Chain& chain, const Report& report, const RenderRequest& request);

// The frame geometry options of render and validate (--focal-length, --pixel-pitch, --psf, --psf-wavelength,
// --psf-fwhm, validated) into a point-target frame's options.
void apply_frame_geometry(SpaceFrameOptions& frame, const Params& options);

// The preview of a rendered image: --stretch and --upscale, else asinh for frames and a linear 0.5-99.5 %
// stretch for scenes.
PreviewOptions preview_options(const Params& options, SensorImage kind);

}  // namespace radchain::render

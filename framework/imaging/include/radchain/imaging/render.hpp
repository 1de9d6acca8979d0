#pragma once
// Image simulation: see what the designed sensor would see, and check the model against it.
//   image.hpp          Image, FITS (with the sensor in the header) and PNG/TIFF previews through OpenImageIO
//   render_request.hpp which image a sensor gives (SensorView), and the image of one render request
//   space_frame.hpp   a point-target frame (ccd_frame): targets, star field, PSF, shot/dark/read noise, ADC
//   earth_scene.hpp   a pushbroom image of a reflectance map (ccd_line): MTF (FFTW), GSD, NEE noise, ADC
//   checks.hpp  closed loop: detection Monte Carlo, slanted-edge MTF, flat-field SNR
// docs/rendering.md describes the models, the checks and the speed.
#include "radchain/imaging/checks.hpp"
#include "radchain/imaging/earth_scene.hpp"
#include "radchain/imaging/image.hpp"
#include "radchain/imaging/render_request.hpp"
#include "radchain/imaging/space_frame.hpp"

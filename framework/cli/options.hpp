#pragma once
// The option structs of the `radchain` subcommands, and the CLI11 declarations that several of them share
// (declared once here, in options.cpp). main.cpp parses into the structs; the executable's commands and the
// imaging module (imaging_module.hpp) read them, so the structs hold plain std types only.
#include <cstdint>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace radchain::cli {

// The sensor file and what is changed in it: every command that loads one sensor.
struct SensorArgs {
  std::string sensor;              // the sensor TOML file
  std::vector<std::string> sets;   // --set section.key=value (repeatable)
  bool no_solve = false;           // --no-solve: forward only, the [[solve]] entries skipped (run, compare)
};

struct Output {
  std::string out;     // --out file ("" = stdout)
  std::string format;  // --format ("" = from --out's extension, else the command's default)
};

struct Batch {
  std::string shard;                 // --shard k/n
  std::string shard_order = "block"; // --shard-order block|round-robin
  std::size_t threads = 0;           // --threads (0 = all cores)
};

// Where a point image falls on the detector, for point-target sensors that do not say (render, validate).
struct FrameGeometry {
  std::string focal_length, pixel_pitch;  // --focal-length "45 cm", --pixel-pitch "27 um"
  std::string psf;                        // --psf pixel|airy|gaussian
  std::string psf_wavelength, psf_fwhm;   // --psf-wavelength "0.6 um", --psf-fwhm "20 um"
};

struct RunCommand {
  SensorArgs sensor;
  std::string format = "text";
};

struct CatalogueCommand {
  std::vector<std::string> inputs;
  std::vector<std::string> sets;
  std::vector<std::string> results;
  Output output;
  Batch batch;
};

struct CompareCommand {
  std::string a, b;
  std::vector<std::string> sets;
  bool no_solve = false;
  std::string tolerance;
  Output output;
};

struct SweepCommand {
  SensorArgs sensor;
  std::vector<std::string> results;
  std::string plot;
  Output output;
  Batch batch;
  bool allow_large = false;  // --allow-large: a grid above SweepOptions::large_points
};

struct MergeCommand {
  std::vector<std::string> shards;
  Output output;
};

// MTF curves of a pushbroom design (Kolobrodov 1996 Fig. 2) as CSV (stdout or --out) and optionally a PNG.
struct MtfCommand {
  SensorArgs sensor;
  std::string out;
  std::string plot;
};

// radchain render SENSOR [options]: a point-target sensor (ccd_frame) renders a detector frame, a pushbroom
// sensor (ccd_line) an Earth scene. Writes the data as FITS/TIFF/EXR (--out) and/or a display-stretched
// preview (--png/--preview .png/.tif); prints what it rendered.
struct RenderCommand {
  SensorArgs sensor;
  std::string out;                 // --out frame.fits | frame.tif | frame.exr
  std::string preview;             // --png, --preview frame.png | frame.tif
  std::string fits_type = "auto";  // --fits-type auto|float|int16|int32 (auto: integers when the ADC is on)
  std::uint64_t seed = 1;          // --seed (noise)
  std::vector<std::string> no_noise;  // --no-noise shot,dark,read,saturation,adc | all (Earth scenes: the NEE noise
                                      // goes with shot+dark+read, i.e. "all" or all three)

  // point-target frame
  int width = 512, height = 512;       // --width, --height (pixels)
  std::vector<std::string> targets;    // --target "x,y,mag" (pixels, row 0 at the top) or "mag" (centre); mag may be
                                       // "limit"; none given: one at the limiting magnitude in the centre
  int stars = 0;                       // --stars N
  std::string star_magnitudes;         // --star-magnitudes bright:faint (default 8:limit+1)
  double star_slope = 0.4;             // --star-slope d log N/dm
  std::uint64_t star_seed = 1;         // --star-seed
  FrameGeometry geometry;
  std::string obscuration;             // --obscuration 0.3
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

// radchain validate SENSOR [options]: the closed-loop checks at full size. Point-target sensors: detection
// Monte Carlo at the limiting magnitude and a flat field; pushbroom sensors: slanted-edge MTF and flat fields.
// Prints measured vs predicted; exit 1 when a check fails.
struct ValidateCommand {
  SensorArgs sensor;
  long trials = 20000;       // --trials (detection frames)
  int size = 512;            // --size (flat fields, pixels)
  std::uint64_t seed = 1;    // --seed
  double threshold_sigma = 2.3263478740408408;  // --threshold γ in noise units (default z(0.99): P_fa = 1 %)
  double max_z = 4.0;        // --max-z: binomial sigmas allowed
  FrameGeometry geometry;    // for point-target sensors that lack it (as render)
};

// The shared declarations (options.cpp).
inline constexpr const char* set_help = "override a key: section.key=value (repeatable)";
void add_sets(CLI::App* command, std::vector<std::string>& sets, const std::string& help = set_help);
void add_sensor(CLI::App* command, SensorArgs& sensor, const std::string& help = set_help);  // SENSOR and --set
void add_no_solve(CLI::App* command, bool& no_solve);
void add_output(CLI::App* command, Output& output, const std::string& formats);
void add_batch(CLI::App* command, Batch& batch);
void add_seed(CLI::App* command, std::uint64_t& seed);
void add_frame_geometry(CLI::App* command, FrameGeometry& geometry);

}  // namespace radchain::cli

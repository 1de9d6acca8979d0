// `radchain render` (in the imaging module): a detector frame (point targets) or an Earth scene (pushbroom),
// written as FITS/TIFF/EXR and a preview.
#include "imaging_common.hpp"
#include "../overrides.hpp"

#include "radchain/error.hpp"
#include "radchain/imaging/render.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

namespace radchain::cli {
namespace {

using namespace radchain::render;

NoiseTerms noise_of(const std::vector<std::string>& off) {
  NoiseTerms n;
  for (const auto& item : off) {
    std::stringstream list(item);
    std::string t;
    while (std::getline(list, t, ',')) {
      if (t == "all") n = NoiseTerms::none();
      else if (t == "shot") n.shot = false;
      else if (t == "dark") n.dark = false;
      else if (t == "read") n.read = false;
      else if (t == "saturation") n.saturation = false;
      else if (t == "adc" || t == "quantisation") n.quantisation = false;
      else bad_option("--no-noise", t, "expected shot, dark, read, saturation, adc or all");
    }
  }
  return n;
}

FitsPixel fits_type_of(const std::string& name, const Image& image) {
  if (name == "auto") return fits_pixel_for(image);
  if (name == "float") return FitsPixel::float32;
  if (name == "int16") return FitsPixel::int16;
  if (name == "int32") return FitsPixel::int32;
  bad_option("--fits-type", name, "expected auto, float, int16 or int32");
}

PreviewOptions preview_of(const RenderCommand& c, bool space) {
  PreviewOptions p;
  if (!space) {  // a scene: linear between the 0.5 % and 99.5 % points
    p.stretch = Stretch::linear;
    p.low_percentile = 0.5;
    p.high_percentile = 99.5;
  }
  if (c.stretch == "linear") p.stretch = Stretch::linear;
  else if (c.stretch == "asinh") p.stretch = Stretch::asinh;
  else if (!c.stretch.empty()) bad_option("--stretch", c.stretch, "expected asinh or linear");
  p.upscale = std::clamp(c.upscale, 1, 16);
  return p;
}

void write_outputs(const RenderCommand& c, const Image& image, const Header& header, bool space) {
  if (!c.out.empty()) {
    const std::string extension = std::filesystem::path(c.out).extension().string();
    if (extension == ".fits" || extension == ".fit" || extension == ".fts") {
      write_fits(c.out, image, header, fits_type_of(c.fits_type, image));
      fmt::print("wrote {} ({}×{}, FITS, {} header cards)\n", c.out, image.width, image.height, header.size());
    } else if (extension == ".tif" || extension == ".tiff" || extension == ".exr") {
      write_float_image(c.out, image, header);
      fmt::print("wrote {} ({}×{}, 32-bit float, {} metadata entries)\n", c.out, image.width, image.height, header.size());
    } else {
      bad_option("--out", c.out, "expected a .fits, .tif or .exr file for the data (previews: --png frame.png)");
    }
  }
  if (!c.preview.empty()) {
    write_preview(c.preview, image, preview_of(c, space));
    fmt::print("wrote {} (preview)\n", c.preview);
  }
  if (c.out.empty() && c.preview.empty()) fmt::print("nothing written: give --out frame.fits and/or --preview frame.png\n");
}

int render_space(Chain& chain, const Report& report, const RenderCommand& c) {
  SpaceFrameOptions o;
  o.width = c.width;
  o.height = c.height;
  for (const auto& t : c.targets) {
    std::vector<double> v;
    std::stringstream list(t);
    std::string item;
    try {
      while (std::getline(list, item, ',')) v.push_back(item == "limit" ? std::nan("") : std::stod(item));
    } catch (const std::exception&) {
      bad_option("--target", t, "expected x,y,magnitude or a magnitude (\"limit\": the limiting magnitude)");
    }
    if (v.size() == 1) o.targets.push_back({std::floor(c.width / 2.0) + 0.5, std::floor(c.height / 2.0) + 0.5, v[0]});
    else if (v.size() == 3) o.targets.push_back({v[0], v[1], v[2]});
    else bad_option("--target", t, "expected x,y,magnitude or a magnitude (\"limit\": the limiting magnitude)");
    if (v.size() == 3 && (std::isnan(v[0]) || std::isnan(v[1]))) bad_option("--target", t, "the position must be numbers");
  }
  o.stars.count = c.stars;
  o.stars.slope = c.star_slope;
  o.stars.seed = c.star_seed;
  if (!c.star_magnitudes.empty()) {
    const auto colon = c.star_magnitudes.find(':');
    try {
      if (colon == std::string::npos) throw std::invalid_argument("no colon");
      o.stars.bright_magnitude = std::stod(c.star_magnitudes.substr(0, colon));
      o.stars.faint_magnitude = std::stod(c.star_magnitudes.substr(colon + 1));
    } catch (const std::exception&) {
      bad_option("--star-magnitudes", c.star_magnitudes, "expected bright:faint, e.g. 8:17");
    }
  }
  apply_frame_geometry(o, c.geometry);
  o.obscuration = quantity("--obscuration", c.obscuration, "1", "0.3");
  o.sky_electrons_per_pixel = quantity("--sky", c.sky, "electron", "40 e-");
  o.oversampling = c.oversampling;
  o.offset_dn = c.offset_dn;
  o.noise = noise_of(c.no_noise);
  const SpaceFrameRenderer renderer(space_frame_setup(chain, report, o));
  const SpaceFrameSetup& s = renderer.setup();
  const Image frame = renderer.render(c.seed);
  fmt::print("{}: point-target frame {}×{}, PSF {}, limiting magnitude {:.4g}, {} targets, {} stars\n", s.sensor_name, s.width,
             s.height, to_string(s.psf), s.limiting_magnitude,
             std::count_if(s.sources.begin(), s.sources.end(), [](const auto& x) { return x.target; }),
             std::count_if(s.sources.begin(), s.sources.end(), [](const auto& x) { return !x.target; }));
  for (std::size_t k = 0; k < s.sources.size() && k < 9; ++k)
    if (s.sources[k].target)
      fmt::print("  target at ({:.2f}, {:.2f}) magnitude {:.3f}: {:.4g} e- in the image, {:.4g} in the {}-pixel window\n",
                 s.sources[k].x_px, s.sources[k].y_px, s.sources[k].magnitude, s.sources[k].electrons,
                 s.sources[k].electrons * renderer.window_fraction(k, static_cast<int>(std::lround(std::sqrt(s.window_pixels)))),
                 s.window_pixels);
  fmt::print("  dark {:.4g} e-, sky {:.4g} e-, read {:.4g} e- per pixel; {} ({:.4g} e-/DN, {} bits)\n", s.dark_electrons,
             s.sky_electrons, s.read_noise_electrons, renderer.unit(), s.gain_e_per_dn, s.adc_bits);
  write_outputs(c, frame, renderer.header(c.seed), true);
  return 0;
}

int render_earth(Chain& chain, const Report& report, const RenderCommand& c) {
  EarthSceneOptions o;
  o.output_sampling_m = quantity("--gsd", c.gsd, "m", "5 m");
  o.wavelength_m = quantity("--wavelength", c.wavelength, "m", "0.76 um");
  const auto mtf = optics_mtf_from_string(c.optics_mtf);
  if (!mtf) bad_option("--optics-mtf", c.optics_mtf, "expected diffraction, eq7 or none");
  o.optics = *mtf;
  o.detector_mtf = !c.no_detector_mtf;
  o.adc_bits = c.adc_bits;
  const NoiseTerms n = noise_of(c.no_noise);
  o.noise = n.read || n.shot || n.dark;
  o.saturation = n.saturation;
  o.quantisation = n.quantisation;
  Image map;
  if (c.scene.empty()) {
    // The built-in scene at a quarter of the output sampling.
    o.input_sampling_m = 1.0;
    const double gsd = earth_scene_setup(chain, report, o).output_sampling_m;
    TestSceneOptions scene;
    scene.sampling_m = quantity("--scene-sampling", c.scene_sampling, "m", "1.25 m").value_or(gsd / 4.0);
    scene.bar_unit_m = gsd;
    map = make_test_scene(scene);
    o.input_sampling_m = scene.sampling_m;
  } else {
    const auto sampling = quantity("--scene-sampling", c.scene_sampling, "m", "1.25 m");
    if (!sampling) bad_option("--scene-sampling", "", "give the ground size of one pixel of " + c.scene + ", e.g. \"1.25 m\"");
    o.input_sampling_m = *sampling;
    map = read_reflectance_map(c.scene);
  }
  const EarthSceneSetup s = earth_scene_setup(chain, report, o);
  const Image image = render_earth_scene(s, map, c.seed);
  fmt::print("{}: Earth scene {}×{} at {:.4g} m → {}×{} at {:.4g} m (optics MTF {}, λ = {:.4g} um, N = {:.4g})\n", s.sensor_name,
             map.width, map.height, s.input_sampling_m, image.width, image.height, s.output_sampling_m, to_string(s.optics),
             s.wavelength_m * 1e6, s.f_number);
  fmt::print("  exposure per unit reflectance {:.4g} J m-2, NEE {:.4g} J m-2, SNR of Δρ = {:.4g}: {:.4g}; {}\n",
             s.exposure_per_reflectance(), s.nee_J_m2, s.reflectance_difference, s.snr, earth_unit(s));
  write_outputs(c, image, earth_scene_header(s, c.seed), false);
  return 0;
}

}  // namespace

int render_command(const RenderCommand& c) {
  Chain chain = load_sensor_of(c.sensor);
  const Report report = chain.run();
  if (!report.all_passed())
    fmt::print(stderr, "radchain render: {}: a solve or an [expected] check failed (rendering anyway)\n", c.sensor.sensor);
  if (is_point_target_sensor(chain)) return render_space(chain, report, c);
  return render_earth(chain, report, c);
}

}  // namespace radchain::cli

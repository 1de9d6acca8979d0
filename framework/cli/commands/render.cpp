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

NoiseTerms noise_of(const Params& v) {
  NoiseTerms n;
  if (!v.has("--no-noise")) return n;
  for (const auto& t : v.entry("--no-noise").texts) {
    if (t == "all") n = NoiseTerms::none();
    else if (t == "shot") n.shot = false;
    else if (t == "dark") n.dark = false;
    else if (t == "read") n.read = false;
    else if (t == "saturation") n.saturation = false;
    else if (t == "adc") n.quantisation = false;
  }
  return n;
}

FitsPixel fits_type_of(const std::string& name, const Image& image) {
  if (name == "float") return FitsPixel::float32;
  if (name == "int16") return FitsPixel::int16;
  if (name == "int32") return FitsPixel::int32;
  return fits_pixel_for(image);  // auto
}

PreviewOptions preview_of(const Params& v, bool space) {
  PreviewOptions p;
  if (!space) {  // a scene: linear between the 0.5 % and 99.5 % points
    p.stretch = Stretch::linear;
    p.low_percentile = 0.5;
    p.high_percentile = 99.5;
  }
  if (v.has("--stretch")) p.stretch = v.text("--stretch") == "linear" ? Stretch::linear : Stretch::asinh;
  p.upscale = static_cast<int>(v.integer("--upscale"));
  return p;
}

void write_outputs(const RenderCommand& c, const Params& v, const Image& image, const Header& header, bool space) {
  if (!c.out.empty()) {
    const std::string extension = std::filesystem::path(c.out).extension().string();
    if (extension == ".fits" || extension == ".fit" || extension == ".fts") {
      write_fits(c.out, image, header, fits_type_of(v.text("--fits-type"), image));
      fmt::print("wrote {} ({}×{}, FITS, {} header cards)\n", c.out, image.width, image.height, header.size());
    } else if (extension == ".tif" || extension == ".tiff" || extension == ".exr") {
      write_float_image(c.out, image, header);
      fmt::print("wrote {} ({}×{}, 32-bit float, {} metadata entries)\n", c.out, image.width, image.height, header.size());
    } else {
      bad_option("--out", c.out, "expected a .fits, .tif or .exr file for the data (previews: --png frame.png)");
    }
  }
  if (!c.preview.empty()) {
    write_preview(c.preview, image, preview_of(v, space));
    fmt::print("wrote {} (preview)\n", c.preview);
  }
  if (c.out.empty() && c.preview.empty()) fmt::print("nothing written: give --out frame.fits and/or --preview frame.png\n");
}

int render_space(Chain& chain, const Report& report, const RenderCommand& c, const Params& v) {
  SpaceFrameOptions o;
  o.width = static_cast<int>(v.integer("--width"));
  o.height = static_cast<int>(v.integer("--height"));
  for (const auto& t : c.targets) {
    std::vector<double> xym;
    std::stringstream list(t);
    std::string item;
    try {
      while (std::getline(list, item, ',')) xym.push_back(item == "limit" ? std::nan("") : std::stod(item));
    } catch (const std::exception&) {
      bad_option("--target", t, "expected x,y,magnitude or a magnitude (\"limit\": the limiting magnitude)");
    }
    if (xym.size() == 1) o.targets.push_back({std::floor(o.width / 2.0) + 0.5, std::floor(o.height / 2.0) + 0.5, xym[0]});
    else if (xym.size() == 3) o.targets.push_back({xym[0], xym[1], xym[2]});
    else bad_option("--target", t, "expected x,y,magnitude or a magnitude (\"limit\": the limiting magnitude)");
    if (xym.size() == 3 && (std::isnan(xym[0]) || std::isnan(xym[1]))) bad_option("--target", t, "the position must be numbers");
  }
  o.stars.count = static_cast<int>(v.integer("--stars"));
  o.stars.slope = v.get("--star-slope");
  o.stars.seed = c.star_seed;
  if (v.has("--star-magnitudes")) {
    const std::string& range = v.text("--star-magnitudes");
    const auto colon = range.find(':');
    try {
      if (colon == std::string::npos) throw std::invalid_argument("no colon");
      o.stars.bright_magnitude = std::stod(range.substr(0, colon));
      o.stars.faint_magnitude = std::stod(range.substr(colon + 1));
    } catch (const std::exception&) {
      bad_option("--star-magnitudes", range, "expected bright:faint, e.g. 8:17");
    }
  }
  apply_frame_geometry(o, v);
  o.obscuration = v.maybe("--obscuration");
  o.sky_electrons_per_pixel = v.maybe("--sky");
  o.oversampling = static_cast<int>(v.integer("--oversampling"));
  o.offset_dn = v.get("--offset");
  o.noise = noise_of(v);
  const SpaceFrameRenderer renderer(space_frame_setup(chain, report, o));
  const SpaceFrameSetup& s = renderer.setup();
  const Image frame = renderer.render(c.seed);
  fmt::print("{}: point-target frame {}×{}, PSF {}, limiting magnitude {:.4g}, {} targets, {} stars\n", s.sensor_name, s.width,
             s.height, to_string(s.psf), s.limiting_magnitude,
             std::count_if(s.sources.begin(), s.sources.end(), [](const auto& x) { return x.target; }),
             std::count_if(s.sources.begin(), s.sources.end(), [](const auto& x) { return !x.target; }));
  for (std::size_t k = 0; k < s.sources.size() && k < 9; ++k)
    if (s.sources[k].target && s.target_streak_px > 0)
      fmt::print("  target at ({:.2f}, {:.2f}) magnitude {:.3f}: {:.4g} e- in a streak of {:.4g} pixels along +x\n",
                 s.sources[k].x_px, s.sources[k].y_px, s.sources[k].magnitude, s.sources[k].electrons, s.target_streak_px);
    else if (s.sources[k].target)
      fmt::print("  target at ({:.2f}, {:.2f}) magnitude {:.3f}: {:.4g} e- in the image, {:.4g} in the {}-pixel window\n",
                 s.sources[k].x_px, s.sources[k].y_px, s.sources[k].magnitude, s.sources[k].electrons,
                 s.sources[k].electrons * renderer.window_fraction(k, static_cast<int>(std::lround(std::sqrt(s.window_pixels)))),
                 s.window_pixels);
  fmt::print("  dark {:.4g} e-, sky {:.4g} e-, read {:.4g} e- per pixel; {} ({:.4g} e-/DN, {} bits)\n", s.dark_electrons,
             s.sky_electrons, s.read_noise_electrons, renderer.unit(), s.gain_e_per_dn, s.adc_bits);
  write_outputs(c, v, frame, renderer.header(c.seed), true);
  return 0;
}

int render_earth(Chain& chain, const Report& report, const RenderCommand& c, const Params& v) {
  EarthSceneOptions o;
  o.output_sampling_m = v.maybe("--gsd");
  o.wavelength_m = v.maybe("--wavelength");
  o.optics = *optics_mtf_from_string(v.text("--optics-mtf"));  // one of the schema's choices
  o.detector_mtf = !v.flag("--no-detector-mtf");
  o.adc_bits = static_cast<int>(v.integer("--adc-bits"));
  const NoiseTerms n = noise_of(v);
  o.noise = n.read || n.shot || n.dark;
  o.saturation = n.saturation;
  o.quantisation = n.quantisation;
  Image map;
  if (c.scene.empty()) {
    // The built-in scene at a quarter of the output sampling.
    o.input_sampling_m = 1.0;
    const double gsd = earth_scene_setup(chain, report, o).output_sampling_m;
    TestSceneOptions scene;
    scene.sampling_m = v.maybe("--scene-sampling").value_or(gsd / 4.0);
    scene.bar_unit_m = gsd;
    map = make_test_scene(scene);
    o.input_sampling_m = scene.sampling_m;
  } else {
    const auto sampling = v.maybe("--scene-sampling");
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
  write_outputs(c, v, image, earth_scene_header(s, c.seed), false);
  return 0;
}

}  // namespace

int render_command(const RenderCommand& c) {
  const Params values = validated_options(render_option_schema(), c.values, "radchain render");
  Chain chain = load_sensor_of(c.sensor);
  const Report report = chain.run();
  if (!report.all_passed())
    fmt::print(stderr, "radchain render: {}: a solve or an [expected] check failed (rendering anyway)\n", c.sensor.sensor);
  if (is_point_target_sensor(chain)) return render_space(chain, report, c, values);
  return render_earth(chain, report, c, values);
}

}  // namespace radchain::cli

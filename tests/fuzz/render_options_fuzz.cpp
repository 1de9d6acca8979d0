// The options of `radchain render` (render_option_schema(), radchain/command_options.hpp) and its plain arguments
// (--target, --seed, --star-seed): one option per input line, "--width 64", "--sky \"40 e-\"", "--no-noise
// shot,dark", "--target 10,10,12", a flag alone ("--no-detector-mtf"). The lines are validated as the command
// validates them (validated_options), then render_image (radchain/imaging/render_request.hpp) draws a point-target
// frame of sensors/msx-sbv.toml and an Earth scene of sensors/kolobrodov-1996-ccd151-computed.toml (ccd_line) from a
// 64×64 test map, and the image is written as the command writes it (FITS of --fits-type, the preview of --stretch
// and --upscale). Sizes are capped so that an input stays fast: a frame at most 64×64 pixels, at most 50 field
// stars, an upscale of at most 2, a scene output of at most 128 pixels a side (larger requests are rendered at the
// cap, or the scene is left out); what the caps leave out is the schema's limits, which validation still sees.
// A finding: anything but InputError escaping the validation or the render (the command prints "internal error",
// exit 3), or anything but InputError, std::runtime_error or std::invalid_argument from the writers (what the
// command reports at --out); a non-finite pixel; a sanitizer report; a hang.
#include "fuzz_input.hpp"

#include "radchain/command_options.hpp"
#include "radchain/error.hpp"
#include "radchain/imaging/earth_scene.hpp"
#include "radchain/imaging/image.hpp"
#include "radchain/imaging/render_request.hpp"
#include "radchain/sensor_file.hpp"
#include "radchain/strings.hpp"

#include <charconv>
#include <cstdint>
#include <initializer_list>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace radchain;
using namespace radchain::render;

struct Sensor {
  std::optional<Chain> chain;
  std::optional<Report> report;
};
Sensor frame_sensor, scene_sensor;
std::string scene_map;                // the 64×64 test map (FITS) the Earth scene is drawn from
constexpr double scene_map_px = 64;
double design_sampling_m = 0;         // the scene sensor's output sampling without --gsd
constexpr const char* default_scene_sampling = "4 m";  // a --scene-sampling for inputs that give none

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "render_options_fuzz: %s\n", what.c_str());
  std::abort();
}

Sensor load(const std::string& file) {
  Sensor s;
  s.chain.emplace(load_sensor(RADCHAIN_SOURCE_DIR "/sensors/" + file));
  s.report.emplace(s.chain->run());
  return s;
}

// "--key value", "--key=value" or "--key" (a flag); the value without one pair of enclosing quotes, as the shell
// passes it.
std::pair<std::string, std::string> option_of(const std::string& line) {
  const std::size_t end = line.find_first_of(" \t=");
  std::string key = line.substr(0, end), value = end == std::string::npos ? "" : strings::trimmed(line.substr(end + 1));
  if (value.size() >= 2 && (value.front() == '"' || value.front() == '\'') && value.back() == value.front())
    value = value.substr(1, value.size() - 2);
  return {key, value};
}

const ParamSpec* schema_entry(const std::string& key) {
  for (const ParamSpec& p : render_option_schema())
    if (p.key == key) return &p;
  return nullptr;
}

// The options validated, then again with each integer option of `caps` above its cap given once more at the cap (the
// last one given wins): the render sees Params as validated_options makes them.
Params validated_with_caps(OptionValues values, std::initializer_list<std::pair<const char*, std::int64_t>> caps) {
  const Params given = validated_options(render_option_schema(), values, "radchain render");
  bool capped = false;
  for (const auto& [key, cap] : caps)
    if (given.integer(key) > cap) values.given.emplace_back(key, std::to_string(cap)), capped = true;
  return capped ? validated_options(render_option_schema(), values, "radchain render") : given;
}

void check_pixels(const Image& image, const char* what) {
  for (const float v : image.pixels)
    if (!std::isfinite(v)) finding(std::string(what) + ": a pixel is not finite");
}

// As `radchain render --out x.fits --preview x.png` writes the image (framework/cli/commands/render.cpp).
void write(const RenderedImage& r, const Params& v) {
  const std::string& type = v.text("--fits-type");
  const FitsPixel pixel = type == "float"   ? FitsPixel::float32
                          : type == "int16" ? FitsPixel::int16
                          : type == "int32" ? FitsPixel::int32
                                            : fits_pixel_for(r.image);
  try {
    write_fits((fuzz::scratch_dir() / "image.fits").string(), r.image, r.header, pixel);
    write_preview((fuzz::scratch_dir() / "preview.png").string(), r.image, preview_options(v, r.kind));
  } catch (const std::runtime_error&) {  // InputError included
  } catch (const std::invalid_argument&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  fuzz::configure_host();
  frame_sensor = load("msx-sbv.toml");
  scene_sensor = load("kolobrodov-1996-ccd151-computed.toml");
  TestSceneOptions map;
  map.size_px = static_cast<int>(scene_map_px);
  scene_map = (fuzz::scratch_dir() / "map.fits").string();
  write_fits(scene_map, make_test_scene(map), {});
  EarthSceneOptions defaults;
  defaults.input_sampling_m = 1.0;
  design_sampling_m = earth_scene_setup(*scene_sensor.chain, *scene_sensor.report, defaults).output_sampling_m;
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  OptionValues values;
  std::vector<std::string> targets;
  std::uint64_t seed = 1, star_seed = 1;
  std::istringstream lines{std::string(fuzz::as_text(data, size))};
  for (std::string line; std::getline(lines, line);) {
    const auto [key, value] = option_of(strings::trimmed(line));
    if (key == "--target") {
      targets.push_back(value);
    } else if (key == "--seed" || key == "--star-seed") {
      // CLI11 reads these as unsigned integers and refuses anything else itself.
      std::uint64_t n = 0;
      const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), n);
      if (error == std::errc() && end == value.data() + value.size()) (key == "--seed" ? seed : star_seed) = n;
    } else if (const ParamSpec* spec = schema_entry(key)) {
      values.given.emplace_back(key, spec->type == ParamType::flag ? "true" : value);
    }  // anything else is an option CLI11 refuses before radchain sees it
  }
  std::optional<Params> options;
  try {
    options.emplace(validated_options(render_option_schema(), values, "radchain render"));
  } catch (const InputError&) {
    return 0;  // the command's answer to bad options: one line, exit 2
  }

  // The point-target frame.
  try {
    const RenderRequest request{validated_with_caps(values, {{"--width", 64}, {"--height", 64}, {"--stars", 50}, {"--upscale", 2}}),
                                targets, "", seed, star_seed};
    const RenderedImage r = render_image(*frame_sensor.chain, *frame_sensor.report, request);
    check_pixels(r.image, "point-target frame");
    write(r, request.options);
  } catch (const InputError&) {
  }

  // The Earth scene from the 64×64 map: its output has 64 × (map sampling / output sampling) pixels a side.
  try {
    if (!options->has("--scene-sampling")) values.given.emplace_back("--scene-sampling", default_scene_sampling);
    const RenderRequest request{validated_with_caps(values, {{"--upscale", 2}}), targets, scene_map, seed, star_seed};
    const double output_sampling = request.options.maybe("--gsd").value_or(design_sampling_m);
    if (scene_map_px * *request.options.maybe("--scene-sampling") / output_sampling > 128) return 0;
    const RenderedImage r = render_image(*scene_sensor.chain, *scene_sensor.report, request);
    check_pixels(r.image, "Earth scene");
    write(r, request.options);
  } catch (const InputError&) {
  }
  return 0;
}

// Which image a sensor gives and the image of one request (render_request.hpp): the render options into the
// renderer's, the frame or scene drawn, its FITS header and the summary lines.
#include "radchain/imaging/render_request.hpp"

#include "radchain/error.hpp"
#include "radchain/imaging/checks.hpp"
#include "radchain/imaging/earth_scene.hpp"
#include "radchain/vocabulary.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace radchain::render {
namespace {

[[noreturn]] void refuse_option(const std::string& option, const std::string& value, const std::string& problem) {
  throw InputError(SourceLocation{option, 0, 0}, "", value, problem);
}

// Signal and noise electrons and a target magnitude: a detector frame of point targets; else a pushbroom's scene.
bool is_point_target_sensor(Chain& chain) {
  if (!chain.results().find(vocabulary::detector_signal_electrons.name) ||
      !chain.results().find(vocabulary::detector_noise_electrons.name))
    return false;
  try {
    chain.parameter("target.magnitude");
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

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

RenderedImage render_space(Chain& chain, const Report& report, const RenderRequest& c) {
  const Params& v = c.options;
  SpaceFrameOptions o;
  o.width = static_cast<int>(v.integer("--width"));
  o.height = static_cast<int>(v.integer("--height"));
  for (const auto& t : c.targets) {
    std::vector<double> xym;
    std::stringstream list(t);
    std::string item;
    try {
      while (std::getline(list, item, ',')) {
        if (item == "limit") {
          xym.push_back(std::nan(""));  // the limiting magnitude, filled in by the frame
          continue;
        }
        xym.push_back(std::stod(item));
        // A typed "nan" or "inf" is not "limit": it would be drawn at the limit or not at all.
        if (!std::isfinite(xym.back())) throw std::invalid_argument("not a finite number");
      }
    } catch (const std::exception&) {
      refuse_option("--target", t, "expected x,y,magnitude or a magnitude (\"limit\": the limiting magnitude)");
    }
    if (xym.size() == 1) o.targets.push_back({std::floor(o.width / 2.0) + 0.5, std::floor(o.height / 2.0) + 0.5, xym[0]});
    else if (xym.size() == 3) o.targets.push_back({xym[0], xym[1], xym[2]});
    else refuse_option("--target", t, "expected x,y,magnitude or a magnitude (\"limit\": the limiting magnitude)");
    if (xym.size() == 3 && (std::isnan(xym[0]) || std::isnan(xym[1]))) refuse_option("--target", t, "the position must be numbers");
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
      refuse_option("--star-magnitudes", range, "expected bright:faint, e.g. 8:17");
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
  RenderedImage out;
  out.image = renderer.render(c.seed);
  out.header = renderer.header(c.seed);
  const auto targets = std::count_if(s.sources.begin(), s.sources.end(), [](const auto& x) { return x.target; });
  out.summary.push_back(fmt::format("{}: point-target frame {}×{}, PSF {}, limiting magnitude {:.4g}, {} targets, {} stars",
                                    s.sensor_name, s.width, s.height, to_string(s.psf), s.limiting_magnitude, targets,
                                    static_cast<std::ptrdiff_t>(s.sources.size()) - targets));
  for (std::size_t k = 0; k < s.sources.size() && k < 9; ++k)
    if (s.sources[k].target && s.target_streak_px > 0)
      out.summary.push_back(fmt::format("  target at ({:.2f}, {:.2f}) magnitude {:.3f}: {:.4g} e- in a streak of {:.4g} pixels along +x",
                 s.sources[k].x_px, s.sources[k].y_px, s.sources[k].magnitude, s.sources[k].electrons, s.target_streak_px));
    else if (s.sources[k].target)
      out.summary.push_back(fmt::format("  target at ({:.2f}, {:.2f}) magnitude {:.3f}: {:.4g} e- in the image, {:.4g} in the {}-pixel window",
                 s.sources[k].x_px, s.sources[k].y_px, s.sources[k].magnitude, s.sources[k].electrons,
                 s.sources[k].electrons * renderer.window_fraction(k, static_cast<int>(std::lround(std::sqrt(s.window_pixels)))),
                 s.window_pixels));
  out.summary.push_back(fmt::format("  dark {:.4g} e-, sky {:.4g} e-, read {:.4g} e- per pixel; {} ({:.4g} e-/DN, {} bits)",
                                    s.dark_electrons, s.sky_electrons, s.read_noise_electrons, renderer.unit(),
                                    s.gain_e_per_dn, s.adc_bits));
  return out;
}

RenderedImage render_earth(Chain& chain, const Report& report, const RenderRequest& c) {
  const Params& v = c.options;
  EarthSceneOptions o;
  o.output_sampling_m = v.maybe("--gsd");
  o.wavelength_m = v.maybe("--wavelength");
  if (v.text("--optics-mtf") != "auto") o.optics = *optics_mtf_from_string(v.text("--optics-mtf"));  // a schema choice
  o.detector_mtf = !v.flag("--no-detector-mtf");
  if (v.has("--adc-bits")) o.adc_bits = static_cast<int>(v.integer("--adc-bits"));
  const NoiseTerms n = noise_of(v);
  o.noise = n.read || n.shot || n.dark;
  o.shot = n.shot;
  o.dark = n.dark;
  o.read = n.read;
  o.saturation = n.saturation;
  o.quantisation = n.quantisation;
  Image map;
  if (c.scene.empty()) {
    // The built-in scene at a quarter of the native sampling (of the output sampling without binning).
    o.input_sampling_m = 1.0;
    const EarthSceneSetup sampling = earth_scene_setup(chain, report, o);
    TestSceneOptions scene;
    scene.sampling_m = v.maybe("--scene-sampling").value_or(sampling.native_sampling_m() / 4.0);
    scene.bar_unit_m = sampling.output_sampling_m;
    map = make_test_scene(scene);
    o.input_sampling_m = scene.sampling_m;
  } else {
    const auto sampling = v.maybe("--scene-sampling");
    if (!sampling) refuse_option("--scene-sampling", "", "give the ground size of one pixel of " + c.scene + ", e.g. \"1.25 m\"");
    o.input_sampling_m = *sampling;
    try {  // a scene file is input: one that cannot be read is refused at --scene (exit 2), not an internal error
      map = read_reflectance_map(c.scene);
    } catch (const std::runtime_error& error) {
      refuse_option("--scene", c.scene, error.what());
    } catch (const std::invalid_argument& error) {
      refuse_option("--scene", c.scene, error.what());
    }
  }
  const EarthSceneSetup s = earth_scene_setup(chain, report, o);
  RenderedImage out;
  out.kind = SensorImage::earth_scene;
  out.image = render_earth_scene(s, map, c.seed);
  out.header = earth_scene_header(s, c.seed);
  const Image& image = out.image;
  out.summary.push_back(fmt::format("{}: Earth scene {}×{} at {:.4g} m → {}×{} at {:.4g} m (optics MTF {}, λ = {:.4g} um, N = {:.4g})",
                                    s.sensor_name, map.width, map.height, s.input_sampling_m, image.width, image.height,
                                    s.output_sampling_m, to_string(s.optics), s.wavelength_m * 1e6, s.f_number));
  if (s.radiometry == EarthRadiometry::electrons) {
    out.summary.push_back(fmt::format("  {:.5g} e- per unit reflectance + {:.4g} e- path radiance, dark {:.4g} e-, read {:.4g} e-, "
                                      "well {:.5g} e-, K {:.4g} DN/e-, SNR at ρ = {:.4g}: {:.4g}; {}",
                                      s.electrons_per_reflectance, s.path_electrons, s.dark_electrons, s.read_noise_e,
                                      s.capacity_e, s.gain_dn_per_e, s.scene_reflectance, s.snr, earth_unit(s)));
    if (s.native_sums() > 1)
      out.summary.push_back(fmt::format("  per native pixel and frame; each output pixel sums {}×{} native pixels over {} frame{} "
                                        "({} reads)",
                                        s.binning, s.binning, s.exposures, s.exposures == 1 ? "" : "s", s.native_sums()));
  }
  else
    out.summary.push_back(fmt::format("  exposure per unit reflectance {:.4g} J m-2, NEE {:.4g} J m-2, SNR of Δρ = {:.4g}: {:.4g}; {}",
                                      s.exposure_per_reflectance(), s.nee_J_m2, s.reflectance_difference, s.snr, earth_unit(s)));
  return out;
}

}  // namespace

bool SensorView::clipped_at_zero(double offset_dn) const {
  const double half_step = gain_dn_per_electron > 0 ? 0.5 / gain_dn_per_electron : 0.0;
  return offset_dn == 0 && level_electrons + half_step < 3.0 * std::sqrt(level_electrons + read_noise_electrons * read_noise_electrons);
}

SensorView sensor_view(Chain& chain, const Report& report) {
  SensorView view;
  if (!is_point_target_sensor(chain)) return view;
  view.image = SensorImage::point_frame;
  auto value = [&](const Term& term) { return report.value(std::string(term.name)).value_or(0.0); };
  if (value(vocabulary::detector_target_streak_pixels) > 0) view.point_check = PointCheck::streak;
  else if (psf_weighted_photometry(report)) view.point_check = PointCheck::psf_photometry;
  view.level_electrons = value(vocabulary::detector_dark_rate) * value(vocabulary::detector_integration_time) +
                         value(vocabulary::detector_sky_electrons_per_pixel);
  view.read_noise_electrons = value(vocabulary::detector_read_noise_per_pixel);
  view.gain_dn_per_electron = value(vocabulary::detector_system_gain);
  return view;
}

RenderedImage render_image(Chain& chain, const Report& report, const RenderRequest& request) {
  if (is_point_target_sensor(chain)) return render_space(chain, report, request);
  return render_earth(chain, report, request);
}

void apply_frame_geometry(SpaceFrameOptions& o, const Params& values) {
  o.focal_length_m = values.maybe("--focal-length");
  o.pixel_pitch_m = values.maybe("--pixel-pitch");
  o.psf_wavelength_m = values.maybe("--psf-wavelength");
  o.gaussian_fwhm_m = values.maybe("--psf-fwhm");
  if (values.has("--psf")) o.psf = psf_model_from_string(values.text("--psf"));
}

PreviewOptions preview_options(const Params& v, SensorImage kind) {
  PreviewOptions p;
  if (kind == SensorImage::earth_scene) {  // a scene: linear between the 0.5 % and 99.5 % points
    p.stretch = Stretch::linear;
    p.low_percentile = 0.5;
    p.high_percentile = 99.5;
  } else {  // a star frame: asinh from 2σ above the background, so that the noise is dark and the stars show
    p.black_sigmas = 2.0;
  }
  if (v.has("--stretch")) p.stretch = v.text("--stretch") == "linear" ? Stretch::linear : Stretch::asinh;
  p.upscale = static_cast<int>(v.integer("--upscale"));
  return p;
}

}  // namespace radchain::render

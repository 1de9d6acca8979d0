// Closed-loop checks: detection Monte Carlo, slanted-edge MTF, flat-field SNR (checks.hpp).
#include "radchain/imaging/checks.hpp"

#include "chain_access.hpp"
#include "noise_law.hpp"
#include "space_law.hpp"

#include <boost/math/distributions/normal.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace radchain::render {

namespace {

double phi(double x) { return boost::math::cdf(boost::math::normal_distribution<double>(), x); }
double q_tail(double x) { return boost::math::cdf(boost::math::complement(boost::math::normal_distribution<double>(), x)); }

double sinc(double x) { return std::abs(x) < 1e-12 ? 1.0 : std::sin(std::numbers::pi * x) / (std::numbers::pi * x); }

int window_side(const SpaceFrameSetup& s) { return std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(s.window_pixels))))); }

// Sum of an n×n window whose top-left pixel is (x0, y0).
double window_sum(const Image& frame, int x0, int y0, int n) {
  double sum = 0;
  for (int y = y0; y < y0 + n; ++y)
    for (int x = x0; x < x0 + n; ++x) sum += frame(x, y);
  return sum;
}

// The window statistic's threshold in the frame's own units (DN or electrons): X > γσ₀ with
// X = g Σ(DN − offset) − n²(N_d + B) (ADC on) or Σe − n²(N_d + B) (off); N_d + B = dark + sky per pixel.
double value_threshold(const SpaceFrameSetup& s, int n, double electrons_above_background) {
  const double pixels = static_cast<double>(n) * n;
  const double background = pixels * (s.dark_electrons + s.sky_electrons);
  if (!s.noise.quantisation) return background + electrons_above_background;
  return pixels * s.offset_dn + (background + electrons_above_background) / s.gain_e_per_dn;
}

// Window values → electrons above the known background.
double window_electrons(const SpaceFrameSetup& s, int n, double value_sum) {
  const double pixels = static_cast<double>(n) * n;
  const double background = pixels * (s.dark_electrons + s.sky_electrons);
  if (!s.noise.quantisation) return value_sum - background;
  return s.gain_e_per_dn * (value_sum - pixels * s.offset_dn) - background;
}

struct Moments {
  double sum = 0, sum2 = 0;
  long n = 0;
  void add(double v) {
    sum += v;
    sum2 += v * v;
    ++n;
  }
  double mean() const { return sum / static_cast<double>(n); }
  double variance() const { return (sum2 - sum * sum / static_cast<double>(n)) / static_cast<double>(n - 1); }
};

// A check places its own sources: no targets, stars or flat field from the caller's frame options.
void clear_sources(SpaceFrameOptions& frame) {
  frame.targets.clear();
  frame.stars.count = 0;
  frame.flat_field_electrons = 0;
  frame.no_default_target = true;
}

}  // namespace

double Rate::binomial_sigma() const {
  const double n = static_cast<double>(std::max(trials, 1L));
  return std::max(std::sqrt(predicted * (1.0 - predicted) / n), 1.0 / n);
}
double Rate::z_predicted() const { return (measured - predicted) / binomial_sigma(); }
double Rate::z_exact() const {
  const double n = static_cast<double>(std::max(trials, 1L));
  return (measured - exact) / std::max(std::sqrt(exact * (1.0 - exact) / n), 1.0 / n);
}

bool DetectionCheck::passed(double max_z) const {
  return std::abs(detection.z_predicted()) <= max_z && std::abs(false_alarm.z_predicted()) <= max_z &&
         std::abs(rendered_signal_electrons / signal_electrons - 1.0) <= 0.01;
}

bool FlatFieldCheck::passed(double max_z) const { return std::abs(measured_snr - predicted_snr) <= max_z * snr_sigma; }

DetectionCheck check_detection(Chain& chain, const Report& report, SpaceFrameOptions frame, const DetectionCheckOptions& o) {
  if (o.trials < 10) detail::refuse(chain.sensor_file, "trials", "at least 10 frames");
  clear_sources(frame);
  frame.width = frame.height = std::max(o.frame_size, 4);
  const SpaceFrameSetup geometry = space_frame_setup(chain, report, frame);
  const int n = window_side(geometry), r = geometry.stamp_radius_px;
  // The target in the centre pixel c; its stamp must leave the corner window free.
  const int size = std::max(o.frame_size, 2 * (r + n) + 2);
  const int c = size / 2;
  frame.width = frame.height = size;
  frame.targets = {{c + 0.5, c + 0.5, geometry.limiting_magnitude}};
  const SpaceFrameSetup setup = space_frame_setup(chain, report, frame);
  const SpaceFrameRenderer renderer(setup);

  DetectionCheck check;
  check.magnitude = setup.limiting_magnitude;
  check.window = n;
  check.signal_electrons = setup.limit_signal_electrons;
  check.noise_electrons = setup.limit_noise_electrons;
  check.noise_only_electrons = std::sqrt(std::max(0.0, check.noise_electrons * check.noise_electrons - check.signal_electrons));
  check.snr = check.signal_electrons / check.noise_electrons;
  check.threshold_T = setup.snr_threshold;
  check.threshold_sigma = o.threshold_sigma;
  check.rendered_signal_electrons = setup.sources.at(0).electrons * renderer.window_fraction(0, n);
  // With the ADC the window sum takes integer values: the decision level goes to the nearest half-integer (a level
  // between two sums; where else it falls between them changes nothing measured but moves a continuous
  // prediction by up to half a step's probability), and the Gaussian prediction uses that level.
  double threshold = value_threshold(setup, n, o.threshold_sigma * check.noise_only_electrons);
  if (setup.noise.quantisation) threshold = std::floor(threshold) + 0.5;
  check.effective_threshold_sigma = window_electrons(setup, n, threshold) / check.noise_only_electrons;
  const auto [px, py] = renderer.source_pixel(0);
  const int wx = px - n / 2, wy = py - n / 2;  // target window's top-left pixel

  // Target-free windows: the tiles of the frame outside the target's stamp.
  std::vector<std::pair<int, int>> free_windows;
  for (int ty = 0; ty + n <= size; ty += n)
    for (int tx = 0; tx + n <= size; tx += n) {
      const bool clear = tx + n - 1 < px - r || tx > px + r || ty + n - 1 < py - r || ty > py + r;
      if (clear) free_windows.emplace_back(tx, ty);
    }
  if (free_windows.empty()) detail::refuse(chain.sensor_file, "frame size", "leaves no target-free window");
  if (o.false_alarm_windows_per_frame > 0 && static_cast<std::size_t>(o.false_alarm_windows_per_frame) < free_windows.size())
    free_windows.resize(static_cast<std::size_t>(o.false_alarm_windows_per_frame));

  Image image;
  for (long t = 0; t < o.trials; ++t) {
    renderer.render(o.seed + static_cast<std::uint64_t>(t), image);
    check.detection.count += window_sum(image, wx, wy, n) > threshold ? 1 : 0;
    for (const auto& [tx, ty] : free_windows) check.false_alarm.count += window_sum(image, tx, ty, n) > threshold ? 1 : 0;
  }
  check.detection.trials = o.trials;
  check.false_alarm.trials = o.trials * static_cast<long>(free_windows.size());
  check.detection.measured = static_cast<double>(check.detection.count) / static_cast<double>(check.detection.trials);
  check.false_alarm.measured = static_cast<double>(check.false_alarm.count) / static_cast<double>(check.false_alarm.trials);

  // The Gaussian criterion (Pan 2010 eq. 10 and its Fig. 5).
  const double gamma = check.effective_threshold_sigma;
  check.false_alarm.predicted = q_tail(gamma);
  check.detection.predicted = phi((check.signal_electrons - gamma * check.noise_only_electrons) / check.noise_electrons);

  // The renderer's own law of the window sums (ADC on: discrete, exact).
  if (setup.noise.quantisation) {
    const Image expected = renderer.expected_electrons();
    const double background = setup.sky_electrons + setup.dark_electrons;
    detail::DiscreteLaw target_sum, free_sum;
    const detail::DiscreteLaw free_pixel = detail::dn_law(detail::pixel_law(setup, 0.0));
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double source = std::max(0.0, static_cast<double>(expected(wx + i, wy + j)) - background);
        const detail::DiscreteLaw pixel = detail::dn_law(detail::pixel_law(setup, source));
        target_sum = (i == 0 && j == 0) ? pixel : detail::sum_law(target_sum, pixel);
        free_sum = (i == 0 && j == 0) ? free_pixel : detail::sum_law(free_sum, free_pixel);
      }
    check.detection.exact = target_sum.tail_above(threshold);
    check.false_alarm.exact = free_sum.tail_above(threshold);
  } else {
    check.detection.exact = check.false_alarm.exact = std::nan("");
  }
  return check;
}

EdgeCheck check_edge_mtf(Chain& chain, const Report& report, EarthSceneOptions scene, const EdgeCheckOptions& o) {
  if (o.output_size < 32 || o.input_oversampling < 1) detail::refuse(chain.sensor_file, "edge check", "needs ≥ 32 output pixels and oversampling ≥ 1");
  scene.noise = scene.saturation = scene.quantisation = false;
  if (!(scene.input_sampling_m > 0)) scene.input_sampling_m = 1.0;  // placeholder: only the output sampling is wanted
  const double gsd = earth_scene_setup(chain, report, scene).output_sampling_m;
  scene.output_sampling_m = gsd;
  scene.input_sampling_m = gsd / o.input_oversampling;
  const EarthSceneSetup setup = earth_scene_setup(chain, report, scene);
  const int input = (o.output_size - 1) * o.input_oversampling + 1;
  const Image map = make_edge_scene(input, input, o.edge_angle_deg, 0.2, 0.6);
  const Image image = render_earth_scene(setup, map, 1);
  // Leave out the rows next to the top and bottom (the mirror padding bends the edge there).
  const int border = 8;
  Image roi(image.width, image.height - 2 * border);
  for (int y = 0; y < roi.height; ++y)
    for (int x = 0; x < roi.width; ++x) roi(x, y) = image(x, y + border);
  const EdgeMtf measured = slanted_edge_mtf(roi, 4);

  EdgeCheck check;
  check.tolerance = o.tolerance;
  check.angle_deg = measured.angle_deg;
  const double theta = measured.angle_deg * std::numbers::pi / 180.0;
  for (std::size_t i = 0; i < measured.frequency_per_px.size(); ++i) {
    const double nu = measured.frequency_per_px[i];
    if (nu > 0.5 + 1e-9) break;
    const double ground = nu / gsd, nx = ground * std::cos(theta), ny = ground * std::sin(theta);
    // The scene map itself is the scene averaged over input pixels: its box is part of what is imaged.
    const double scene_box = std::abs(sinc(setup.input_sampling_m * nx) * sinc(setup.input_sampling_m * ny));
    const double model = system_mtf(setup, nx, ny) * scene_box;
    check.frequency_per_px.push_back(nu);
    check.measured.push_back(measured.mtf[i]);
    check.model.push_back(model);
    if (model > 1e-6) check.max_relative_error = std::max(check.max_relative_error, std::abs(measured.mtf[i] / model - 1.0));
  }
  if (!check.frequency_per_px.empty()) {
    check.mtf_at_nyquist_measured = check.measured.back();
    check.mtf_at_nyquist_model = check.model.back();
  }
  return check;
}

FlatFieldCheck check_earth_flat_field(Chain& chain, const Report& report, EarthSceneOptions scene, int size, std::uint64_t seed) {
  if (size < 8) detail::refuse(chain.sensor_file, "flat field", "needs ≥ 8 pixels");
  if (!(scene.input_sampling_m > 0)) scene.input_sampling_m = 1.0;
  const double gsd = earth_scene_setup(chain, report, scene).output_sampling_m;
  scene.output_sampling_m = scene.input_sampling_m = gsd;  // one input pixel per output pixel (b native samples of a flat map)
  const EarthSceneSetup s = earth_scene_setup(chain, report, scene);
  FlatFieldCheck check;
  const double q = s.exposure_per_dn();
  if (s.radiometry == EarthRadiometry::electrons) {
    // One flat field at the chain's own reflectance: its SNR is the chain's detector.snr (EMVA 1288 eq. 6, the
    // dark level subtracted as EMVA's μ_e is). An output pixel sums n = M b² native reads (binning, co-adds):
    // temporal variances add n times, the fixed patterns (the same in every frame) M² b² times.
    const Image a = render_earth_scene(s, make_flat_scene(size, size, s.scene_reflectance), seed);
    const double reads = s.native_sums(), frames = s.exposures, pixels = s.binning * s.binning;
    auto electrons = [&](float v) { return s.quantisation ? (v - reads * s.offset_dn) * q : static_cast<double>(v); };
    Moments m;
    for (float v : a.pixels) m.add(electrons(v));
    const double photo = s.photo_electrons(s.scene_reflectance);
    const double dark = s.dark ? s.dark_electrons : 0.0;
    check.what = "earth: flat field at the scene's reflectance";
    check.measured_label = "flat field at the scene's reflectance: measured SNR";
    check.noise_unit = "e-";
    check.samples = m.n;
    check.measured_noise = std::sqrt(m.variance());
    check.measured_snr = (m.mean() - reads * dark) / check.measured_noise;
    check.chain_snr = s.snr;
    const double temporal = (s.shot ? photo : 0.0) + dark + (s.read ? s.read_noise_e * s.read_noise_e : 0.0) +
                            (s.quantisation ? q * q / 12.0 : 0.0);
    const double fixed = (s.dark ? s.dsnu_e * s.dsnu_e : 0.0) + (s.shot ? s.prnu * s.prnu * photo * photo : 0.0);
    check.predicted_noise = std::sqrt(reads * temporal + frames * frames * pixels * fixed);
    check.predicted_snr = reads * photo / check.predicted_noise;
    // Error of mean/σ from n samples of a Gaussian: var ≈ (1 + SNR²/2) / n.
    check.snr_sigma = std::sqrt((1.0 + 0.5 * check.predicted_snr * check.predicted_snr) / static_cast<double>(check.samples));
    return check;
  }
  const double rho = s.background_reflectance > 0 ? s.background_reflectance : 0.3;
  const Image a = render_earth_scene(s, make_flat_scene(size, size, rho), seed);
  const Image b = render_earth_scene(s, make_flat_scene(size, size, rho + s.reflectance_difference), seed + 1);
  auto exposure = [&](float v) { return s.quantisation ? (v - s.offset_dn) * q : static_cast<double>(v); };
  Moments ma, mb;
  for (float v : a.pixels) ma.add(exposure(v));
  for (float v : b.pixels) mb.add(exposure(v));
  check.what = "earth: flat fields at rho0 and rho0 + drho";
  check.measured_label = "flat fields: measured SNR of Δρ";
  check.noise_unit = "J m-2";
  check.samples = ma.n;
  check.measured_noise = std::sqrt(0.5 * (ma.variance() + mb.variance()));
  check.measured_snr = (mb.mean() - ma.mean()) / check.measured_noise;
  check.chain_snr = s.snr;
  check.predicted_noise = std::sqrt((s.noise ? s.nee_J_m2 * s.nee_J_m2 : 0.0) + (s.quantisation ? q * q / 12.0 : 0.0));
  check.predicted_snr = s.exposure_per_reflectance() * s.reflectance_difference / check.predicted_noise;
  const double nn = static_cast<double>(check.samples);
  check.snr_sigma = std::sqrt(2.0 / nn + check.predicted_snr * check.predicted_snr / (4.0 * nn));
  return check;
}

double StreakCheck::snr_loss_sigma() const {
  return 2.5 / std::numbers::ln10 * std::hypot(still.sigma / still.measured, streak.sigma / streak.measured);
}

bool PsfPhotometryCheck::passed(double max_z) const {
  return std::abs(still.z()) <= max_z && (fixed_pattern || chain_agrees());
}

bool StreakCheck::passed(double max_z) const {
  return std::abs(streak.z()) <= max_z && std::abs(still.z()) <= max_z &&
         std::abs(measured_snr_loss() - predicted_snr_loss()) <= max_z * snr_loss_sigma();
}

namespace {
// PSF-weighted (matched-filter) photometry of the frame's one target on `trials` rendered frames: the weights f_i
// are the target's expected share of each pixel (from the renderer's own expected image), the estimate
// Σ f_i (e_i − B)/Σ f_i² (unbiased for the target's total), its SNR mean/σ over the frames; the renderer's law
// from the same weights and each pixel's variance; n_eff = 1/Σ f_i² (King 1983).
struct MatchedFilter {
  StreakSnr snr;
  double neff = 0, signal = 0;
  double chain_form_snr = 0;  // S/√(S + n_eff v) with the frame's n_eff and per-pixel variance v (SMTN-002's form)
};

MatchedFilter matched_filter(Chain& chain, const Report& report, const SpaceFrameOptions& frame, long trials, std::uint64_t seed) {
  const SpaceFrameSetup s = space_frame_setup(chain, report, frame);
  const SpaceFrameRenderer renderer(s);
  const Image expected = renderer.expected_electrons();
  const double background = s.sky_electrons + s.dark_electrons, total = s.sources.at(0).electrons;
  std::vector<std::size_t> index;
  std::vector<double> f;
  double sum_f2 = 0;
  for (std::size_t i = 0; i < expected.size(); ++i)
    if (const double v = (expected.pixels[i] - background) / total; v > 1e-9) {  // float: 1e-7 relative is noise
      index.push_back(i);
      f.push_back(v);
      sum_f2 += v * v;
    }
  const double floor_variance = (s.noise.shot ? s.sky_electrons : 0.0) + (s.noise.dark ? s.dark_electrons : 0.0) +
                                (s.noise.read ? s.read_noise_electrons * s.read_noise_electrons : 0.0) +
                                (s.noise.quantisation ? s.gain_e_per_dn * s.gain_e_per_dn / 12.0 : 0.0);
  double variance = 0;
  for (const double v : f) variance += v * v * ((s.noise.shot ? total * v : 0.0) + floor_variance);
  variance /= sum_f2 * sum_f2;
  MatchedFilter out;
  out.snr.predicted = total / std::sqrt(variance);
  out.neff = 1.0 / sum_f2;
  out.signal = total;
  out.chain_form_snr = total / std::sqrt((s.noise.shot ? total : 0.0) + out.neff * floor_variance);
  Moments m;
  Image image;
  for (long t = 0; t < trials; ++t) {
    renderer.render(seed + static_cast<std::uint64_t>(t), image);
    double estimate = 0;
    for (std::size_t k = 0; k < index.size(); ++k) {
      const double value = image.pixels[index[k]];
      const double electrons = s.noise.quantisation ? s.gain_e_per_dn * (value - s.offset_dn) : value;
      estimate += f[k] * (electrons - background);
    }
    m.add(estimate / sum_f2);
  }
  out.snr.measured = m.mean() / std::sqrt(m.variance());
  const double n = static_cast<double>(m.n);
  out.snr.sigma = std::sqrt(1.0 / n + out.snr.predicted * out.snr.predicted / (2.0 * n));
  return out;
}
}  // namespace

bool psf_weighted_photometry(const Report& report) {
  return detail::result(report, vocabulary::detector_psf_weighted).value_or(0.0) == 1.0;
}

PsfPhotometryCheck check_psf_photometry(Chain& chain, const Report& report, SpaceFrameOptions frame, const StreakCheckOptions& o) {
  if (o.trials < 10) detail::refuse(chain.sensor_file, "trials", "at least 10 frames");
  clear_sources(frame);
  const SpaceFrameSetup geometry = space_frame_setup(chain, report, frame);
  // Room for the PSF: 8σ of a Gaussian; 8 FWHM (1.028 λN) of an Airy core (≈ 2.5 % of a clear pupil's light lies
  // beyond: the matched filter stays unbiased, its weights are the frame's own); nothing for the pixel PSF.
  double reach_px = 0;
  if (geometry.psf == PsfModel::gaussian) reach_px = 8.0 * geometry.gaussian_fwhm_m / (2.0 * std::sqrt(2.0 * std::numbers::ln2));
  else if (geometry.psf == PsfModel::airy) reach_px = 8.0 * 1.028 * geometry.psf_wavelength_m * geometry.f_number;
  reach_px /= geometry.pixel_pitch_m;
  const int margin = static_cast<int>(std::ceil(std::min(reach_px, 2048.0))) + 4;
  frame.width = frame.height = 2 * margin;
  frame.targets = {{margin + 0.5, margin + 0.5, geometry.limiting_magnitude}};
  PsfPhotometryCheck check;
  check.trials = o.trials;
  check.magnitude = geometry.limiting_magnitude;
  check.chain_snr = geometry.limit_signal_electrons / geometry.limit_noise_electrons;
  check.chain_neff = detail::result(report, vocabulary::detector_noise_equivalent_area).value_or(std::nan(""));
  const MatchedFilter still = matched_filter(chain, report, frame, o.trials, o.seed);
  check.still = still.snr;
  check.neff = still.neff;
  check.signal_electrons = still.signal;
  check.chain_form_snr = still.chain_form_snr;
  check.fixed_pattern = detail::result(report, vocabulary::detector_prnu).value_or(0.0) > 0 ||
                        detail::result(report, vocabulary::detector_dsnu).value_or(0.0) > 0;
  return check;
}

StreakCheck check_streak(Chain& chain, const Report& report, SpaceFrameOptions frame, const StreakCheckOptions& o) {
  if (o.trials < 10) detail::refuse(chain.sensor_file, "trials", "at least 10 frames");
  clear_sources(frame);
  // Wide enough for the streak while the geometry is resolved; the frame is sized to it below.
  const double chain_streak = frame.target_streak_px.value_or(
      detail::result(report, vocabulary::detector_target_streak_pixels).value_or(0.0));
  frame.width = std::max(frame.width, static_cast<int>(std::min(std::ceil(chain_streak), 1e6)) + 1);
  const SpaceFrameSetup geometry = space_frame_setup(chain, report, frame);
  if (!(geometry.target_streak_px > 0))
    detail::refuse(chain.sensor_file, "streak", "the target does not move (detector.target_rate, sidereal tracking)");
  const double sigma = geometry.gaussian_fwhm_m / (2.0 * std::sqrt(2.0 * std::numbers::ln2)) / geometry.pixel_pitch_m;
  const int margin = static_cast<int>(std::ceil(8.0 * sigma)) + 4;
  frame.width = static_cast<int>(std::ceil(geometry.target_streak_px)) + 2 * margin;
  frame.height = o.height > 0 ? o.height : 2 * margin;
  frame.targets = {{frame.width / 2 + 0.5, frame.height / 2 + 0.5, geometry.limiting_magnitude}};

  StreakCheck check;
  check.trials = o.trials;
  check.magnitude = geometry.limiting_magnitude;
  check.streak_px = geometry.target_streak_px;
  check.chain_snr = geometry.limit_signal_electrons / geometry.limit_noise_electrons;
  // The moving target, then the same target still: matched filter from each frame's own expected light.
  frame.target_streak_px = geometry.target_streak_px;
  const MatchedFilter streak = matched_filter(chain, report, frame, o.trials, o.seed);
  check.streak = streak.snr;
  check.neff = streak.neff;
  check.signal_electrons = streak.signal;
  frame.target_streak_px = 0.0;
  const MatchedFilter still = matched_filter(chain, report, frame, o.trials, o.seed);
  check.still = still.snr;
  check.static_neff = still.neff;
  check.chain_trailing_loss = detail::result(report, vocabulary::detector_trailing_loss).value_or(std::nan(""));
  return check;
}

FlatFieldCheck check_space_flat_field(Chain& chain, const Report& report, SpaceFrameOptions frame, int size, std::uint64_t seed) {
  clear_sources(frame);
  frame.width = frame.height = std::max(size, 8);
  const SpaceFrameSetup geometry = space_frame_setup(chain, report, frame);
  const int n = window_side(geometry);
  frame.flat_field_electrons = geometry.limit_signal_electrons / (static_cast<double>(n) * n);
  const SpaceFrameSetup s = space_frame_setup(chain, report, frame);
  const Image image = SpaceFrameRenderer(s).render(seed);
  Moments m;
  for (int y = 0; y + n <= s.height; y += n)
    for (int x = 0; x + n <= s.width; x += n) m.add(window_electrons(s, n, window_sum(image, x, y, n)));
  FlatFieldCheck check;
  check.what = "space: flat field of S/n^2 electrons per pixel";
  check.samples = m.n;
  // X = the window's electrons above dark and sky: the flat field's signal plus noise.
  const double signal = static_cast<double>(n) * n * s.flat_field_electrons;
  check.measured_noise = std::sqrt(m.variance());
  check.measured_snr = m.mean() / check.measured_noise;
  check.chain_snr = s.limit_signal_electrons / s.limit_noise_electrons;
  const double pixels = static_cast<double>(n) * n;
  const double variance = (s.noise.shot ? signal + pixels * s.sky_electrons : 0.0) + (s.noise.dark ? pixels * s.dark_electrons : 0.0) +
                          (s.noise.read ? pixels * s.read_noise_electrons * s.read_noise_electrons : 0.0) +
                          (s.noise.quantisation ? pixels * s.gain_e_per_dn * s.gain_e_per_dn / 12.0 : 0.0);
  check.predicted_noise = std::sqrt(variance);
  check.predicted_snr = signal / check.predicted_noise;
  const double nn = static_cast<double>(check.samples);
  check.snr_sigma = std::sqrt(1.0 / nn + check.predicted_snr * check.predicted_snr / (2.0 * nn));
  return check;
}

}  // namespace radchain::render

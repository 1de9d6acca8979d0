// A point-target sensor's frame (space_frame.hpp): the setup from the chain, and the renderer.
#include "radchain/imaging/space_frame.hpp"

#include "chain_access.hpp"
#include "noise_law.hpp"
#include "psf_stamps.hpp"
#include "random.hpp"
#include "space_law.hpp"

#include "radchain/physics/streak.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>

namespace radchain::render {

using detail::refuse;
using detail::result;

namespace {

constexpr double arcsec_per_rad = 180.0 * 3600.0 / std::numbers::pi;

double electrons_now(const Chain& chain) {
  if (auto id = chain.results().find(vocabulary::detector_image_electrons.name)) return chain.results().value(*id);
  return chain.result(std::string(vocabulary::detector_signal_electrons.name));
}

// Sets target.magnitude for each question and puts the value back (and re-evaluates) when it goes.
class MagnitudeProbe {
 public:
  explicit MagnitudeProbe(Chain& chain) : chain_(chain) {
    try {
      saved_ = chain.parameter("target.magnitude").value();
    } catch (const std::out_of_range&) {
      refuse(chain.sensor_file, "target.magnitude",
             "a frame needs a point target with a magnitude (plugin point_magnitude); this sensor's target has none");
    }
  }
  MagnitudeProbe(const MagnitudeProbe&) = delete;
  MagnitudeProbe& operator=(const MagnitudeProbe&) = delete;
  ~MagnitudeProbe() {
    chain_.set("target.magnitude", saved_);
    try {
      chain_.evaluate();
    } catch (...) {  // it evaluated at this value before; nothing to report from a destructor
    }
  }
  double electrons(double magnitude) {
    chain_.set("target.magnitude", magnitude);
    chain_.evaluate();
    return electrons_now(chain_);
  }

 private:
  Chain& chain_;
  double saved_ = 0;
};

double limiting_magnitude(Chain& chain, const Report& report) {
  for (const auto& s : report.solves)
    if (s.spec.unknown == "target.magnitude" && s.converged) return s.value_si;
  return chain.parameter("target.magnitude").value();
}

double threshold_of(const Report& report) {
  for (const auto& s : report.solves)
    if (s.spec.unknown == "target.magnitude" && !s.binding.empty())
      if (auto t = result(report, vocabulary::criterion_threshold, s.binding)) return *t;
  if (auto t = detail::criterion_result(report, vocabulary::criterion_threshold)) return t->second;
  return std::nan("");
}

}  // namespace

std::string to_string(PsfModel model) {
  switch (model) {
    case PsfModel::pixel: return "pixel";
    case PsfModel::airy: return "airy";
    case PsfModel::gaussian: return "gaussian";
  }
  return "?";
}

std::optional<PsfModel> psf_model_from_string(const std::string& name) {
  if (name == "pixel" || name == "none") return PsfModel::pixel;
  if (name == "airy") return PsfModel::airy;
  if (name == "gaussian") return PsfModel::gaussian;
  return std::nullopt;
}

double point_source_electrons(Chain& chain, double magnitude) {
  MagnitudeProbe probe(chain);
  return probe.electrons(magnitude);
}

SpaceFrameSetup space_frame_setup(Chain& chain, const Report& report, const SpaceFrameOptions& o) {
  const std::string& file = chain.sensor_file;
  SpaceFrameSetup s;
  s.sensor_name = chain.sensor_name;
  s.sensor_file = chain.sensor_file;
  if (o.width < 1 || o.height < 1 || o.width > 32768 || o.height > 32768)
    refuse(file, "frame size " + std::to_string(o.width) + "×" + std::to_string(o.height), "must lie in 1..32768 pixels");
  s.width = o.width;
  s.height = o.height;
  if (!detail::publishes(chain, vocabulary::detector_signal_electrons) ||
      !detail::publishes(chain, vocabulary::detector_noise_electrons)) {
    const StageSlot* det = detail::find_slot(chain, "detector");
    refuse(file, "detector",
           fmt::format("a frame needs a point-target detector publishing signal and noise electrons (ccd_frame); "
                       "this sensor has {} (a pushbroom sensor renders an Earth scene instead)",
                       det ? "\"" + det->plugin + "\"" : std::string("none")));
  }
  // The frame checks measure n×n windows; a circular aperture would be compared with the wrong pixels.
  if (result(report, vocabulary::detector_aperture_radius_pixels))
    refuse(file, "detector", "photometry = \"circle\" is not measured on frames (validate counts n×n windows): use "
                             "photometry = \"window\" or \"psf\" to render or validate");
  // One frame of one exposure: co-added frames and TDI stages are not simulated here (the chain's signal would be
  // M or N_tdi exposures' worth in one frame's noise).
  for (const Term* term : {&vocabulary::detector_exposures, &vocabulary::detector_tdi_stages})
    if (const double n = result(report, *term).value_or(1.0); n != 1.0)
      refuse(file, std::string(term->name),
             fmt::format("a point-target frame is one exposure; {:g} {} are not simulated (render and validate one)", n,
                         term == &vocabulary::detector_exposures ? "co-added exposures" : "TDI stages"));
  const auto time = result(report, vocabulary::detector_integration_time);
  const auto well = result(report, vocabulary::detector_saturation_capacity);
  const auto bits = result(report, vocabulary::detector_adc_bits);
  if (!time || !well || !bits)
    refuse(file, "detector", "a frame needs a detector publishing detector.integration_time, detector.saturation_capacity and "
                             "detector.adc_bits (radchain describe <detector>)");
  s.integration_time_s = *time;
  s.full_well_electrons = *well;
  s.adc_bits = static_cast<int>(*bits);
  s.dark_electrons = result(report, vocabulary::detector_dark_rate).value_or(0.0) * s.integration_time_s;
  s.read_noise_electrons = result(report, vocabulary::detector_read_noise_per_pixel).value_or(0.0);
  s.noise = o.noise;
  s.flat_field_electrons = o.flat_field_electrons;
  if (!(o.flat_field_electrons >= 0)) refuse(file, "flat field", "must be ≥ 0 electrons");

  // Optics, geometry and PSF: options first, then what the chain publishes.
  s.aperture_m = result(report, vocabulary::optics_aperture).value_or(0.0);
  s.obscuration = o.obscuration ? *o.obscuration : result(report, vocabulary::optics_obscuration).value_or(0.0);
  s.focal_length_m = o.focal_length_m ? *o.focal_length_m : result(report, vocabulary::optics_focal_length).value_or(0.0);
  s.pixel_pitch_m = o.pixel_pitch_m ? *o.pixel_pitch_m : result(report, vocabulary::detector_pixel_pitch).value_or(0.0);
  s.f_number = s.focal_length_m > 0 && s.aperture_m > 0 ? s.focal_length_m / s.aperture_m : 0.0;
  const auto chain_wavelength = result(report, vocabulary::optics_psf_wavelength);
  // A detector that counts with a Gaussian of seeing ⊕ diffraction (emva1288) publishes it: the frame's PSF.
  const auto detector_fwhm = result(report, vocabulary::detector_psf_fwhm);
  const bool detector_gaussian = detector_fwhm && *detector_fwhm > 0;
  const auto chain_fwhm = detector_gaussian ? detector_fwhm : result(report, vocabulary::optics_gaussian_fwhm);
  if (o.psf) s.psf = *o.psf;
  else if (detector_gaussian && !o.psf_wavelength_m) s.psf = PsfModel::gaussian;
  else if (o.psf_wavelength_m || chain_wavelength) s.psf = PsfModel::airy;
  else if (o.gaussian_fwhm_m || chain_fwhm) s.psf = PsfModel::gaussian;
  else s.psf = PsfModel::pixel;
  if (s.psf != PsfModel::pixel && !(s.pixel_pitch_m > 0))
    refuse(file, "pixel pitch", "a " + to_string(s.psf) + " PSF needs the pixel pitch (detector.pixel_pitch, or the render option)");
  // Detector pixels lie between a fraction of a micrometre and millimetres; "033 zm" (render_options_fuzz) made a
  // PSF 6e14 pixels wide.
  if (s.pixel_pitch_m > 0 && !(s.pixel_pitch_m >= 1e-7 && s.pixel_pitch_m <= 1e-2))
    refuse(file, "pixel pitch", fmt::format("{:.4g} m: a detector pixel lies between 0.1 um and 10 mm", s.pixel_pitch_m));
  if (s.psf == PsfModel::airy) {
    s.psf_wavelength_m = o.psf_wavelength_m ? *o.psf_wavelength_m : chain_wavelength.value_or(0.0);
    if (!(s.psf_wavelength_m > 0)) refuse(file, "PSF wavelength", "an Airy PSF needs a wavelength (optics.psf_wavelength, or the render option)");
    if (!(s.f_number > 0)) refuse(file, "focal length", "an Airy PSF needs the focal length (optics.focal_length, or the render option)");
    if (!(s.obscuration >= 0 && s.obscuration < 1)) refuse(file, "obscuration", "must lie in [0, 1)");
  }
  if (s.psf == PsfModel::gaussian) {
    s.gaussian_fwhm_m = o.gaussian_fwhm_m ? *o.gaussian_fwhm_m : chain_fwhm.value_or(0.0);
    if (!(s.gaussian_fwhm_m > 0)) refuse(file, "PSF FWHM", "a Gaussian PSF needs its FWHM (optics.gaussian_fwhm, or the render option)");
  }
  if (o.oversampling < 1 || o.oversampling > 64) refuse(file, "oversampling", "must lie in 1..64 phases per pixel");
  s.oversampling = s.psf == PsfModel::pixel ? 1 : o.oversampling;
  detail::PsfSpec spec{s.psf, s.pixel_pitch_m, s.psf_wavelength_m, s.f_number, s.obscuration, s.gaussian_fwhm_m, s.oversampling, 0};
  s.stamp_radius_px = o.stamp_radius_px ? std::clamp(*o.stamp_radius_px, 0, 256) : detail::default_stamp_radius(spec);
  if (s.psf == PsfModel::pixel) s.stamp_radius_px = 0;

  // Streaks of a moving target (sidereal tracking) or of the stars (rate tracking).
  s.target_streak_px = o.target_streak_px ? *o.target_streak_px
                                          : result(report, vocabulary::detector_target_streak_pixels).value_or(0.0);
  s.star_streak_px = o.star_streak_px ? *o.star_streak_px : result(report, vocabulary::detector_star_streak_pixels).value_or(0.0);
  if (!(s.target_streak_px >= 0 && s.star_streak_px >= 0 && s.target_streak_px < 1e6 && s.star_streak_px < 1e6))
    refuse(file, "streak", "must lie in 0..1e6 pixels");
  const double longest = std::max(s.target_streak_px, s.star_streak_px);
  if (longest > 0) {
    if (s.psf != PsfModel::gaussian)
      refuse(file, "streak", "a streak is drawn with a Gaussian PSF (seeing, or the optics' psf = \"gaussian\"); this frame's PSF is " +
                                 to_string(s.psf));
    if (longest > s.width)
      refuse(file, "streak", fmt::format("the streak of {:.1f} pixels is longer than the frame ({} pixels wide): give a wider frame",
                                         longest, s.width));
  }

  // Detector background and ADC.
  s.sky_electrons = o.sky_electrons_per_pixel ? *o.sky_electrons_per_pixel
                                              : result(report, vocabulary::detector_sky_electrons_per_pixel).value_or(0.0);
  if (!(s.sky_electrons >= 0)) refuse(file, "sky", "must be ≥ 0 electrons per pixel");
  // A background that fills the well leaves a frame of saturated pixels with nothing to see: no frame to write.
  if (s.sky_electrons + s.dark_electrons >= s.full_well_electrons)
    refuse(file, "sky", fmt::format("{:.4g} e- of sky and dark current per pixel fill the {:.4g} e- well: every pixel "
                                    "saturates and the frame shows nothing",
                                    s.sky_electrons + s.dark_electrons, s.full_well_electrons));
  // Each pixel's counts are drawn from their exact law, tabulated over ±12 σ: beyond ~1e11 e- that table outgrows
  // the sampler (and any real well).
  constexpr double sampled_electrons_max = 1e11;
  if (s.sky_electrons + s.dark_electrons + s.flat_field_electrons > sampled_electrons_max)
    refuse(file, "sky", fmt::format("{:.4g} e- per pixel of sky, dark and flat field: the renderer samples up to {:.0e} e- "
                                    "per pixel", s.sky_electrons + s.dark_electrons + s.flat_field_electrons,
                                    sampled_electrons_max));
  // The chain's own system gain K (DN/e-, a datasheet detector) when it publishes one, else full well / 2^bits.
  const auto system_gain = result(report, vocabulary::detector_system_gain);
  s.gain_e_per_dn = o.gain_e_per_dn ? *o.gain_e_per_dn
                    : system_gain   ? 1.0 / *system_gain
                                    : s.full_well_electrons / std::exp2(s.adc_bits);
  if (!(s.gain_e_per_dn > 0)) refuse(file, "gain", "must be > 0 e-/DN");
  s.offset_dn = o.offset_dn;

  // The chain's answer.
  s.limiting_magnitude = limiting_magnitude(chain, report);
  s.snr_threshold = threshold_of(report);
  s.limit_signal_electrons = result(report, vocabulary::detector_signal_electrons).value_or(std::nan(""));
  s.limit_noise_electrons = result(report, vocabulary::detector_noise_electrons).value_or(std::nan(""));
  s.window_pixels = static_cast<int>(std::lround(result(report, vocabulary::detector_window_pixel_count).value_or(1.0)));
  s.chain_ensquared_energy = result(report, vocabulary::detector_ensquared_energy).value_or(1.0);

  // Sources: electrons from the chain at each magnitude.
  MagnitudeProbe probe(chain);
  std::vector<PointTarget> targets = o.targets;
  if (targets.empty() && !o.no_default_target && o.flat_field_electrons == 0.0)
    targets.push_back({std::floor(s.width / 2.0) + 0.5, std::floor(s.height / 2.0) + 0.5, s.limiting_magnitude});
  std::map<double, double> electrons_at;  // one evaluation per distinct magnitude
  auto electrons = [&](double m) {
    auto it = electrons_at.find(m);
    if (it == electrons_at.end()) it = electrons_at.emplace(m, probe.electrons(m)).first;
    return it->second;
  };
  for (const auto& t : targets) {
    const double m = std::isnan(t.magnitude) ? s.limiting_magnitude : t.magnitude;
    if (!(std::abs(t.x_px) < 1e7 && std::abs(t.y_px) < 1e7) || !std::isfinite(m))
      refuse(file, "target", "position (within 1e7 pixels) and magnitude must be finite numbers");
    s.sources.push_back({t.x_px, t.y_px, m, electrons(m), true});
  }
  const StarField& f = o.stars;
  if (f.count < 0 || f.count > 1000000) refuse(file, "stars", "the star count must lie in 0..1000000");
  s.star_seed = f.seed;
  if (f.count > 0) {
    const double faint = f.faint_magnitude.value_or(s.limiting_magnitude + 1.0);
    if (!(faint > f.bright_magnitude)) refuse(file, "stars", "the faint magnitude must exceed the bright one");
    if (!(f.slope > 0)) refuse(file, "stars", "the slope d log N / dm must be > 0");
    detail::Random random(f.seed);
    const double span = std::pow(10.0, f.slope * (faint - f.bright_magnitude)) - 1.0;
    for (int i = 0; i < f.count; ++i) {
      const double x = random.uniform() * s.width, y = random.uniform() * s.height;
      // Inverse of the truncated cumulative N(<m) ∝ 10^{slope·m}.
      const double m = f.bright_magnitude + std::log10(1.0 + random.uniform() * span) / f.slope;
      s.sources.push_back({x, y, m, probe.electrons(m), false});
    }
  }
  return s;
}

// ---- The renderer ---------------------------------------------------------------------------------------

struct SpaceFrameRenderer::Impl {
  SpaceFrameSetup s;
  detail::PsfStamps stamps;
  std::vector<std::pair<int, int>> pixel, phase;    // per source
  std::vector<std::size_t> source_index;            // pixels that source light reaches, ascending
  std::vector<double> source_electrons;             // their expected source electrons
  detail::PixelLaw background_law;                  // a pixel without source light
  detail::AliasTable background_dn;                 // its DN (ADC on)
  detail::AliasTable background_counts;             // its Poisson counts

  // A pixel with source light x: Poisson(background) + Poisson(x) is Poisson(background + x), so the background
  // counts come from the table and only the source's share is drawn term by term.
  float draw(double source, detail::Random& random) const {
    const detail::PixelLaw& l = background_law;
    double e = static_cast<double>(background_counts(static_cast<std::uint32_t>(random.bits()))) + l.constant;
    if (s.noise.shot) e += static_cast<double>(random.poisson(source));
    else e += source;
    e = std::min(e, l.full_well);
    if (l.read_sigma > 0) e += l.read_sigma * random.normal();
    if (!s.noise.quantisation) return static_cast<float>(e);
    return static_cast<float>(std::clamp(std::floor(e / l.gain + l.offset_dn + 0.5), 0.0, l.max_dn));
  }
};

namespace {

// A streak: the Gaussian PSF smeared along +x over `length` pixels, centred on the source's exact position, per
// pixel s_i g_j (physics/streak.hpp: exact pixel integrals, no sub-pixel rounding).
void add_streak(const RenderedSource& src, double length, const SpaceFrameSetup& s, std::map<std::size_t, double>& light) {
  const double sigma = s.gaussian_fwhm_m / (2.0 * std::sqrt(2.0 * std::numbers::ln2)) / s.pixel_pitch_m;
  const int cx = static_cast<int>(std::floor(src.x_px)), cy = static_cast<int>(std::floor(src.y_px));
  const double ox = src.x_px - (cx + 0.5), oy = src.y_px - (cy + 0.5);
  const int across = static_cast<int>(std::ceil(6.0 * sigma)) + 1, along = static_cast<int>(std::ceil(6.0 * sigma + 0.5 * length)) + 1;
  for (int j = -across; j <= across; ++j) {
    const int y = cy + j;
    if (y < 0 || y >= s.height) continue;
    const double column = physics::gaussian_pixel_fraction(j, sigma, oy);
    for (int i = -along; i <= along; ++i) {
      const int x = cx + i;
      if (x < 0 || x >= s.width) continue;
      const double v = src.electrons * column * physics::streaked_gaussian_pixel_fraction(i, sigma, length, ox);
      if (v != 0.0) light[static_cast<std::size_t>(y) * static_cast<std::size_t>(s.width) + static_cast<std::size_t>(x)] += v;
    }
  }
}

}  // namespace

SpaceFrameRenderer::SpaceFrameRenderer(SpaceFrameSetup setup) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.s = std::move(setup);
  const SpaceFrameSetup& s = m.s;
  m.stamps = detail::PsfStamps(detail::PsfSpec{s.psf, s.pixel_pitch_m, s.psf_wavelength_m, s.f_number, s.obscuration,
                                               s.gaussian_fwhm_m, s.oversampling, s.stamp_radius_px});
  // Expected source light, accumulated densely once, kept sparsely for the frames.
  std::map<std::size_t, double> light;
  const int r = m.stamps.radius(), n = m.stamps.side();
  for (const auto& src : s.sources) {
    int px = 0, py = 0, fx = 0, fy = 0;
    m.stamps.locate(src.x_px, px, fx);
    m.stamps.locate(src.y_px, py, fy);
    m.pixel.emplace_back(px, py);
    m.phase.emplace_back(fx, fy);
    if (const double streak = src.target ? s.target_streak_px : s.star_streak_px; streak > 0) {
      add_streak(src, streak, s, light);
      continue;
    }
    const double* stamp = m.stamps.stamp(fx, fy);
    for (int j = -r; j <= r; ++j) {
      const int y = py + j;
      if (y < 0 || y >= s.height) continue;
      for (int i = -r; i <= r; ++i) {
        const int x = px + i;
        if (x < 0 || x >= s.width) continue;
        const double v = src.electrons * stamp[(j + r) * n + (i + r)];
        if (v != 0.0) light[static_cast<std::size_t>(y) * static_cast<std::size_t>(s.width) + static_cast<std::size_t>(x)] += v;
      }
    }
  }
  for (const auto& [index, electrons] : light) {
    m.source_index.push_back(index);
    m.source_electrons.push_back(electrons);
  }
  m.background_law = detail::pixel_law(s, 0.0);
  m.background_counts = detail::AliasTable(detail::poisson_law(m.background_law.poisson_mean));
  if (s.noise.quantisation) m.background_dn = detail::AliasTable(detail::dn_law(m.background_law));
}

SpaceFrameRenderer::~SpaceFrameRenderer() = default;
SpaceFrameRenderer::SpaceFrameRenderer(SpaceFrameRenderer&&) noexcept = default;
SpaceFrameRenderer& SpaceFrameRenderer::operator=(SpaceFrameRenderer&&) noexcept = default;

const SpaceFrameSetup& SpaceFrameRenderer::setup() const { return impl_->s; }

Image SpaceFrameRenderer::render(std::uint64_t seed) const {
  Image frame;
  render(seed, frame);
  return frame;
}

void SpaceFrameRenderer::render(std::uint64_t seed, Image& frame) const {
  const Impl& m = *impl_;
  if (frame.width != m.s.width || frame.height != m.s.height) frame = Image(m.s.width, m.s.height);
  detail::Random random(seed);
  float* out = frame.pixels.data();
  const std::size_t count = frame.size();
  // Every pixel from the background law, 32 random bits each (two pixels per 64-bit draw); then the pixels with
  // source light redrawn in full.
  if (m.s.noise.quantisation) {
    const detail::AliasTable& table = m.background_dn;
    constexpr std::size_t chunk = 2048;  // random words per pass (16 kB: stays in L1)
    std::uint64_t bits[chunk];
    for (std::size_t start = 0; start < count; start += 2 * chunk) {
      const std::size_t pixels = std::min(2 * chunk, count - start), words = (pixels + 1) / 2;
      random.fill(bits, words);
      float* o = out + start;
      for (std::size_t w = 0; w < pixels / 2; ++w) {
        o[2 * w] = table(static_cast<std::uint32_t>(bits[w]));
        o[2 * w + 1] = table(static_cast<std::uint32_t>(bits[w] >> 32));
      }
      if (pixels % 2 == 1) o[pixels - 1] = table(static_cast<std::uint32_t>(bits[words - 1]));  // the low half
    }
  } else {
    const detail::PixelLaw& l = m.background_law;
    for (std::size_t i = 0; i < count; ++i) {
      double e = std::min(static_cast<double>(m.background_counts(static_cast<std::uint32_t>(random.bits()))) + l.constant, l.full_well);
      if (l.read_sigma > 0) e += l.read_sigma * random.normal();
      out[i] = static_cast<float>(e);
    }
  }
  for (std::size_t k = 0; k < m.source_index.size(); ++k) out[m.source_index[k]] = m.draw(m.source_electrons[k], random);
}

Image SpaceFrameRenderer::expected_electrons() const {
  const Impl& m = *impl_;
  Image image(m.s.width, m.s.height, static_cast<float>(m.s.sky_electrons + m.s.flat_field_electrons + m.s.dark_electrons));
  for (std::size_t k = 0; k < m.source_index.size(); ++k) image.pixels[m.source_index[k]] += static_cast<float>(m.source_electrons[k]);
  return image;
}

double SpaceFrameRenderer::window_fraction(std::size_t source, int window) const {
  const Impl& m = *impl_;
  if (source >= m.phase.size()) throw std::out_of_range("window_fraction: no such source");
  if ((m.s.sources[source].target ? m.s.target_streak_px : m.s.star_streak_px) > 0)
    throw std::logic_error("window_fraction: a streak has no square-window fraction");
  const double* stamp = m.stamps.stamp(m.phase[source].first, m.phase[source].second);
  const int r = m.stamps.radius(), n = m.stamps.side();
  const int lo = -(window / 2), hi = lo + window - 1;
  double sum = 0;
  for (int j = std::max(lo, -r); j <= std::min(hi, r); ++j)
    for (int i = std::max(lo, -r); i <= std::min(hi, r); ++i) sum += stamp[(j + r) * n + (i + r)];
  return sum;
}

std::pair<int, int> SpaceFrameRenderer::source_pixel(std::size_t source) const { return impl_->pixel.at(source); }

std::string SpaceFrameRenderer::unit() const { return impl_->s.noise.quantisation ? "adu" : "electron"; }

Header SpaceFrameRenderer::header(std::uint64_t seed) const {
  const SpaceFrameSetup& s = impl_->s;
  Header h;
  auto number = [&](const std::string& key, double value, const std::string& comment) {
    if (std::isfinite(value)) h.push_back({key, value, comment});
  };
  auto integer = [&](const std::string& key, std::int64_t value, const std::string& comment) { h.push_back({key, value, comment}); };
  auto text = [&](const std::string& key, const std::string& value, const std::string& comment) { h.push_back({key, value, comment}); };
  auto flag = [&](const std::string& key, bool value, const std::string& comment) { h.push_back({key, value, comment}); };
  auto file_name = [](const std::string& path) { return path.substr(path.find_last_of('/') == std::string::npos ? 0 : path.find_last_of('/') + 1); };
  text("ORIGIN", "radchain", "radchain render: point-target frame");
  text("INSTRUME", s.sensor_name, "sensor");
  text("SENSFILE", file_name(s.sensor_file), "sensor file");
  text("BUNIT", unit(), s.noise.quantisation ? "ADC counts" : "electrons");
  number("EXPTIME", s.integration_time_s, "[s] integration time");
  if (s.noise.quantisation) {
    number("GAIN", s.gain_e_per_dn, "[e-/adu] full well / 2^bits");
    number("OFFSET", s.offset_dn, "[adu] ADC pedestal");
    integer("ADCBITS", s.adc_bits, "ADC resolution");
    number("SATURATE", std::exp2(s.adc_bits) - 1.0, "[adu] largest value");
  }
  number("FULLWELL", s.full_well_electrons, "[e-] well depth");
  number("RDNOISE", s.read_noise_electrons, "[e-] read noise rms");
  number("DARKCUR", s.integration_time_s > 0 ? s.dark_electrons / s.integration_time_s : 0.0, "[e-/s] dark rate per pixel");
  number("DARK", s.dark_electrons, "[e-] dark electrons per pixel and frame");
  number("SKY", s.sky_electrons, "[e-] sky electrons per pixel and frame");
  if (s.flat_field_electrons > 0) number("FLAT", s.flat_field_electrons, "[e-] flat-field signal per pixel");
  if (s.pixel_pitch_m > 0) number("PIXSIZE", s.pixel_pitch_m * 1e6, "[um] pixel pitch");
  if (s.focal_length_m > 0) number("FOCALLEN", s.focal_length_m * 1e3, "[mm] focal length");
  if (s.aperture_m > 0) number("APERTURE", s.aperture_m * 1e3, "[mm] entrance pupil");
  if (s.f_number > 0) number("FNUMBER", s.f_number, "f'/D");
  number("OBSCUR", s.obscuration, "central obscuration (linear)");
  if (s.pixel_pitch_m > 0 && s.focal_length_m > 0)
    number("PIXSCALE", s.pixel_pitch_m / s.focal_length_m * arcsec_per_rad, "[arcsec] per pixel");
  text("PSF", to_string(s.psf), "pixel: whole image in one pixel (Pan 2010)");
  if (s.psf == PsfModel::airy) number("PSFWAVE", s.psf_wavelength_m * 1e6, "[um] Airy wavelength");
  if (s.psf == PsfModel::gaussian) number("PSFFWHM", s.gaussian_fwhm_m * 1e6, "[um] Gaussian FWHM");
  integer("PSFOVER", s.oversampling, "PSF phases per pixel");
  integer("PSFRAD", s.stamp_radius_px, "[pixel] PSF stamp half-size");
  if (s.target_streak_px > 0) number("STREAK", s.target_streak_px, "[pixel] target streak along +x (sidereal tracking)");
  if (s.star_streak_px > 0) number("STARSTRK", s.star_streak_px, "[pixel] star streaks along +x (rate tracking)");
  number("LIMMAG", s.limiting_magnitude, "limiting magnitude (solved)");
  number("SNRTHR", s.snr_threshold, "detection threshold T on S/n");
  number("SIGLIM", s.limit_signal_electrons, "[e-] chain signal at LIMMAG (window)");
  number("NOISELIM", s.limit_noise_electrons, "[e-] chain noise at LIMMAG (window)");
  integer("WINDOW", s.window_pixels, "detection window pixels (n^2)");
  integer("SEED", static_cast<std::int64_t>(seed), "noise seed (mt19937_64)");
  integer("NTARGET", static_cast<std::int64_t>(std::count_if(s.sources.begin(), s.sources.end(), [](const auto& x) { return x.target; })), "point targets");
  integer("NSTARS", static_cast<std::int64_t>(std::count_if(s.sources.begin(), s.sources.end(), [](const auto& x) { return !x.target; })), "field stars");
  if (s.star_seed != 0) integer("STARSEED", static_cast<std::int64_t>(s.star_seed), "star field seed");
  flag("NSHOT", s.noise.shot, "photon shot noise simulated");
  flag("NDARK", s.noise.dark, "dark shot noise simulated");
  flag("NREAD", s.noise.read, "read noise simulated");
  flag("NSAT", s.noise.saturation, "full-well clipping simulated");
  flag("NADC", s.noise.quantisation, "ADC quantisation simulated");
  int shown = 0;
  for (const auto& src : s.sources) {
    if (!src.target || shown == 9) continue;
    const std::string k = "T" + std::to_string(++shown);
    number(k + "X", src.x_px, "[pixel] target x (centres at i+0.5)");
    number(k + "Y", src.y_px, "[pixel] target y (row 0 = top)");
    number(k + "MAG", src.magnitude, "target magnitude");
    number(k + "E", src.electrons, "[e-] target image electrons");
  }
  return h;
}

}  // namespace radchain::render

// A pushbroom sensor's image of a reflectance map (earth_scene.hpp).
#include "radchain/imaging/earth_scene.hpp"

#include "chain_access.hpp"
#include "fftw.hpp"
#include "radchain/mtf_curves.hpp"
#include "radchain/physics/mtf.hpp"
#include "random.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace radchain::render {

using detail::refuse;
using detail::result;

namespace {

// Half-sample symmetric reflection of an index into [0, n): … 1 0 | 0 1 … n−1 | n−1 n−2 …
std::int64_t reflect(std::int64_t i, std::int64_t n) {
  const std::int64_t period = 2 * n;
  i %= period;
  if (i < 0) i += period;
  return i < n ? i : period - 1 - i;
}

// Keys' cubic convolution kernel, a = −½ (Keys 1981, IEEE Trans. ASSP 29, 1153).
double keys(double x) {
  x = std::abs(x);
  if (x < 1) return (1.5 * x - 2.5) * x * x + 1.0;
  if (x < 2) return ((-0.5 * x + 2.5) * x - 4.0) * x + 2.0;
  return 0.0;
}

double optics_otf(const EarthSceneSetup& s, double nu_focal) {
  switch (s.optics) {
    case OpticsMtf::diffraction: return physics::diffraction_mtf(nu_focal, s.wavelength_m, s.f_number, s.obscuration);
    case OpticsMtf::kolobrodov_eq7: return physics::kolobrodov_linear_mtf(nu_focal, s.wavelength_m, s.f_number, s.eta);
    case OpticsMtf::budget: {
      // The budget's radially symmetric terms (physics/mtf_budget.hpp); smear and TDI act along track only.
      const physics::MtfBudget& b = s.budget;
      return physics::diffraction_mtf(nu_focal, b.wavelength_m, b.f_number, b.obscuration) *
             physics::wavefront_error_mtf(nu_focal, b.wavelength_m, b.f_number, b.wavefront_error_waves) *
             physics::jitter_mtf(nu_focal, b.jitter_rms_m) * physics::diffusion_mtf(nu_focal, b.diffusion_rms_m) *
             physics::turbulence_mtf(nu_focal, b.wavelength_m, b.focal_length_m, b.fried_parameter_m);
    }
    case OpticsMtf::none: break;
  }
  return 1.0;
}

// Across track (x): the element aperture. Along track (y): also the budget's linear smear and TDI
// synchronisation, signed (the OTF of a box and of N shifted copies: physics::sinc_pi, shifted_copies_otf).
double detector_otf_x(const EarthSceneSetup& s, double nu_focal) {
  return s.detector_mtf ? physics::sinc_pi(s.element_m * nu_focal) : 1.0;
}

double detector_otf_y(const EarthSceneSetup& s, double nu_focal) {
  double otf = detector_otf_x(s, nu_focal);
  if (s.optics == OpticsMtf::budget) {
    const physics::MtfBudget& b = s.budget;
    otf *= physics::sinc_pi(b.smear_m * nu_focal) * physics::shifted_copies_otf(nu_focal, b.tdi_stages, b.tdi_mismatch * b.pitch_m);
  }
  return otf;
}

// b native samples δ apart summed into one binned pixel: their array factor sin(π b δ ν)/(b sin(π δ ν)), δ the
// native sampling on the focal plane (the pitch p unless an output sampling was given); the element's sinc is in
// detector_otf_*. Not applied to the native field: the binning sum does it.
double binning_otf(const EarthSceneSetup& s, double nu_focal) {
  return physics::shifted_copies_otf(nu_focal, s.binning, s.native_sampling_m() * s.ground_to_focal());
}

// Native samples per input pixel.
double sampling_ratio(const EarthSceneSetup& s) { return s.native_sampling_m() / s.input_sampling_m; }

}  // namespace

std::string to_string(OpticsMtf model) {
  switch (model) {
    case OpticsMtf::diffraction: return "diffraction";
    case OpticsMtf::kolobrodov_eq7: return "eq7";
    case OpticsMtf::budget: return "budget";
    case OpticsMtf::none: return "none";
  }
  return "?";
}

std::optional<OpticsMtf> optics_mtf_from_string(const std::string& name) {
  if (name == "diffraction") return OpticsMtf::diffraction;
  if (name == "eq7" || name == "kolobrodov_eq7") return OpticsMtf::kolobrodov_eq7;
  if (name == "budget") return OpticsMtf::budget;
  if (name == "none") return OpticsMtf::none;
  return std::nullopt;
}

double EarthSceneSetup::exposure_per_dn() const {
  return radiometry == EarthRadiometry::electrons ? 1.0 / gain_dn_per_e : saturation_J_m2 / std::exp2(adc_bits);
}

EarthSceneSetup earth_scene_setup(Chain& chain, const Report& report, const EarthSceneOptions& o) {
  const std::string& file = chain.sensor_file;
  EarthSceneSetup s;
  // A datasheet detector counts electrons of a reflectance; a ccd_line design has a noise-equivalent exposure.
  s.radiometry = !result(report, vocabulary::detector_nee_working) && result(report, vocabulary::detector_system_gain) &&
                         result(report, vocabulary::target_reflectance)
                     ? EarthRadiometry::electrons
                     : EarthRadiometry::exposure;
  const bool electrons = s.radiometry == EarthRadiometry::electrons;
  auto need = [&](const Term& term) {
    const auto v = result(report, term);
    if (!v)
      refuse(file, std::string(term.name),
             "an Earth scene needs a pushbroom chain (platform, telescope with a focal length, a ccd_line detector, or "
             "an emva1288 detector on a reflectance_ground target, a ground_resolution or gsd_requirement criterion) "
             "publishing this result; this sensor does not");
    return *v;
  };
  s.sensor_name = chain.sensor_name;
  s.sensor_file = chain.sensor_file;
  s.altitude_m = need(vocabulary::platform_altitude);
  s.focal_length_m = need(vocabulary::optics_focal_length);
  s.f_number = need(vocabulary::optics_f_number);
  s.aperture_m = need(vocabulary::optics_aperture);
  s.obscuration = result(report, vocabulary::optics_obscuration).value_or(0.0);
  s.element_m = electrons ? result(report, vocabulary::detector_element_size_for_mtf).value_or(need(vocabulary::detector_pixel_pitch))
                          : need(vocabulary::detector_element_size_for_mtf);
  s.pitch_m = result(report, vocabulary::detector_pixel_pitch).value_or(s.element_m);
  s.integration_time_s = need(vocabulary::detector_integration_time);
  s.snr = need(vocabulary::detector_snr);
  if (electrons) {
    // The chain counts an output pixel: b×b native pixels over M frames. The scene is drawn per native pixel and
    // frame (render_earth_scene sums them), so the chain's per-pixel terms are taken back to one native pixel.
    auto whole = [&](const Term& term, double lo, double hi) {
      const double v = result(report, term).value_or(1.0);
      if (!(v >= lo && v <= hi) || v != std::floor(v))
        refuse(file, std::string(term.name), fmt::format("{:g} is not a whole number in [{:g}, {:g}]", v, lo, hi));
      return static_cast<int>(v);
    };
    s.binning = whole(vocabulary::detector_binning, 1, 64);
    s.exposures = whole(vocabulary::detector_exposures, 1, 1e6);
    s.scene_reflectance = need(vocabulary::target_reflectance);
    if (!(s.scene_reflectance > 0))
      refuse(file, std::string(vocabulary::target_reflectance.name), "the scene's reflectance must be > 0 to give electrons per reflectance");
    const double reads = s.native_sums();
    const double path = result(report, vocabulary::detector_path_radiance_electrons).value_or(0.0);
    s.path_electrons = path / reads;
    s.electrons_per_reflectance = (need(vocabulary::detector_signal_electrons) - path) / s.scene_reflectance / reads;
    // detector.dark_rate is b² μ_I and detector.read_noise_per_pixel b σ_d per binned pixel (emva1288).
    s.dark_electrons = need(vocabulary::detector_dark_rate) / (s.binning * s.binning) * s.integration_time_s *
                       result(report, vocabulary::detector_tdi_stages).value_or(1.0);
    s.read_noise_e = need(vocabulary::detector_read_noise_per_pixel) / s.binning;
    s.prnu = result(report, vocabulary::detector_prnu).value_or(0.0);
    s.dsnu_e = result(report, vocabulary::detector_dsnu).value_or(0.0);
    s.gain_dn_per_e = need(vocabulary::detector_system_gain);
    s.capacity_e = need(vocabulary::detector_saturation_capacity);
    s.background_reflectance = s.scene_reflectance;
  } else {
    s.reflectance_difference = need(vocabulary::target_reflectance_difference);
    s.irradiance_per_reflectance_W_m2 = need(vocabulary::detector_signal_irradiance) / s.reflectance_difference;
    s.nee_J_m2 = need(vocabulary::detector_nee_working);
  }
  if (auto g = detail::criterion_result(report, vocabulary::criterion_ground_element)) s.ground_element_m = g->second;
  if (auto g = detail::criterion_result(report, vocabulary::criterion_gsd_nadir)) s.pixel_gsd_m = g->second;

  s.optics = o.optics.value_or(has_mtf_budget(report) ? OpticsMtf::budget : OpticsMtf::diffraction);
  if (s.optics == OpticsMtf::budget) {
    if (!has_mtf_budget(report)) refuse(file, "optics MTF", "\"budget\" needs a chain with an MTF budget (a giqe criterion)");
    s.budget = mtf_budget(report);
    if (o.wavelength_m) s.budget.wavelength_m = *o.wavelength_m;
  }
  const auto quality = detail::criterion_result(report, vocabulary::criterion_required_quality);
  if (quality) s.eta = quality->second;
  if (o.wavelength_m) s.wavelength_m = *o.wavelength_m;
  else if (has_mtf_budget(report)) s.wavelength_m = mtf_budget(report).wavelength_m;
  else if (quality && result(report, vocabulary::criterion_wavelength, quality->first))
    s.wavelength_m = *result(report, vocabulary::criterion_wavelength, quality->first);
  else {
    const auto lo = result(report, vocabulary::detector_band_min), hi = result(report, vocabulary::detector_band_max);
    if (!lo || !hi) refuse(file, "wavelength", "give the MTF wavelength as an option (the sensor has no mtf_match criterion or band)");
    s.wavelength_m = 0.5 * (*lo + *hi);
  }
  if (s.optics == OpticsMtf::kolobrodov_eq7 && !quality)
    refuse(file, "optics MTF", "\"eq7\" needs the design quality η of an mtf_match criterion");
  s.detector_mtf = o.detector_mtf;
  if (!(s.wavelength_m > 0)) refuse(file, "wavelength", "must be > 0");

  if (electrons) {
    if (o.saturation_exposure_J_m2) refuse(file, "saturation exposure", "a datasheet detector saturates at its detector.saturation_capacity");
  } else {
    if (o.saturation_exposure_J_m2) s.saturation_J_m2 = *o.saturation_exposure_J_m2;
    else if (auto h = result(report, vocabulary::detector_saturation_exposure))
      s.saturation_J_m2 = *h * result(report, vocabulary::detector_utilisation_ratio).value_or(1.0);  // H_m k_i/k_c, as H_nr
    if (auto rho = result(report, vocabulary::target_background_reflectance)) s.background_reflectance = *rho;
    else if (auto m = result(report, vocabulary::target_background_exitance), e = result(report, vocabulary::atmosphere_ground_irradiance); m && e && *e > 0)
      s.background_reflectance = *m / *e;
  }

  if (!(o.input_sampling_m > 0)) refuse(file, "input sampling", "give the ground size of one input pixel (> 0 m)");
  s.input_sampling_m = o.input_sampling_m;
  // One output pixel per detector sample: the pixel-pitch GSD h p / f' (of a binned pixel: b h p / f'), else
  // Kolobrodov's element V_s h / f'.
  s.output_sampling_m = o.output_sampling_m ? *o.output_sampling_m
                                            : s.binning * (s.pixel_gsd_m > 0 ? s.pixel_gsd_m : s.ground_element_m);
  if (!(s.output_sampling_m > 0))
    refuse(file, "output sampling",
           "the sensor publishes neither criteria.<name>.gsd_nadir nor criteria.<name>.ground_element: give the output sampling");
  // An output pixel a thousand times finer or coarser than the detector's sample is a unit slip (1e-300 m gave an
  // image of NaN), not a rendering.
  const double design_m = s.binning * (s.pixel_gsd_m > 0 ? s.pixel_gsd_m : s.ground_element_m);
  if (design_m > 0 && !(s.output_sampling_m >= 1e-3 * design_m && s.output_sampling_m <= 1e3 * design_m))
    refuse(file, "output sampling", fmt::format("{:.4g} m is not within a factor 1000 of the detector sample's {:.4g} m on the "
                                                "ground", s.output_sampling_m, design_m));
  if (!(s.output_sampling_m >= 1e-6 && s.output_sampling_m <= 1e6))
    refuse(file, "output sampling", fmt::format("{:.4g} m: an Earth scene's pixel lies between 1 um and 1000 km", s.output_sampling_m));

  const double detector_bits = result(report, vocabulary::detector_adc_bits).value_or(12.0);
  const int bits = o.adc_bits ? *o.adc_bits : static_cast<int>(detector_bits);
  if (bits < 1 || bits > 31) refuse(file, "ADC bits", "must lie in 1..31");
  s.adc_bits = bits;
  s.offset_dn = o.offset_dn;
  s.noise = o.noise;
  s.shot = o.noise && o.shot;
  s.dark = o.noise && o.dark;
  s.read = o.noise && o.read;
  if (electrons) s.noise = s.shot || s.dark || s.read;
  s.saturation = o.saturation;
  s.quantisation = o.quantisation;
  if (!electrons && (s.saturation || s.quantisation) && !(s.saturation_J_m2 > 0))
    refuse(file, "saturation exposure",
           "the detector gives no saturation_exposure: give it as an option, or render without saturation and ADC");
  if (electrons && (s.saturation || s.quantisation) && !(s.capacity_e > 0 && s.gain_dn_per_e > 0))
    refuse(file, "saturation capacity", "the detector's saturation capacity and gain must be > 0 to saturate and digitise");
  return s;
}

double system_mtf(const EarthSceneSetup& s, double nu_x, double nu_y) {
  const double scale = 1.0 / s.ground_to_focal();  // ground cycles/m → focal-plane cycles/m: × h/f'
  const double fx = nu_x * scale, fy = nu_y * scale;
  return std::abs(optics_otf(s, std::hypot(fx, fy)) * detector_otf_x(s, fx) * detector_otf_y(s, fy) * binning_otf(s, fx) *
                  binning_otf(s, fy));
}

namespace {
// The largest padded grid the PSF filter allocates beyond 4 times the map's own cells (2^26: 0.5 GB of doubles
// and half that of their transform).
constexpr double max_filter_cells = 67108864.0;

int native_size(const EarthSceneSetup& s, int input_px) {
  if (input_px < 1) return 0;
  return static_cast<int>(std::floor((input_px - 1) / sampling_ratio(s) + 1e-9)) + 1;
}
}  // namespace

int earth_output_size(const EarthSceneSetup& s, int input_px) { return native_size(s, input_px) / s.binning; }

namespace {
// The PSF's reach on the ground: detector element + ten Airy radii + the budget's blurs.
double psf_ground_m(const EarthSceneSetup& s) {
  const physics::MtfBudget& b = s.budget;
  const double budget_blur = s.optics == OpticsMtf::budget
                                 ? b.smear_m + b.tdi_mismatch * b.tdi_stages * b.pitch_m + 4.0 * (b.jitter_rms_m + b.diffusion_rms_m) +
                                       (b.fried_parameter_m > 0 ? 4.0 * b.wavelength_m * b.focal_length_m / b.fried_parameter_m : 0.0)
                                 : 0.0;
  return (s.element_m + 10.0 * s.wavelength_m * s.f_number + budget_blur) / s.ground_to_focal();
}

// Mirror padding wide enough for the PSF, in input pixels (a double: an absurd PSF must not overflow an integer).
double psf_margin_px(const EarthSceneSetup& s) { return std::ceil(2.0 * psf_ground_m(s) / s.input_sampling_m) + 4; }
}  // namespace

Image filtered_reflectance(const EarthSceneSetup& s, const Image& reflectance) {
  if (reflectance.empty()) throw std::invalid_argument("render: empty reflectance map");
  const std::int64_t w = reflectance.width, h = reflectance.height;
  const auto margin = static_cast<std::int64_t>(psf_margin_px(s));
  const int nx = detail::fft_friendly_size(static_cast<int>(w + 2 * margin));
  const int ny = detail::fft_friendly_size(static_cast<int>(h + 2 * margin));
  const int half = nx / 2 + 1;
  auto field = detail::real_buffer(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
  auto spectrum = detail::complex_buffer(static_cast<std::size_t>(ny) * static_cast<std::size_t>(half));
  const detail::Plan forward = detail::Plan::r2c_2d(ny, nx, field.get(), spectrum.get());
  const detail::Plan backward = detail::Plan::c2r_2d(ny, nx, spectrum.get(), field.get());
  for (std::int64_t y = 0; y < ny; ++y) {
    const std::int64_t sy = reflect(y - margin, h);
    for (std::int64_t x = 0; x < nx; ++x)
      field[static_cast<std::size_t>(y * nx + x)] = reflectance(static_cast<int>(reflect(x - margin, w)), static_cast<int>(sy));
  }
  forward.execute();

  // The OTF on the FFT grid: separable detector terms per axis, the radially symmetric optics term per point.
  const double scale = 1.0 / s.ground_to_focal();
  std::vector<double> fx(static_cast<std::size_t>(half)), fy(static_cast<std::size_t>(ny)), dx(fx.size()), dy(fy.size());
  for (int k = 0; k < half; ++k) {
    fx[static_cast<std::size_t>(k)] = k / (nx * s.input_sampling_m) * scale;
    dx[static_cast<std::size_t>(k)] = detector_otf_x(s, fx[static_cast<std::size_t>(k)]);
  }
  for (int k = 0; k < ny; ++k) {
    fy[static_cast<std::size_t>(k)] = (k <= ny / 2 ? k : k - ny) / (ny * s.input_sampling_m) * scale;
    dy[static_cast<std::size_t>(k)] = detector_otf_y(s, fy[static_cast<std::size_t>(k)]);
  }
  // Radial optics OTF tabulated in ν up to the grid's largest frequency (step small enough for < 1e-6).
  const double nu_max = std::hypot(fx.back(), 0.5 / s.input_sampling_m * scale) * 1.0001;
  constexpr int table_size = 16384;
  std::vector<double> radial(table_size + 2);
  for (int i = 0; i <= table_size + 1; ++i) radial[static_cast<std::size_t>(i)] = optics_otf(s, nu_max * i / table_size);
  const double norm = 1.0 / (static_cast<double>(nx) * ny);
  const double to_table = table_size / nu_max;
  for (int ky = 0; ky < ny; ++ky)
    for (int kx = 0; kx < half; ++kx) {
      const double ux = fx[static_cast<std::size_t>(kx)], uy = fy[static_cast<std::size_t>(ky)];
      const double t = std::sqrt(ux * ux + uy * uy) * to_table;
      const auto i = static_cast<std::size_t>(t);
      const double optics = radial[i] + (t - static_cast<double>(i)) * (radial[i + 1] - radial[i]);
      const double otf = optics * dx[static_cast<std::size_t>(kx)] * dy[static_cast<std::size_t>(ky)] * norm;
      fftw_complex& c = spectrum[static_cast<std::size_t>(ky) * half + kx];
      c[0] *= otf;
      c[1] *= otf;
    }
  backward.execute();

  // Point samples every r input pixels (exact for an integer r, else Keys' cubic).
  const double r = sampling_ratio(s);
  const int wo = native_size(s, reflectance.width), ho = native_size(s, reflectance.height);
  Image out(wo, ho);
  const auto ri = std::llround(r);
  auto at = [&](std::int64_t x, std::int64_t y) {
    x = std::clamp<std::int64_t>(x, 0, nx - 1);
    y = std::clamp<std::int64_t>(y, 0, ny - 1);
    return field[static_cast<std::size_t>(y * nx + x)];
  };
  if (ri >= 1 && std::abs(r - static_cast<double>(ri)) < 1e-9 * r) {
    for (int j = 0; j < ho; ++j)
      for (int i = 0; i < wo; ++i) out(i, j) = static_cast<float>(at(margin + i * ri, margin + j * ri));
  } else {
    for (int j = 0; j < ho; ++j) {
      const double y = static_cast<double>(margin) + j * r;
      const auto y0 = static_cast<std::int64_t>(std::floor(y));
      for (int i = 0; i < wo; ++i) {
        const double x = static_cast<double>(margin) + i * r;
        const auto x0 = static_cast<std::int64_t>(std::floor(x));
        double sum = 0;
        for (std::int64_t b = y0 - 1; b <= y0 + 2; ++b) {
          const double wy = keys(y - static_cast<double>(b));
          for (std::int64_t a = x0 - 1; a <= x0 + 2; ++a) sum += wy * keys(x - static_cast<double>(a)) * at(a, b);
        }
        out(i, j) = static_cast<float>(sum);
      }
    }
  }
  return out;
}

Image render_earth_scene(const EarthSceneSetup& s, const Image& reflectance, std::uint64_t seed) {
  // A map a thousand times finer or coarser than the output is a unit slip, not a scene.
  if (!(s.input_sampling_m >= 1e-3 * s.output_sampling_m && s.input_sampling_m <= 1e3 * s.output_sampling_m))
    refuse(s.sensor_file, "input sampling", fmt::format("{:.4g} m is not within a factor 1000 of the output sampling {:.4g} m",
                                                        s.input_sampling_m, s.output_sampling_m));
  // The output's size and the native reads it sums, refused before any work.
  const int wo = earth_output_size(s, reflectance.width), ho = earth_output_size(s, reflectance.height);
  if (wo < 1 || ho < 1)
    refuse(s.sensor_file, "output sampling",
           fmt::format("a {}×{} map at {:g} m gives {}×{} native samples at {:g} m, too few for one {}×{} binned pixel",
                       reflectance.width, reflectance.height, s.input_sampling_m, native_size(s, reflectance.width),
                       native_size(s, reflectance.height), s.native_sampling_m(), s.binning, s.binning));
  const double draws = static_cast<double>(wo) * ho * s.native_sums();
  if (draws > 4e9)
    refuse(s.sensor_file, std::string(vocabulary::detector_exposures.name),
           fmt::format("{}×{} pixels of {}×{} binned pixels over {} frames is {:.3g} native reads to draw (at most 4e9): "
                       "render a smaller scene or fewer exposures",
                       wo, ho, s.binning, s.binning, s.exposures, draws));
  // A PSF far wider than the scene (a wavelength in mm, a unit slip in the budget) would pad the FFT grid to
  // gigabytes (render_options_fuzz: --wavelength "2276 um" asked for 24 GB) and blur the scene to its mean.
  const double margin = psf_margin_px(s), w = reflectance.width, h = reflectance.height;
  const double padded = (w + 2 * margin) * (h + 2 * margin);
  if (!(padded <= std::max(4.0 * w * h, max_filter_cells)))
    refuse(s.sensor_file, "wavelength",
           fmt::format("the PSF at {:.4g} um reaches {:.4g} m on the ground ({:.3g} input pixels): padding the {}×{} map for "
                       "it needs {:.3g} cells (at most {:.3g}, or 4 times the map's): check the wavelength and the MTF inputs",
                       s.wavelength_m * 1e6, psf_ground_m(s), margin, reflectance.width, reflectance.height, padded,
                       max_filter_cells));
  Image image = filtered_reflectance(s, reflectance);
  detail::Random random(seed);
  const double q = s.exposure_per_dn(), top = std::exp2(s.adc_bits) - 1.0;
  auto digitise = [&](double value, double full) {
    if (s.saturation) value = std::min(value, full);
    return static_cast<float>(s.quantisation ? std::clamp(std::floor(value / q + s.offset_dn + 0.5), 0.0, top) : value);
  };
  if (s.radiometry == EarthRadiometry::exposure) {
    const double k = s.exposure_per_reflectance();
    for (float& v : image.pixels) {
      double exposure = static_cast<double>(v) * k;
      if (s.noise) exposure += s.nee_J_m2 * random.normal();
      v = digitise(exposure, s.saturation_J_m2);
    }
    return image;
  }
  // Electrons (EMVA 1288 eqs. 1-6, 18), per native pixel and frame. The fixed pattern comes from its own stream,
  // so that it is the same for one seed whatever the noise switches, and in every co-added frame.
  const int b = s.binning, frames = s.exposures;
  Image out(wo, ho);
  detail::Random pattern(seed ^ 0x9e3779b97f4a7c15ULL);
  const double dark = s.dark ? s.dark_electrons : 0.0;
  // Per native pixel: the mean photo signal with its PRNU, and the dark level with its DSNU.
  std::vector<double> photo(image.pixels.size()), level(image.pixels.size());
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    // PRNU goes with the shot noise (--no-noise shot), DSNU with the dark signal (--no-noise dark).
    const double g = pattern.normal(), d = pattern.normal();
    const double gain_pattern = s.shot ? 1.0 + s.prnu * g : 1.0;
    photo[i] = std::max(0.0, s.photo_electrons(static_cast<double>(image.pixels[i])) * gain_pattern);
    level[i] = photo[i] + dark + (s.dark ? s.dsnu_e * d : 0.0);
  }
  const double read_variance = s.read ? s.read_noise_e * s.read_noise_e : 0.0;
  std::vector<double> sum(out.pixels.size(), 0.0);
  for (int frame = 0; frame < frames; ++frame)
    for (int y = 0; y < out.height; ++y)
      for (int x = 0; x < out.width; ++x) {
        double& total = sum[static_cast<std::size_t>(y) * out.width + x];
        for (int v = 0; v < b; ++v)
          for (int u = 0; u < b; ++u) {
            const std::size_t i = static_cast<std::size_t>(y * b + v) * image.width + (x * b + u);
            const double variance = (s.shot ? photo[i] : 0.0) + dark + read_variance;
            double e = level[i];
            if (variance > 0) e += std::sqrt(variance) * random.normal();
            total += digitise(e, s.capacity_e);
          }
      }
  for (std::size_t i = 0; i < sum.size(); ++i) out.pixels[i] = static_cast<float>(sum[i]);
  return out;
}

std::string earth_unit(const EarthSceneSetup& s) {
  return s.quantisation ? "adu" : s.radiometry == EarthRadiometry::electrons ? "electron" : "J m-2";
}

Header earth_scene_header(const EarthSceneSetup& s, std::uint64_t seed) {
  Header h;
  auto number = [&](const std::string& key, double value, const std::string& comment) {
    if (std::isfinite(value)) h.push_back({key, value, comment});
  };
  auto text = [&](const std::string& key, const std::string& value, const std::string& comment) { h.push_back({key, value, comment}); };
  auto flag = [&](const std::string& key, bool value, const std::string& comment) { h.push_back({key, value, comment}); };
  const auto slash = s.sensor_file.find_last_of('/');
  text("ORIGIN", "radchain", "radchain render: pushbroom Earth scene");
  text("INSTRUME", s.sensor_name, "sensor");
  text("SENSFILE", slash == std::string::npos ? s.sensor_file : s.sensor_file.substr(slash + 1), "sensor file");
  const bool electrons = s.radiometry == EarthRadiometry::electrons;
  text("BUNIT", earth_unit(s), s.quantisation ? "ADC counts" : electrons ? "charge" : "exposure");
  text("RADIOM", electrons ? "electrons" : "exposure", electrons ? "datasheet detector (EMVA 1288)" : "noise-equivalent exposure (Kolobrodov)");
  number("EXPTIME", s.integration_time_s, "[s] line integration time of one frame");
  number("ALTITUDE", s.altitude_m, "[m] platform altitude");
  number("FOCALLEN", s.focal_length_m * 1e3, "[mm] focal length");
  number("APERTURE", s.aperture_m * 1e3, "[mm] entrance pupil");
  number("FNUMBER", s.f_number, "f'/D");
  number("OBSCUR", s.obscuration, "central obscuration (linear)");
  text("MTFOPT", to_string(s.optics), "optics MTF model");
  number("MTFWAVE", s.wavelength_m * 1e6, "[um] MTF wavelength");
  if (s.optics == OpticsMtf::kolobrodov_eq7) number("ETA", s.eta, "objective quality (eq. 7)");
  if (s.optics == OpticsMtf::budget) {
    number("JITTER", s.budget.jitter_rms_m * 1e6, "[um] rms jitter on the focal plane");
    number("SMEAR", s.budget.smear_m * 1e6, "[um] linear smear along track (y)");
    number("DIFFUS", s.budget.diffusion_rms_m * 1e6, "[um] rms diffusion");
    number("WFE", s.budget.wavefront_error_waves, "[waves] rms wavefront error");
    number("TDISTAGE", s.budget.tdi_stages, "TDI stages (MTF)");
    number("TDIMIS", s.budget.tdi_mismatch, "TDI mismatch (pixels per stage)");
    number("FRIEDR0", s.budget.fried_parameter_m * 100, "[cm] turbulence r0 (0: none)");
  }
  flag("MTFDET", s.detector_mtf, "detector element MTF applied");
  number("ELEMENT", s.element_m * 1e6, "[um] detector element V_D");
  number("PIXSIZE", s.pitch_m * 1e6, "[um] detector pitch");
  number("INSAMP", s.input_sampling_m, "[m] input map sampling");
  number("GSD", s.output_sampling_m, "[m] output sampling");
  if (s.pixel_gsd_m > 0) number("PIXGSD", s.pixel_gsd_m, "[m] pixel-pitch GSD h p / f'");
  if (s.ground_element_m > 0) number("GRNDELEM", s.ground_element_m, "[m] designed ground element");
  if (electrons) {
    number("EPERRHO", s.electrons_per_reflectance, "[e-] per unit reflectance, native pixel and frame");
    number("PATHE", s.path_electrons, "[e-] path radiance, native pixel and frame");
    number("DARKE", s.dark_electrons, "[e-] dark electrons per native pixel and frame");
    number("READNOIS", s.read_noise_e, "[e-] read noise per native pixel");
    h.push_back({"BINNING", static_cast<std::int64_t>(s.binning), "native pixels summed per side"});
    h.push_back({"NCOADD", static_cast<std::int64_t>(s.exposures), "frames co-added"});
    number("PRNU", s.prnu, "photo-response non-uniformity s_g");
    number("DSNU", s.dsnu_e, "[e-] dark-signal non-uniformity");
    number("GAIN", s.gain_dn_per_e, "[adu/e-] system gain K");
    number("FULLWELL", s.capacity_e, "[e-] saturation capacity");
    if (s.quantisation) {
      h.push_back({"ADCBITS", static_cast<std::int64_t>(s.adc_bits), "ADC resolution"});
      number("OFFSET", s.offset_dn, "[adu] ADC pedestal per native read (summed: x BINNING^2 x NCOADD)");
    }
    number("RHO", s.scene_reflectance, "the chain's scene reflectance");
    number("SNR", s.snr, "chain SNR of the scene pixel");
  } else {
    number("KIRRAD", s.irradiance_per_reflectance_W_m2, "[W m-2] image irradiance per reflectance");
    number("NEE", s.nee_J_m2, "[J m-2] noise-equivalent exposure");
    if (s.saturation_J_m2 > 0) number("HSAT", s.saturation_J_m2, "[J m-2] saturation exposure");
    if (s.quantisation) {
      h.push_back({"ADCBITS", static_cast<std::int64_t>(s.adc_bits), "ADC resolution"});
      number("EXPPERDN", s.exposure_per_dn(), "[J m-2/adu] HSAT / 2^bits");
      number("OFFSET", s.offset_dn, "[adu] ADC pedestal");
    }
    number("DRHO", s.reflectance_difference, "design contrast (reflectance)");
    number("RHO0", s.background_reflectance, "design background reflectance");
    number("SNR", s.snr, "chain SNR of DRHO");
  }
  h.push_back({"SEED", static_cast<std::int64_t>(seed), "noise seed (mt19937_64)"});
  flag("NNOISE", s.noise, electrons ? "shot, dark or read noise simulated" : "NEE noise simulated");
  flag("NSAT", s.saturation, "saturation simulated");
  flag("NADC", s.quantisation, "ADC quantisation simulated");
  return h;
}

}  // namespace radchain::render

// A pushbroom sensor's image of a reflectance map (render_earth.hpp).
#include "radchain/imaging/earth_scene.hpp"

#include "chain_access.hpp"
#include "fftw.hpp"
#include "radchain/physics/mtf.hpp"
#include "random.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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
    case OpticsMtf::none: break;
  }
  return 1.0;
}

double detector_otf(const EarthSceneSetup& s, double nu_focal) {
  return s.detector_mtf ? physics::sinc_pi(s.element_m * nu_focal) : 1.0;
}

double sampling_ratio(const EarthSceneSetup& s) { return s.output_sampling_m / s.input_sampling_m; }

}  // namespace

std::string to_string(OpticsMtf model) {
  switch (model) {
    case OpticsMtf::diffraction: return "diffraction";
    case OpticsMtf::kolobrodov_eq7: return "eq7";
    case OpticsMtf::none: return "none";
  }
  return "?";
}

std::optional<OpticsMtf> optics_mtf_from_string(const std::string& name) {
  if (name == "diffraction") return OpticsMtf::diffraction;
  if (name == "eq7" || name == "kolobrodov_eq7") return OpticsMtf::kolobrodov_eq7;
  if (name == "none") return OpticsMtf::none;
  return std::nullopt;
}

double EarthSceneSetup::exposure_per_dn() const { return saturation_J_m2 / std::exp2(adc_bits); }

EarthSceneSetup earth_scene_setup(Chain& chain, const Report& report, const EarthSceneOptions& o) {
  const std::string& file = chain.sensor_file;
  auto need = [&](const Term& term) {
    const auto v = result(report, term);
    if (!v)
      refuse(file, std::string(term.name),
             "an Earth scene needs a pushbroom chain (platform, telescope with a focal length, ccd_line detector, "
             "ground_resolution criterion) publishing this result; this sensor does not");
    return *v;
  };
  EarthSceneSetup s;
  s.sensor_name = chain.sensor_name;
  s.sensor_file = chain.sensor_file;
  s.altitude_m = need(vocabulary::platform_altitude);
  s.focal_length_m = need(vocabulary::optics_focal_length);
  s.f_number = need(vocabulary::optics_f_number);
  s.aperture_m = need(vocabulary::optics_aperture);
  s.obscuration = result(report, vocabulary::optics_obscuration).value_or(0.0);
  s.element_m = need(vocabulary::detector_element_size_for_mtf);
  s.pitch_m = result(report, vocabulary::detector_pixel_pitch).value_or(s.element_m);
  s.reflectance_difference = need(vocabulary::target_reflectance_difference);
  s.irradiance_per_reflectance_W_m2 = need(vocabulary::detector_signal_irradiance) / s.reflectance_difference;
  s.integration_time_s = need(vocabulary::detector_integration_time);
  s.nee_J_m2 = need(vocabulary::detector_nee_working);
  s.snr = need(vocabulary::detector_snr);
  if (auto g = detail::criterion_result(report, vocabulary::criterion_ground_element)) s.ground_element_m = g->second;
  if (auto g = detail::criterion_result(report, vocabulary::criterion_gsd_nadir)) s.pixel_gsd_m = g->second;

  const auto quality = detail::criterion_result(report, vocabulary::criterion_required_quality);
  if (quality) s.eta = quality->second;
  if (o.wavelength_m) s.wavelength_m = *o.wavelength_m;
  else if (quality && result(report, vocabulary::criterion_wavelength, quality->first))
    s.wavelength_m = *result(report, vocabulary::criterion_wavelength, quality->first);
  else {
    const auto lo = result(report, vocabulary::detector_band_min), hi = result(report, vocabulary::detector_band_max);
    if (!lo || !hi) refuse(file, "wavelength", "give the MTF wavelength as an option (the sensor has no mtf_match criterion or band)");
    s.wavelength_m = 0.5 * (*lo + *hi);
  }
  s.optics = o.optics;
  s.detector_mtf = o.detector_mtf;
  if (!(s.wavelength_m > 0)) refuse(file, "wavelength", "must be > 0");

  if (o.saturation_exposure_J_m2) s.saturation_J_m2 = *o.saturation_exposure_J_m2;
  else if (auto h = result(report, vocabulary::detector_saturation_exposure))
    s.saturation_J_m2 = *h * result(report, vocabulary::detector_utilisation_ratio).value_or(1.0);  // H_m k_i/k_c, as H_nr
  if (auto rho = result(report, vocabulary::target_background_reflectance)) s.background_reflectance = *rho;
  else if (auto m = result(report, vocabulary::target_background_exitance), e = result(report, vocabulary::atmosphere_ground_irradiance); m && e && *e > 0)
    s.background_reflectance = *m / *e;

  if (!(o.input_sampling_m > 0)) refuse(file, "input sampling", "give the ground size of one input pixel (> 0 m)");
  s.input_sampling_m = o.input_sampling_m;
  // One output pixel per detector sample: the pixel-pitch GSD h p / f', else Kolobrodov's element V_s h / f'.
  s.output_sampling_m = o.output_sampling_m ? *o.output_sampling_m : s.pixel_gsd_m > 0 ? s.pixel_gsd_m : s.ground_element_m;
  if (!(s.output_sampling_m > 0))
    refuse(file, "output sampling",
           "the sensor publishes neither criteria.<name>.gsd_nadir nor criteria.<name>.ground_element: give the output sampling");
  if (o.adc_bits < 1 || o.adc_bits > 31) refuse(file, "ADC bits", "must lie in 1..31");
  s.adc_bits = o.adc_bits;
  s.offset_dn = o.offset_dn;
  s.noise = o.noise;
  s.saturation = o.saturation;
  s.quantisation = o.quantisation;
  if ((s.saturation || s.quantisation) && !(s.saturation_J_m2 > 0))
    refuse(file, "saturation exposure",
           "the detector gives no saturation_exposure: give it as an option, or render without saturation and ADC");
  return s;
}

double system_mtf(const EarthSceneSetup& s, double nu_x, double nu_y) {
  const double scale = 1.0 / s.ground_to_focal();  // ground cycles/m → focal-plane cycles/m: × h/f'
  const double fx = nu_x * scale, fy = nu_y * scale;
  return std::abs(optics_otf(s, std::hypot(fx, fy)) * detector_otf(s, fx) * detector_otf(s, fy));
}

int earth_output_size(const EarthSceneSetup& s, int input_px) {
  if (input_px < 1) return 0;
  return static_cast<int>(std::floor((input_px - 1) / sampling_ratio(s) + 1e-9)) + 1;
}

Image filtered_reflectance(const EarthSceneSetup& s, const Image& reflectance) {
  if (reflectance.empty()) throw std::invalid_argument("render: empty reflectance map");
  const std::int64_t w = reflectance.width, h = reflectance.height;
  // Mirror padding wide enough for the PSF (detector element + ten Airy radii, on the ground).
  const double psf_ground = (s.element_m + 10.0 * s.wavelength_m * s.f_number) / s.ground_to_focal();
  const auto margin = static_cast<std::int64_t>(std::ceil(2.0 * psf_ground / s.input_sampling_m)) + 4;
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
    dx[static_cast<std::size_t>(k)] = detector_otf(s, fx[static_cast<std::size_t>(k)]);
  }
  for (int k = 0; k < ny; ++k) {
    fy[static_cast<std::size_t>(k)] = (k <= ny / 2 ? k : k - ny) / (ny * s.input_sampling_m) * scale;
    dy[static_cast<std::size_t>(k)] = detector_otf(s, fy[static_cast<std::size_t>(k)]);
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
  const int wo = earth_output_size(s, reflectance.width), ho = earth_output_size(s, reflectance.height);
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
  Image image = filtered_reflectance(s, reflectance);
  detail::Random random(seed);
  const double k = s.exposure_per_reflectance(), q = s.exposure_per_dn(), top = std::exp2(s.adc_bits) - 1.0;
  for (float& v : image.pixels) {
    double exposure = static_cast<double>(v) * k;
    if (s.noise) exposure += s.nee_J_m2 * random.normal();
    if (s.saturation) exposure = std::min(exposure, s.saturation_J_m2);
    v = static_cast<float>(s.quantisation ? std::clamp(std::floor(exposure / q + s.offset_dn + 0.5), 0.0, top) : exposure);
  }
  return image;
}

std::string earth_unit(const EarthSceneSetup& s) { return s.quantisation ? "adu" : "J m-2"; }

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
  text("BUNIT", earth_unit(s), s.quantisation ? "ADC counts" : "exposure");
  number("EXPTIME", s.integration_time_s, "[s] line integration time");
  number("ALTITUDE", s.altitude_m, "[m] platform altitude");
  number("FOCALLEN", s.focal_length_m * 1e3, "[mm] focal length");
  number("APERTURE", s.aperture_m * 1e3, "[mm] entrance pupil");
  number("FNUMBER", s.f_number, "f'/D");
  number("OBSCUR", s.obscuration, "central obscuration (linear)");
  text("MTFOPT", to_string(s.optics), "optics MTF model");
  number("MTFWAVE", s.wavelength_m * 1e6, "[um] MTF wavelength");
  if (s.optics == OpticsMtf::kolobrodov_eq7) number("ETA", s.eta, "objective quality (eq. 7)");
  flag("MTFDET", s.detector_mtf, "detector element MTF applied");
  number("ELEMENT", s.element_m * 1e6, "[um] detector element V_D");
  number("PIXSIZE", s.pitch_m * 1e6, "[um] detector pitch");
  number("INSAMP", s.input_sampling_m, "[m] input map sampling");
  number("GSD", s.output_sampling_m, "[m] output sampling");
  if (s.pixel_gsd_m > 0) number("PIXGSD", s.pixel_gsd_m, "[m] pixel-pitch GSD h p / f'");
  if (s.ground_element_m > 0) number("GRNDELEM", s.ground_element_m, "[m] designed ground element");
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
  h.push_back({"SEED", static_cast<std::int64_t>(seed), "noise seed (mt19937_64)"});
  flag("NNOISE", s.noise, "NEE noise simulated");
  flag("NSAT", s.saturation, "saturation simulated");
  flag("NADC", s.quantisation, "ADC quantisation simulated");
  return h;
}

}  // namespace radchain::render

#include "psf_stamps.hpp"

#include "fftw.hpp"
#include "radchain/physics/mtf.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace radchain::render::detail {

namespace {

constexpr double pi = std::numbers::pi;
constexpr int max_radius = 32;

double sinc(double x) {
  if (std::abs(x) < 1e-8) return 1.0;
  return std::sin(pi * x) / (pi * x);
}

std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  std::int64_t q = a / b;
  if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
  return q;
}

std::size_t wrap(std::int64_t i, std::int64_t n) { return static_cast<std::size_t>(((i % n) + n) % n); }

}  // namespace

int default_stamp_radius(const PsfSpec& spec) {
  switch (spec.model) {
    case PsfModel::pixel:
      return 0;
    case PsfModel::gaussian: {
      const double sigma = spec.fwhm_m / (2.0 * std::sqrt(2.0 * std::log(2.0)));
      // Clamped as a double: a PSF wider than an int counts pixels must not overflow the conversion.
      return static_cast<int>(std::clamp(std::ceil(4.0 * sigma / spec.pitch_m + 0.5), 1.0, static_cast<double>(max_radius)));
    }
    case PsfModel::airy: {
      const double v = 2.0 / (pi * 1e-3 * (1.0 - spec.obscuration));
      const double radius_m = v * spec.wavelength_m * spec.f_number / pi;
      return static_cast<int>(std::clamp(std::ceil(radius_m / spec.pitch_m + 0.5), 2.0, static_cast<double>(max_radius)));
    }
  }
  return 0;
}

PsfStamps::PsfStamps(const PsfSpec& spec) {
  if (spec.oversampling < 1 || spec.oversampling > 64) throw std::invalid_argument("PSF oversampling must lie in 1..64");
  switch (spec.model) {
    case PsfModel::pixel: build_pixel(); break;
    case PsfModel::gaussian: build_gaussian(spec); break;
    case PsfModel::airy: build_airy(spec); break;
  }
}

void PsfStamps::locate(double position_px, int& pixel, int& phase) const {
  const std::int64_t k = phases_, half = phases_ / 2;
  const auto q = static_cast<std::int64_t>(std::llround((position_px - 0.5) * static_cast<double>(k)));
  const std::int64_t base = floor_div(q + half, k);
  pixel = static_cast<int>(base);
  phase = static_cast<int>(q + half - base * k);
}

void PsfStamps::build_pixel() {
  radius_ = 0;
  phases_ = 1;
  values_ = {1.0};
}

void PsfStamps::build_gaussian(const PsfSpec& spec) {
  if (!(spec.fwhm_m > 0 && spec.pitch_m > 0)) throw std::invalid_argument("Gaussian PSF: FWHM and pixel pitch must be positive");
  radius_ = spec.radius_px > 0 ? spec.radius_px : default_stamp_radius(spec);
  phases_ = spec.oversampling;
  const int n = side(), k = phases_;
  const double sigma_px = spec.fwhm_m / (2.0 * std::sqrt(2.0 * std::log(2.0))) / spec.pitch_m;
  const double scale = 1.0 / (std::sqrt(2.0) * sigma_px);
  // One axis: the fraction in pixel i of a source offset by (phase − k/2)/k pixels from the centre pixel.
  std::vector<double> axis(static_cast<std::size_t>(k) * static_cast<std::size_t>(n));
  for (int ph = 0; ph < k; ++ph) {
    const double offset = static_cast<double>(ph - k / 2) / k;
    for (int i = -radius_; i <= radius_; ++i) {
      const double d = i - offset;
      axis[static_cast<std::size_t>(ph * n + i + radius_)] = 0.5 * (std::erf((d + 0.5) * scale) - std::erf((d - 0.5) * scale));
    }
  }
  values_.assign(static_cast<std::size_t>(k) * k * n * n, 0.0);
  for (int py = 0; py < k; ++py)
    for (int px = 0; px < k; ++px) {
      double* s = values_.data() + (static_cast<std::size_t>(py) * k + px) * n * n;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) s[j * n + i] = axis[static_cast<std::size_t>(py * n + j)] * axis[static_cast<std::size_t>(px * n + i)];
    }
}

void PsfStamps::build_airy(const PsfSpec& spec) {
  if (!(spec.wavelength_m > 0 && spec.f_number > 0 && spec.pitch_m > 0))
    throw std::invalid_argument("Airy PSF: wavelength, f-number and pixel pitch must be positive");
  radius_ = spec.radius_px > 0 ? spec.radius_px : default_stamp_radius(spec);
  phases_ = spec.oversampling;
  const int k = phases_, n = side();
  int domain = 2 * n;  // pixels
  while (detail::fft_friendly_size(k * domain) != k * domain) ++domain;
  const int grid = k * domain, half = grid / 2 + 1;
  const double p = spec.pitch_m;
  const double cutoff = 1.0 / (spec.wavelength_m * spec.f_number);  // ν_c, cycles per metre
  const double dnu = 1.0 / (domain * p), period = k / p;

  // The radial OTF, tabulated in x = ν/ν_c (linear interpolation; the table step 1/8192 keeps it to < 1e-7).
  constexpr int table_size = 8192;
  std::vector<double> otf(table_size + 2, 0.0);
  for (int i = 0; i <= table_size; ++i)
    otf[static_cast<std::size_t>(i)] = physics::diffraction_mtf_normalized(static_cast<double>(i) / table_size, spec.obscuration);
  auto radial = [&](double x) {
    if (x >= 1.0) return 0.0;
    const double t = x * table_size;
    const auto i = static_cast<std::size_t>(t);
    const double f = t - static_cast<double>(i);
    return otf[i] + f * (otf[i + 1] - otf[i]);
  };

  // Per axis and frequency index: the aliases ν + q·k/p inside the OTF's support, and their sinc(pν) factors.
  struct Alias {
    double nu, sinc;
  };
  auto aliases = [&](double nu) {
    std::vector<Alias> out;
    const auto q_lo = static_cast<int>(std::ceil((-cutoff - nu) / period));
    const auto q_hi = static_cast<int>(std::floor((cutoff - nu) / period));
    for (int q = q_lo; q <= q_hi; ++q) {
      const double v = nu + q * period;
      out.push_back({v, sinc(p * v)});
    }
    return out;
  };
  std::vector<std::vector<Alias>> alias_x(static_cast<std::size_t>(half)), alias_y(static_cast<std::size_t>(grid));
  for (int j = 0; j < half; ++j) alias_x[static_cast<std::size_t>(j)] = aliases(j * dnu);
  for (int j = 0; j < grid; ++j) alias_y[static_cast<std::size_t>(j)] = aliases((j <= grid / 2 ? j : j - grid) * dnu);

  auto spectrum = detail::complex_buffer(static_cast<std::size_t>(grid) * half);
  auto samples = detail::real_buffer(static_cast<std::size_t>(grid) * grid);
  const double inv_cutoff2 = 1.0 / (cutoff * cutoff);
  for (int jy = 0; jy < grid; ++jy)
    for (int jx = 0; jx < half; ++jx) {
      double sum = 0.0;
      for (const Alias& ay : alias_y[static_cast<std::size_t>(jy)])
        for (const Alias& ax : alias_x[static_cast<std::size_t>(jx)])
          sum += radial(std::sqrt((ax.nu * ax.nu + ay.nu * ay.nu) * inv_cutoff2)) * ax.sinc * ay.sinc;
      fftw_complex& c = spectrum[static_cast<std::size_t>(jy) * half + jx];
      c[0] = sum;
      c[1] = 0.0;
    }
  const Plan plan = Plan::c2r_2d(grid, grid, spectrum.get(), samples.get());
  plan.execute();
  // E(a p/k) = Δν² Σ F e^{...} with F = OTF p² sinc sinc and Δν = 1/(D p): the sum over 1/D².
  const double norm = 1.0 / (static_cast<double>(domain) * domain);
  values_.assign(static_cast<std::size_t>(k) * k * n * n, 0.0);
  for (int py = 0; py < k; ++py)
    for (int px = 0; px < k; ++px) {
      double* s = values_.data() + (static_cast<std::size_t>(py) * k + px) * n * n;
      for (int j = -radius_; j <= radius_; ++j)
        for (int i = -radius_; i <= radius_; ++i) {
          // pixel centre offset from the source, in grid steps of p/k
          const std::int64_t ax = static_cast<std::int64_t>(i) * k - (px - k / 2);
          const std::int64_t ay = static_cast<std::int64_t>(j) * k - (py - k / 2);
          s[(j + radius_) * n + (i + radius_)] = norm * samples[wrap(ay, grid) * grid + wrap(ax, grid)];
        }
    }
}

}  // namespace radchain::render::detail

#include "radchain/physics/psf.hpp"

#include "radchain/physics/mtf.hpp"

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/math/special_functions/bessel.hpp>
#include <boost/math/tools/roots.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace radchain::physics {

namespace {

constexpr double pi = std::numbers::pi;

void check_obscuration(double obscuration) {
  if (!(obscuration >= 0.0 && obscuration < 1.0)) throw std::domain_error("PSF: the obscuration ratio must lie in [0, 1)");
}

// 2 J1(v)/v, 1 at v = 0 (series below 1e-4: 1 − v²/8 + v⁴/192).
double jinc(double v) {
  if (std::abs(v) < 1e-4) return 1.0 - v * v / 8.0 + v * v * v * v / 192.0;
  return 2.0 * boost::math::cyl_bessel_j(1, v) / v;
}

// Field amplitude of the annular pupil, 1 at v = 0.
double annular_amplitude(double v, double obscuration) {
  const double e2 = obscuration * obscuration;
  return (jinc(v) - e2 * jinc(obscuration * v)) / (1.0 - e2);
}

// 1 − J0²(x) − J1²(x): the unobscured encircled energy (Rayleigh).
double rayleigh_encircled(double x) {
  const double j0 = boost::math::cyl_bessel_j(0, x), j1 = boost::math::cyl_bessel_j(1, x);
  return 1.0 - j0 * j0 - j1 * j1;
}

// The cross term C(v) = ∫0^v J1(x) J1(εx)/x dx of the annular encircled energy (→ ε/2 as v → ∞), tabulated
// cumulatively on segments of π/4 (20-point Gauss-Legendre per segment: the integrand is analytic and a segment
// holds an eighth of a ring, so each is exact to rounding), so that the many evaluations of an ensquared-energy
// quadrature cost one short rule each. Beyond v = 2000 the rest of the integral is of order
// 2/(π √ε (1 − ε) v²) ≈ 2e-7/(√ε (1 − ε)) (J1(x) J1(εx) ~ 2/(π x √ε) cos·cos, an oscillation whose integral
// against 1/x² falls as 1/v²), and the limit ε/2 is used: large windows stay cheap.
class AnnularCrossTerm {
 public:
  static constexpr double asymptotic_from = 2000.0;

  // `fine`: segments of π/32, each (and the last, partial one) by a 7-point rule: the same values to ~1e-9 of the
  // n_eff (tested through it) with ~3× fewer Bessel functions per call, for the many calls of an n_eff pixel sum.
  AnnularCrossTerm(double obscuration, double v_max, bool fine = false)
      : eps_(obscuration), segment_(fine ? pi / 32.0 : pi / 4.0), fine_(fine) {
    const double top = std::min(v_max, asymptotic_from);
    const auto segments = static_cast<std::size_t>(std::ceil(top / segment_)) + 1;
    cumulative_.reserve(segments + 1);
    cumulative_.push_back(0.0);
    for (std::size_t k = 0; k < segments; ++k)
      cumulative_.push_back(cumulative_.back() + piece(k * segment_, (k + 1) * segment_));
  }

  double operator()(double v) const {
    if (v > asymptotic_from) return 0.5 * eps_;
    auto k = static_cast<std::size_t>(v / segment_);
    if (k + 1 >= cumulative_.size()) k = cumulative_.size() - 2;  // (not reached: the table covers v_max)
    return cumulative_[k] + piece(k * segment_, v);
  }

 private:
  double integrand(double x) const {
    if (x < 1e-8) return eps_ * x / 4.0;
    return boost::math::cyl_bessel_j(1, x) * boost::math::cyl_bessel_j(1, eps_ * x) / x;
  }
  double piece(double a, double b) const {
    auto f = [this](double x) { return integrand(x); };
    return fine_ ? boost::math::quadrature::gauss<double, 7>::integrate(f, a, b)
                 : boost::math::quadrature::gauss<double, 20>::integrate(f, a, b);
  }

  double eps_, segment_;
  bool fine_;
  std::vector<double> cumulative_;
};

// Annular encircled energy with a prepared cross term.
double annular_encircled(double v, double obscuration, const AnnularCrossTerm& cross) {
  const double e = obscuration, e2 = e * e;
  return (rayleigh_encircled(v) + e2 * rayleigh_encircled(e * v) - 4.0 * e * cross(v)) / (1.0 - e2);
}

}  // namespace

double airy_optical_coordinate(double radius_m, double wavelength_m, double f_number) {
  return pi * radius_m / (wavelength_m * f_number);
}

double airy_normalized_intensity(double v, double obscuration) {
  check_obscuration(obscuration);
  const double a = annular_amplitude(v, obscuration);
  return a * a;
}

double airy_psf_per_m2(double radius_m, double wavelength_m, double f_number, double obscuration) {
  const double lambda_n = wavelength_m * f_number;
  const double peak = pi * (1.0 - obscuration * obscuration) / (4.0 * lambda_n * lambda_n);
  return peak * airy_normalized_intensity(airy_optical_coordinate(radius_m, wavelength_m, f_number), obscuration);
}

double airy_first_dark_ring_v(double obscuration) {
  check_obscuration(obscuration);
  auto amplitude = [obscuration](double v) { return annular_amplitude(v, obscuration); };
  // March out to the first sign change, then TOMS 748 (the zero lies below 3.8317 for every ε).
  const double step = 0.01;
  double lo = step, f_lo = amplitude(lo);
  for (double hi = 2.0 * step; hi < 8.0; hi += step) {
    const double f_hi = amplitude(hi);
    if ((f_lo > 0) != (f_hi > 0)) {
      std::uintmax_t iterations = 100;
      const auto [a, b] = boost::math::tools::toms748_solve(amplitude, lo, hi, f_lo, f_hi,
                                                            boost::math::tools::eps_tolerance<double>(50), iterations);
      return 0.5 * (a + b);
    }
    lo = hi, f_lo = f_hi;
  }
  throw std::runtime_error("airy_first_dark_ring_v: no zero found");
}

double airy_first_dark_ring_radius_m(double wavelength_m, double f_number, double obscuration) {
  return airy_first_dark_ring_v(obscuration) * wavelength_m * f_number / pi;
}

double airy_encircled_energy_v(double v, double obscuration) {
  check_obscuration(obscuration);
  if (v <= 0.0) return 0.0;
  if (obscuration == 0.0) return rayleigh_encircled(v);
  return annular_encircled(v, obscuration, AnnularCrossTerm(obscuration, v));
}

double airy_encircled_energy(double radius_m, double wavelength_m, double f_number, double obscuration) {
  return airy_encircled_energy_v(airy_optical_coordinate(radius_m, wavelength_m, f_number), obscuration);
}

double airy_ensquared_energy(double side_m, double wavelength_m, double f_number, double obscuration) {
  check_obscuration(obscuration);
  if (obscuration == 0.0)
    return ensquared_from_encircled([&](double r) { return airy_encircled_energy(r, wavelength_m, f_number); }, side_m);
  // One cross-term table up to the square's corner serves every radius the quadrature asks for.
  const AnnularCrossTerm cross(obscuration, airy_optical_coordinate(side_m / std::sqrt(2.0), wavelength_m, f_number));
  return ensquared_from_encircled(
      [&](double r) {
        return annular_encircled(airy_optical_coordinate(r, wavelength_m, f_number), obscuration, cross);
      },
      side_m);
}

namespace {

// (1/2π) [∫0^θ0 EC(a/cos θ) dθ + ∫θ0^{π/2} EC(b/sin θ) dθ], θ0 = atan(b/a): the energy in the rectangle
// [0, a] × [0, b] with a corner at the PSF's centre (v units), the polar form of ensquared_from_encircled. Each
// angle range in 2 + 2·(radius swept)/π equal pieces of 12 Gauss-Legendre nodes (rings are π apart in v; the
// radius a/cos θ sweeps faster near θ0, so a piece there may hold more than half a ring — the check against the
// frequency-domain form, 1e-6, is what vouches for it).
template <class Encircled>
double quadrant_energy(const Encircled& encircled, double a, double b) {
  const double theta0 = std::atan2(b, a), corner = std::hypot(a, b);
  auto part = [&](auto radius, double lo, double hi, double swept) {
    const int pieces = 2 + static_cast<int>(std::ceil(2.0 * swept / pi));
    double sum = 0.0;
    for (int k = 0; k < pieces; ++k)
      sum += boost::math::quadrature::gauss<double, 12>::integrate([&](double t) { return encircled(radius(t)); },
                                                                    lo + (hi - lo) * k / pieces, lo + (hi - lo) * (k + 1) / pieces);
    return sum;
  };
  const double along_a = part([&](double t) { return a / std::cos(t); }, 0.0, theta0, corner - a);
  const double along_b = part([&](double t) { return b / std::sin(t); }, theta0, pi / 2.0, corner - b);
  return (along_a + along_b) / (2.0 * pi);
}

}  // namespace

double airy_noise_equivalent_area_px(double pitch_m, double wavelength_m, double f_number, double obscuration) {
  check_obscuration(obscuration);
  const double p = pitch_m / (wavelength_m * f_number);  // the pitch in λN
  if (!(p > 0.0)) throw std::domain_error("airy_noise_equivalent_area_px: the pitch, wavelength and f-number must be positive");
  if (p > 0.5) return airy_noise_equivalent_area_by_pixels(pitch_m, wavelength_m, f_number, obscuration);
  // x = ν/ν_c ∈ [0, 1], ν_c = 1/(λN): Σ f² = p² ∫0^1 x MTF(x)² ∫0^{2π} sinc²(p x cos θ) sinc²(p x sin θ) dθ dx.
  auto sinc = [](double u) { return u == 0.0 ? 1.0 : std::sin(pi * u) / (pi * u); };
  auto around = [&](double x) {  // the angular integral: 8 equal octants, smooth (p x ≤ ½)
    auto f = [&](double t) {
      const double u = sinc(p * x * std::cos(t)), w = sinc(p * x * std::sin(t));
      return u * u * w * w;
    };
    return 8.0 * boost::math::quadrature::gauss<double, 20>::integrate(f, 0.0, pi / 4.0);
  };
  auto radial = [&](double x) {
    const double m = diffraction_mtf_normalized(x, obscuration);
    return x * m * m * around(x);
  };
  // The annular MTF has kinks at x = ε, (1 − ε)/2 and (1 + ε)/2: integrate between them.
  std::vector<double> edges{0.0, 1.0};
  if (obscuration > 0.0) edges = {0.0, obscuration, 0.5 * (1.0 - obscuration), 0.5 * (1.0 + obscuration), 1.0};
  std::sort(edges.begin(), edges.end());
  // (Tanh-sinh: the MTF's derivative has square-root singularities at the edges, which it integrates to rounding.)
  boost::math::quadrature::tanh_sinh<double> integrator;
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < edges.size(); ++i)
    if (edges[i + 1] > edges[i])
      sum += integrator.integrate([&](double x) -> double { return radial(x); }, edges[i], edges[i + 1], 1e-12);
  return 1.0 / (p * p * sum);
}

double airy_noise_equivalent_area_by_pixels(double pitch_m, double wavelength_m, double f_number, double obscuration) {
  check_obscuration(obscuration);
  const double p = pitch_m / (wavelength_m * f_number);
  if (!(p > 0.0)) throw std::domain_error("airy_noise_equivalent_area_by_pixels: the pitch, wavelength and f-number must be positive");
  const int rings = std::max(2, static_cast<int>(std::ceil(12.0 / p)));
  const double s = pi * p;  // the pitch in v
  const double v_max = std::sqrt(2.0) * (rings + 0.5) * s;
  const AnnularCrossTerm cross(obscuration, obscuration > 0.0 ? v_max : 1.0, true);
  auto encircled = [&](double v) {
    return obscuration > 0.0 ? annular_encircled(v, obscuration, cross) : rayleigh_encircled(v);
  };
  // B(i, j): the energy in the centred box of half-sides (i + ½) s and (j + ½) s (symmetric in i, j).
  const auto n = static_cast<std::size_t>(rings) + 1;
  std::vector<double> box(n * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j <= i; ++j)
      box[i * n + j] = box[j * n + i] = 4.0 * quadrant_energy(encircled, (i + 0.5) * s, (j + 0.5) * s);
  auto b = [&](long i, long j) { return i < 0 || j < 0 ? 0.0 : box[static_cast<std::size_t>(i) * n + static_cast<std::size_t>(j)]; };
  // One pixel's energy from the boxes (the pixels (±i, ±j) share it): the box differences over their count.
  double sum = 0.0;
  for (long i = 0; i < static_cast<long>(n); ++i)
    for (long j = 0; j < static_cast<long>(n); ++j) {
      const double pixels = (i > 0 ? 2.0 : 1.0) * (j > 0 ? 2.0 : 1.0);
      const double f = (b(i, j) - b(i - 1, j) - b(i, j - 1) + b(i - 1, j - 1)) / pixels;
      sum += pixels * f * f;
    }
  // Beyond the box of half-side A = (K + ½) p (in λN): Σ f² ≈ p² ∫ h̄² dA over the outside of the square, with
  // h̄ = (λN)/(π³ (1 − ε) r³) the ring average of the intensity (J1² → cos²/(π v/2)): p² (3π/4 + 2)/(4 π⁶ (1 − ε)² A⁴).
  // The square of the average, where pixels smaller than a ring (p ≲ λN) see the average of the square, up to
  // 3/2 of it: the term is ~2e-7 of the sum at p = λN/2 and A = 12, so its own error stays near 1e-7.
  const double half_side = (rings + 0.5) * p;
  sum += p * p * (3.0 * pi / 4.0 + 2.0) /
         (4.0 * std::pow(pi, 6) * (1.0 - obscuration) * (1.0 - obscuration) * std::pow(half_side, 4));
  return 1.0 / sum;
}

double gaussian_sigma_from_fwhm(double fwhm_m) { return fwhm_m / (2.0 * std::sqrt(2.0 * std::numbers::ln2)); }
double gaussian_fwhm_from_sigma(double sigma_m) { return sigma_m * (2.0 * std::sqrt(2.0 * std::numbers::ln2)); }

double gaussian_encircled_energy(double radius_m, double fwhm_m) {
  const double s = gaussian_sigma_from_fwhm(fwhm_m);
  return -std::expm1(-radius_m * radius_m / (2.0 * s * s));
}

double gaussian_ensquared_energy(double side_m, double fwhm_m) {
  const double e = std::erf(side_m / (2.0 * std::numbers::sqrt2 * gaussian_sigma_from_fwhm(fwhm_m)));
  return e * e;
}

double ensquared_from_encircled(const std::function<double(double)>& encircled_energy, double side_m) {
  if (!(side_m > 0.0)) return 0.0;
  const double half = 0.5 * side_m;
  auto f = [&](double theta) { return encircled_energy(half / std::cos(theta)); };
  // Split the angle in 8 pieces so that many rings inside a large window still meet enough nodes.
  double sum = 0.0;
  const int pieces = 8;
  for (int k = 0; k < pieces; ++k) {
    const double a = (pi / 4.0) * k / pieces, b = (pi / 4.0) * (k + 1) / pieces;
    sum += boost::math::quadrature::gauss_kronrod<double, 21>::integrate(f, a, b, 12, 1e-11);
  }
  return 4.0 / pi * sum;
}

}  // namespace radchain::physics

#include "radchain/physics/psf.hpp"

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
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
  static constexpr double segment = pi / 4.0;

  AnnularCrossTerm(double obscuration, double v_max) : eps_(obscuration) {
    const double top = std::min(v_max, asymptotic_from);
    const auto segments = static_cast<std::size_t>(std::ceil(top / segment)) + 1;
    cumulative_.reserve(segments + 1);
    cumulative_.push_back(0.0);
    for (std::size_t k = 0; k < segments; ++k)
      cumulative_.push_back(cumulative_.back() + piece(k * segment, (k + 1) * segment));
  }

  double operator()(double v) const {
    if (v > asymptotic_from) return 0.5 * eps_;
    auto k = static_cast<std::size_t>(v / segment);
    if (k + 1 >= cumulative_.size()) k = cumulative_.size() - 2;  // (not reached: the table covers v_max)
    return cumulative_[k] + piece(k * segment, v);
  }

 private:
  double integrand(double x) const {
    if (x < 1e-8) return eps_ * x / 4.0;
    return boost::math::cyl_bessel_j(1, x) * boost::math::cyl_bessel_j(1, eps_ * x) / x;
  }
  double piece(double a, double b) const {
    return boost::math::quadrature::gauss<double, 20>::integrate([this](double x) { return integrand(x); }, a, b);
  }

  double eps_;
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

// The General Image Quality Equation and the edge response (sources in giqe.hpp).
#include "radchain/physics/giqe.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <stdexcept>

namespace radchain::physics {

namespace {
void require_positive(double value, const char* what) {
  if (!(value > 0)) throw std::invalid_argument(fmt::format("{} must be positive, got {}", what, value));
}
}  // namespace

double giqe5_niirs(double gsd_m, double rer, double snr, const Giqe5Coefficients& c) {
  require_positive(gsd_m, "GIQE: GSD");
  require_positive(rer, "GIQE: RER");
  require_positive(snr, "GIQE: SNR");
  const double gsd_inch = gsd_m / metres_per_inch;
  const double log_rer = std::log10(rer);
  // NGA GIQE v5.0 (2015): A0 + A1 log GSD + A2 [1 − exp(A3/SNR)] log RER + A4 (log RER)^4 + A5/SNR.
  return c.a0 + c.a1 * std::log10(gsd_inch) + c.a2 * (1 - std::exp(c.a3 / snr)) * log_rer +
         c.a4 * std::pow(log_rer, 4) + c.a5 / snr;
}

double giqe5_weighted_gsd_m(double normal_plane_gsd_m, double elevation_rad) {
  require_positive(normal_plane_gsd_m, "GIQE: normal-plane GSD");
  if (!(elevation_rad > 0 && elevation_rad <= std::numbers::pi / 2 + 1e-12))
    throw std::invalid_argument("GIQE: the target elevation must lie in (0°, 90°]");
  return normal_plane_gsd_m / std::pow(std::sin(elevation_rad), 0.25);  // NGA GIQE v5.0 eq. (5)
}

double giqe5_weighted_rer(double rer_a, double rer_b) {
  require_positive(rer_a, "GIQE: RER");
  require_positive(rer_b, "GIQE: RER");
  const double lesser = std::min(rer_a, rer_b);
  return std::cbrt(std::max(rer_a, rer_b) * lesser * lesser);  // NGA GIQE v5.0 eq. (7)
}

double giqe4_niirs(double gsd_m, double rer, double overshoot, double noise_gain, double snr) {
  require_positive(gsd_m, "GIQE: GSD");
  require_positive(rer, "GIQE: RER");
  require_positive(snr, "GIQE: SNR");
  const double gsd_inch = gsd_m / metres_per_inch;
  // Leachtenauer et al. 1997, eq. (2) and its two coefficient sets.
  const double a = rer >= 0.9 ? 3.32 : 3.16;
  const double b = rer >= 0.9 ? 1.559 : 2.817;
  return 10.251 - a * std::log10(gsd_inch) + b * std::log10(rer) - 0.656 * overshoot - 0.344 * noise_gain / snr;
}

double edge_response(const std::function<double(double)>& mtf, double x_samples, double max_frequency,
                     int intervals) {
  require_positive(max_frequency, "edge response: maximum frequency");
  if (intervals < 2) throw std::invalid_argument("edge response: at least 2 Simpson panels");
  if (intervals % 2) ++intervals;
  // ER(x) = ½ + (1/π) ∫₀^νmax MTF(ν) sin(2πνx)/ν dν; the integrand's limit at ν = 0 is 2πx · MTF(0).
  const double two_pi_x = 2 * std::numbers::pi * x_samples;
  auto integrand = [&](double nu) { return nu == 0 ? two_pi_x * mtf(0.0) : mtf(nu) * std::sin(two_pi_x * nu) / nu; };
  const double h = max_frequency / intervals;
  double sum = integrand(0) + integrand(max_frequency);
  for (int i = 1; i < intervals; ++i) sum += (i % 2 ? 4 : 2) * integrand(i * h);
  return 0.5 + sum * h / 3 / std::numbers::pi;
}

double relative_edge_response(const std::function<double(double)>& mtf, double max_frequency, int intervals) {
  return edge_response(mtf, 0.5, max_frequency, intervals) - edge_response(mtf, -0.5, max_frequency, intervals);
}

double edge_overshoot(const std::function<double(double)>& mtf, double max_frequency, int intervals) {
  // Sample ER on [1, 3] every 1/20 sample: an overshoot peak of a sampled imaging system is wider than that.
  double previous = edge_response(mtf, 1.0, max_frequency, intervals), peak = previous;
  bool monotonic = true;
  for (int i = 1; i <= 40; ++i) {
    const double er = edge_response(mtf, 1.0 + i * 0.05, max_frequency, intervals);
    if (er < previous) monotonic = false;
    peak = std::max(peak, er);
    previous = er;
  }
  return monotonic ? edge_response(mtf, 1.25, max_frequency, intervals) : peak;
}

double edge_response_pybsm(const std::function<double(double)>& mtf, double x_samples, double cutoff_samples,
                           double ifov_rad) {
  require_positive(cutoff_samples, "edge response: cut-off frequency");
  require_positive(ifov_rad, "edge response: ifov");
  constexpr int nodes = 50;
  constexpr double offset = 1e-6;  // cycles/rad, pyBSM's
  const double step = cutoff_samples / nodes;
  double sum = 0, previous_w = 0, previous_y = 0;
  for (int k = 0; k < nodes; ++k) {
    const double nu = k * step;
    const double w = nu / ifov_rad + offset;
    const double y = mtf(nu) * std::sin(2 * std::numbers::pi * w * ifov_rad * x_samples) / w;
    if (k > 0) sum += 0.5 * (y + previous_y) * (w - previous_w);
    previous_w = w, previous_y = y;
  }
  return 0.5 + sum / std::numbers::pi;
}

double relative_edge_response_pybsm(const std::function<double(double)>& mtf, double cutoff_samples, double ifov_rad) {
  return edge_response_pybsm(mtf, 0.5, cutoff_samples, ifov_rad) - edge_response_pybsm(mtf, -0.5, cutoff_samples, ifov_rad);
}

double edge_overshoot_pybsm(const std::function<double(double)>& mtf, double cutoff_samples, double ifov_rad) {
  std::array<double, 9> er{};
  for (std::size_t i = 0; i < er.size(); ++i) er[i] = edge_response_pybsm(mtf, 1.0 + 0.25 * i, cutoff_samples, ifov_rad);
  bool rising = true;
  for (std::size_t i = 1; i < er.size(); ++i) rising = rising && er[i] - er[i - 1] > 0;
  return rising ? er[1] : *std::max_element(er.begin(), er.end());
}

}  // namespace radchain::physics

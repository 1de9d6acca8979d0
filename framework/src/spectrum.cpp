#include "radchain/spectrum.hpp"

#include <algorithm>
#include <stdexcept>

namespace radchain {

Spectrum::Spectrum(Eigen::ArrayXd wavelength_m, Eigen::ArrayXd value, std::string unit, Extrapolation extrapolation)
    : wavelength_m_(std::move(wavelength_m)),
      value_(std::move(value)),
      unit_(std::move(unit)),
      extrapolation_(extrapolation) {
  if (wavelength_m_.size() != value_.size()) throw std::invalid_argument("spectrum: grid and values differ in size");
  if (wavelength_m_.size() < 2) throw std::invalid_argument("spectrum: fewer than 2 points");
  for (Eigen::Index i = 1; i < wavelength_m_.size(); ++i)
    if (!(wavelength_m_(i) > wavelength_m_(i - 1)))
      throw std::invalid_argument("spectrum: wavelengths are not strictly increasing");
}

Spectrum Spectrum::constant(double value, std::string unit, double lo_m, double hi_m) {
  Eigen::ArrayXd grid(2), values(2);
  grid << lo_m, hi_m;
  values << value, value;
  return Spectrum(grid, values, std::move(unit), Extrapolation::clamp);
}

Spectrum Spectrum::sampled(const Eigen::ArrayXd& wavelength_m, const std::function<double(double)>& f,
                           std::string unit, Extrapolation extrapolation) {
  Eigen::ArrayXd values(wavelength_m.size());
  for (Eigen::Index i = 0; i < wavelength_m.size(); ++i) values(i) = f(wavelength_m(i));
  return Spectrum(wavelength_m, values, std::move(unit), extrapolation);
}

double Spectrum::operator()(double x) const {
  const Eigen::Index n = wavelength_m_.size();
  if (n == 0) return 0.0;
  if (x <= wavelength_m_(0)) {
    if (x == wavelength_m_(0) || extrapolation_ == Extrapolation::clamp) return value_(0);
    return 0.0;
  }
  if (x >= wavelength_m_(n - 1)) {
    if (x == wavelength_m_(n - 1) || extrapolation_ == Extrapolation::clamp) return value_(n - 1);
    return 0.0;
  }
  const double* begin = wavelength_m_.data();
  const Eigen::Index hi = std::upper_bound(begin, begin + n, x) - begin;  // first grid point > x
  const Eigen::Index lo = hi - 1;
  const double t = (x - wavelength_m_(lo)) / (wavelength_m_(hi) - wavelength_m_(lo));
  return value_(lo) + t * (value_(hi) - value_(lo));
}

Eigen::ArrayXd Spectrum::operator()(const Eigen::ArrayXd& x) const {
  Eigen::ArrayXd out(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) out(i) = (*this)(x(i));
  return out;
}

Spectrum Spectrum::scaled(double k, std::string unit) const {
  return Spectrum(wavelength_m_, value_ * k, unit.empty() ? unit_ : std::move(unit), extrapolation_);
}

Spectrum Spectrum::resampled(const Eigen::ArrayXd& grid) const {
  return Spectrum(grid, (*this)(grid), unit_, extrapolation_);
}

Spectrum Spectrum::product(const Spectrum& other, std::string unit) const {
  // Where one factor is zero by extrapolation the product is zero: keep only the overlap of the supports.
  double lo = std::min(min_wavelength_m(), other.min_wavelength_m());
  double hi = std::max(max_wavelength_m(), other.max_wavelength_m());
  if (extrapolation_ == Extrapolation::zero) lo = std::max(lo, min_wavelength_m()), hi = std::min(hi, max_wavelength_m());
  if (other.extrapolation_ == Extrapolation::zero)
    lo = std::max(lo, other.min_wavelength_m()), hi = std::min(hi, other.max_wavelength_m());
  if (!(hi > lo)) throw std::invalid_argument("spectrum product: the two spectra do not overlap");
  const Eigen::ArrayXd grid = union_grid({this, &other}, lo, hi);
  const Extrapolation rule = (extrapolation_ == Extrapolation::clamp && other.extrapolation_ == Extrapolation::clamp)
                                 ? Extrapolation::clamp
                                 : Extrapolation::zero;
  return Spectrum(grid, (*this)(grid) * other(grid), unit.empty() ? unit_ + " " + other.unit_ : std::move(unit),
                  rule);
}

double Spectrum::peak_value() const { return value_.maxCoeff(); }
double Spectrum::peak_wavelength_m() const {
  Eigen::Index i = 0;
  value_.maxCoeff(&i);
  return wavelength_m_(i);
}

double Spectrum::integral(double lo_m, double hi_m) const { return band_integral({this}, lo_m, hi_m); }

Eigen::ArrayXd union_grid(std::initializer_list<const Spectrum*> spectra, double lo_m, double hi_m) {
  std::vector<double> nodes{lo_m, hi_m};
  for (const Spectrum* s : spectra) {
    if (s->extrapolation() == Extrapolation::clamp && s->size() == 2 && s->value()(0) == s->value()(1)) continue;
    const auto& grid = s->wavelength_m();
    const double* begin = grid.data();
    const double* end = begin + grid.size();
    for (const double* p = std::upper_bound(begin, end, lo_m); p != end && *p < hi_m; ++p) nodes.push_back(*p);
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return Eigen::Map<Eigen::ArrayXd>(nodes.data(), static_cast<Eigen::Index>(nodes.size()));
}

double band_integral(std::initializer_list<const Spectrum*> spectra, double lo_m, double hi_m,
                     const std::function<double(double)>& weight) {
  // A zero-extrapolated spectrum is 0 outside its grid, and so is the product: integrate over the overlap
  // only. Otherwise the trapezoid from a node outside the grid to the grid's first point would ramp from 0
  // to the end value and add area the function does not have (a spectrum of 1 on [1, 2] integrated over
  // [0, 3] gave 2 instead of 1).
  for (const Spectrum* s : spectra) {
    if (s->extrapolation() != Extrapolation::zero) continue;
    if (s->empty()) return 0.0;
    lo_m = std::max(lo_m, s->min_wavelength_m());
    hi_m = std::min(hi_m, s->max_wavelength_m());
  }
  if (!(hi_m > lo_m)) return 0.0;
  const Eigen::ArrayXd grid = union_grid(spectra, lo_m, hi_m);
  Eigen::ArrayXd f = Eigen::ArrayXd::Ones(grid.size());
  for (const Spectrum* s : spectra) f *= (*s)(grid);
  if (weight)
    for (Eigen::Index i = 0; i < grid.size(); ++i) f(i) *= weight(grid(i));
  const Eigen::Index n = grid.size();
  const Eigen::ArrayXd widths = grid.tail(n - 1) - grid.head(n - 1);
  return 0.5 * (widths * (f.tail(n - 1) + f.head(n - 1))).sum();
}

}  // namespace radchain

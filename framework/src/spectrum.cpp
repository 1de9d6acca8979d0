#include "radchain/spectrum.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace radchain {
namespace {

// Spectrum::operator()(double) at abscissae that mostly increase: the same arithmetic, with the bracketing index
// carried from one point to the next instead of a binary search per point (band integrals and products evaluate
// spectra on sorted grids). A point below the previous one falls back to the binary search.
class Cursor {
 public:
  explicit Cursor(const Spectrum& s)
      : w_(s.wavelength_m().data()), v_(s.value().data()), n_(s.size()),
        clamp_(s.extrapolation() == Extrapolation::clamp) {}

  double operator()(double x) {
    if (n_ == 0) return 0.0;
    if (x <= w_[0]) return (x == w_[0] || clamp_) ? v_[0] : 0.0;
    if (x >= w_[n_ - 1]) return (x == w_[n_ - 1] || clamp_) ? v_[n_ - 1] : 0.0;
    if (w_[hi_ - 1] > x) hi_ = std::upper_bound(w_, w_ + n_, x) - w_;
    while (w_[hi_] <= x) ++hi_;  // first grid point > x (exists: x < w[n-1])
    const Eigen::Index lo = hi_ - 1;
    const double t = (x - w_[lo]) / (w_[hi_] - w_[lo]);
    return v_[lo] + t * (v_[hi_] - v_[lo]);
  }

 private:
  const double* w_;
  const double* v_;
  Eigen::Index n_;
  bool clamp_;
  Eigen::Index hi_ = 1;
};

bool is_constant(const Spectrum& s) {
  return s.extrapolation() == Extrapolation::clamp && s.size() == 2 && s.value()(0) == s.value()(1);
}

// The nodes of union_grid() (lo, hi and every grid point strictly between them of each non-constant spectrum,
// sorted, without repeats) into `nodes`, by merging the sorted grids instead of sorting their concatenation.
// Needs lo < hi.
void merge_nodes(std::initializer_list<const Spectrum*> spectra, double lo_m, double hi_m, std::vector<double>& nodes) {
  struct Range {
    const double* next;
    const double* end;
  };
  Range ranges[8];
  std::size_t k = 0;
  std::size_t total = 2;
  bool many = false;  // more grids than `ranges` holds: sort their concatenation instead
  for (const Spectrum* s : spectra) {
    if (is_constant(*s)) continue;
    const double* begin = s->wavelength_m().data();
    const double* end = begin + s->size();
    const double* first = std::upper_bound(begin, end, lo_m);  // > lo
    const double* last = std::lower_bound(first, end, hi_m);   // < hi
    if (first == last) continue;
    if (k < std::size(ranges)) ranges[k++] = Range{first, last};
    else many = true;
    total += static_cast<std::size_t>(last - first);
  }
  if (many) {
    nodes.assign({lo_m, hi_m});
    for (const Spectrum* s : spectra) {
      if (is_constant(*s)) continue;
      const double* begin = s->wavelength_m().data();
      const double* end = begin + s->size();
      nodes.insert(nodes.end(), std::upper_bound(begin, end, lo_m), std::lower_bound(begin, end, hi_m));
    }
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    return;
  }
  nodes.resize(total);
  double* out = nodes.data();
  *out++ = lo_m;
  // Each grid is strictly increasing: repeats can only come from two grids sharing a point.
  if (k == 1) {
    out = std::copy(ranges[0].next, ranges[0].end, out);
  } else if (k == 2) {
    const double *a = ranges[0].next, *a_end = ranges[0].end, *b = ranges[1].next, *b_end = ranges[1].end;
    while (a != a_end && b != b_end) {
      const double x = *a, y = *b;
      *out++ = x < y ? x : y;
      a += x <= y;
      b += y <= x;
    }
    out = std::copy(a, a_end, out);
    out = std::copy(b, b_end, out);
  } else {
    while (true) {
      Range* smallest = nullptr;
      for (std::size_t i = 0; i < k; ++i)
        if (ranges[i].next != ranges[i].end && (!smallest || *ranges[i].next < *smallest->next)) smallest = &ranges[i];
      if (!smallest) break;
      const double x = *smallest->next++;
      if (x != out[-1]) *out++ = x;
    }
  }
  *out++ = hi_m;
  nodes.resize(static_cast<std::size_t>(out - nodes.data()));
}

// f[i] *= s(x[i]) for increasing x: Spectrum::operator()(double)'s arithmetic, bit for bit, in three runs (below
// the grid, inside it, above it) so that the inner loop has no boundary tests.
void multiply_by(const Spectrum& s, const double* x, double* f, std::size_t n) {
  const Eigen::Index m = s.size();
  if (m == 0) {
    for (std::size_t i = 0; i < n; ++i) f[i] *= 0.0;
    return;
  }
  const double* w = s.wavelength_m().data();
  const double* v = s.value().data();
  const bool clamp = s.extrapolation() == Extrapolation::clamp;
  const double w_first = w[0], w_last = w[m - 1];
  std::size_t i = 0;
  for (; i < n && x[i] <= w_first; ++i) f[i] *= (x[i] == w_first || clamp) ? v[0] : 0.0;
  Eigen::Index hi = 1;
  for (; i < n && x[i] < w_last; ++i) {
    const double xi = x[i];
    while (w[hi] <= xi) ++hi;  // first grid point > x
    const double t = (xi - w[hi - 1]) / (w[hi] - w[hi - 1]);
    f[i] *= v[hi - 1] + t * (v[hi] - v[hi - 1]);
  }
  for (; i < n; ++i) f[i] *= (x[i] == w_last || clamp) ? v[m - 1] : 0.0;
}

// Unweighted band integrals of large tables, remembered per thread with a copy of their inputs: a chain whose
// spectral phase re-runs (a sweep over a band limit, a solve over a spectral parameter) integrates the same source
// table again and again (the Sun's AM0 table with V(λ), its total). An entry is used only when every input is
// equal bit for bit, so the result is the one computing would give.
class IntegralMemo {
 public:
  static constexpr std::size_t min_points = 256;  // below this, integrating is cheaper than comparing

  const double* find(std::initializer_list<const Spectrum*> spectra, double lo, double hi) const {
    for (const Entry& e : entries_)
      if (e.matches(spectra, lo, hi)) return &e.result;
    return nullptr;
  }

  void store(std::initializer_list<const Spectrum*> spectra, double lo, double hi, double result) {
    Entry& e = entries_[next_++ % entries_.size()];
    e.lo = lo, e.hi = hi, e.result = result, e.count = spectra.size();
    e.data.clear();
    std::size_t i = 0;
    for (const Spectrum* s : spectra) {
      e.rule[i] = s->extrapolation();
      e.size[i] = s->size();
      e.data.insert(e.data.end(), s->wavelength_m().data(), s->wavelength_m().data() + s->size());
      e.data.insert(e.data.end(), s->value().data(), s->value().data() + s->size());
      ++i;
    }
  }

 private:
  struct Entry {
    std::size_t count = 0;  // 0: empty
    double lo = 0, hi = 0, result = 0;
    Extrapolation rule[8]{};
    Eigen::Index size[8]{};
    std::vector<double> data;  // per spectrum: its wavelengths, then its values

    bool matches(std::initializer_list<const Spectrum*> spectra, double lo_m, double hi_m) const {
      if (count == 0 || count != spectra.size() || lo != lo_m || hi != hi_m) return false;
      std::size_t i = 0;
      for (const Spectrum* s : spectra) {
        if (rule[i] != s->extrapolation() || size[i] != s->size()) return false;
        ++i;
      }
      const double* stored = data.data();
      for (const Spectrum* s : spectra) {
        const std::size_t bytes = static_cast<std::size_t>(s->size()) * sizeof(double);
        if (std::memcmp(stored, s->wavelength_m().data(), bytes) != 0) return false;
        stored += s->size();
        if (std::memcmp(stored, s->value().data(), bytes) != 0) return false;
        stored += s->size();
      }
      return true;
    }
  };
  std::array<Entry, 8> entries_;
  std::size_t next_ = 0;
};

// Scratch buffers of band_integral, reused between calls of a thread (a weight that itself integrates gets
// buffers of its own).
struct IntegralBuffers {
  std::vector<double> nodes, values;
  bool busy = false;
};

}  // namespace

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
  Cursor at(*this);
  for (Eigen::Index i = 0; i < x.size(); ++i) out(i) = at(x(i));
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
  std::vector<double> nodes;
  if (hi_m > lo_m) {
    merge_nodes(spectra, lo_m, hi_m, nodes);
  } else {  // degenerate or reversed limits: the sorted set {lo, hi}
    nodes = {std::min(lo_m, hi_m), std::max(lo_m, hi_m)};
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  }
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
  // No allocation in the steady state: a sweep over a spectral parameter integrates at every point.
  thread_local IntegralBuffers shared;
  IntegralBuffers own;
  IntegralBuffers& buffers = shared.busy ? own : shared;
  buffers.busy = true;
  struct Release {
    IntegralBuffers& b;
    ~Release() { b.busy = false; }
  } release{buffers};
  thread_local IntegralMemo memo;
  std::size_t points = 0;
  for (const Spectrum* s : spectra) points += static_cast<std::size_t>(s->size());
  const bool memoised = !weight && points >= IntegralMemo::min_points && spectra.size() <= 8;
  if (memoised)
    if (const double* known = memo.find(spectra, lo_m, hi_m)) return *known;

  std::vector<double>& grid = buffers.nodes;
  std::vector<double>& f = buffers.values;
  merge_nodes(spectra, lo_m, hi_m, grid);
  const Eigen::Index n = static_cast<Eigen::Index>(grid.size());
  f.assign(grid.size(), 1.0);
  for (const Spectrum* s : spectra) multiply_by(*s, grid.data(), f.data(), grid.size());
  if (weight)
    for (std::size_t i = 0; i < grid.size(); ++i) f[i] *= weight(grid[i]);
  // The trapezoid sum as one Eigen reduction over unaligned blocks: the summation order, hence every bit of the
  // result, is that of the array expression used before the buffers were reused.
  const Eigen::Map<const Eigen::ArrayXd> x(grid.data(), n), y(f.data(), n);
  const double result = 0.5 * ((x.tail(n - 1) - x.head(n - 1)) * (y.tail(n - 1) + y.head(n - 1))).sum();
  if (memoised) memo.store(spectra, lo_m, hi_m, result);
  return result;
}

}  // namespace radchain

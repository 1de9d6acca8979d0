#include "radchain/spectrum.hpp"

#include "radchain/constants.hpp"

#include <algorithm>
#include <limits>
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

}  // namespace

Spectrum::Spectrum(Eigen::ArrayXd wavelength_m, Eigen::ArrayXd value, std::string unit, Extrapolation extrapolation) {
  if (wavelength_m.size() != value.size()) throw std::invalid_argument("spectrum: grid and values differ in size");
  if (wavelength_m.size() < 2) throw std::invalid_argument("spectrum: fewer than 2 points");
  for (Eigen::Index i = 1; i < wavelength_m.size(); ++i)
    if (!(wavelength_m(i) > wavelength_m(i - 1)))
      throw std::invalid_argument("spectrum: wavelengths are not strictly increasing");
  const Eigen::Index n = wavelength_m.size();
  Eigen::ArrayXd slope = (value.tail(n - 1) - value.head(n - 1)) / (wavelength_m.tail(n - 1) - wavelength_m.head(n - 1));
  data_ = std::make_shared<const Data>(
      Data{std::move(wavelength_m), std::move(value), std::move(slope), std::move(unit), extrapolation});
}

const Spectrum::Data& Spectrum::empty_data() {
  static const Data empty{};
  return empty;
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
  const Eigen::ArrayXd& w = wavelength_m();
  const Eigen::ArrayXd& v = value();
  const Eigen::Index n = w.size();
  if (n == 0) return 0.0;
  const bool clamp = extrapolation() == Extrapolation::clamp;
  if (x <= w(0)) return (x == w(0) || clamp) ? v(0) : 0.0;
  if (x >= w(n - 1)) return (x == w(n - 1) || clamp) ? v(n - 1) : 0.0;
  const double* begin = w.data();
  const Eigen::Index hi = std::upper_bound(begin, begin + n, x) - begin;  // first grid point > x
  const Eigen::Index lo = hi - 1;
  const double t = (x - w(lo)) / (w(hi) - w(lo));
  return v(lo) + t * (v(hi) - v(lo));
}

Eigen::ArrayXd Spectrum::operator()(const Eigen::ArrayXd& x) const {
  Eigen::ArrayXd out(x.size());
  Cursor at(*this);
  for (Eigen::Index i = 0; i < x.size(); ++i) out(i) = at(x(i));
  return out;
}

Spectrum Spectrum::scaled(double k, std::string unit) const {
  return Spectrum(wavelength_m(), value() * k, unit.empty() ? this->unit() : std::move(unit), extrapolation());
}

Spectrum Spectrum::resampled(const Eigen::ArrayXd& grid) const {
  return Spectrum(grid, (*this)(grid), unit(), extrapolation());
}

Spectrum Spectrum::product(const Spectrum& other, std::string unit) const {
  // Where one factor is zero by extrapolation the product is zero: keep only the overlap of the supports.
  double lo = std::min(min_wavelength_m(), other.min_wavelength_m());
  double hi = std::max(max_wavelength_m(), other.max_wavelength_m());
  if (extrapolation() == Extrapolation::zero) lo = std::max(lo, min_wavelength_m()), hi = std::min(hi, max_wavelength_m());
  if (other.extrapolation() == Extrapolation::zero)
    lo = std::max(lo, other.min_wavelength_m()), hi = std::min(hi, other.max_wavelength_m());
  if (!(hi > lo)) throw std::invalid_argument("spectrum product: the two spectra do not overlap");
  const Eigen::ArrayXd grid = union_grid({this, &other}, lo, hi);
  const Extrapolation rule = (extrapolation() == Extrapolation::clamp && other.extrapolation() == Extrapolation::clamp)
                                 ? Extrapolation::clamp
                                 : Extrapolation::zero;
  return Spectrum(grid, (*this)(grid) * other(grid), unit.empty() ? this->unit() + " " + other.unit() : std::move(unit),
                  rule);
}

double Spectrum::peak_value() const { return value().maxCoeff(); }
double Spectrum::peak_wavelength_m() const {
  Eigen::Index i = 0;
  value().maxCoeff(&i);
  return wavelength_m()(i);
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

namespace {

constexpr double photons_per_joule_per_metre = 1.0 / (constants::planck_J_s * constants::speed_of_light_m_s);

// One spectrum walked along increasing abscissae: `next` is the first grid index with λ ≥ x.
struct Track {
  const double *w, *v, *slope;
  Eigen::Index n, next;
  bool clamp;

  Track(const Spectrum& s, double x, const double* slopes)
      : w(s.wavelength_m().data()), v(s.value().data()), slope(slopes), n(s.size()),
        next(std::lower_bound(w, w + n, x) - w), clamp(s.extrapolation() == Extrapolation::clamp) {}
  Track(const Track& t, double x) : Track(t) { next = std::lower_bound(w, w + n, x) - w; }
  // The value at x, for w[next - 1] < x ≤ w[next] (linear, through the precomputed slope), or outside the grid.
  double at(double x) const {
    if (next == 0) return (clamp || x == w[0]) ? v[0] : 0.0;
    if (next == n) return clamp ? v[n - 1] : 0.0;
    return x == w[next] ? v[next] : v[next - 1] + (x - w[next - 1]) * slope[next - 1];  // exact at the nodes
  }
  double next_node() const { return next < n ? w[next] : std::numeric_limits<double>::infinity(); }
};

// K ≥ 2 spectra: the trapezoid on the merged grids, streaming (no node array). Every track's next node is ≥ the
// current one, so the next node is their minimum, and each track advances by at most one node per step.
template <std::size_t K>
double merged_integral(Track (&tracks)[K], double lo, double hi, Weight weight) {
  auto integrand = [&](double x) {
    double y = weight == Weight::photons ? x * photons_per_joule_per_metre : 1.0;
    for (const Track& t : tracks) y *= t.at(x);
    return y;
  };
  double x_prev = lo, y_prev = integrand(lo), sum = 0.0;
  for (Track& t : tracks) t.next += (t.next < t.n && t.w[t.next] <= lo);
  while (true) {
    double x = hi;
    for (const Track& t : tracks) x = std::min(x, t.next_node());
    const double y = integrand(x);
    sum += (x - x_prev) * (y + y_prev);
    if (x >= hi) break;
    for (Track& t : tracks) t.next += (t.next < t.n && t.w[t.next] <= x);
    x_prev = x, y_prev = y;
  }
  return 0.5 * sum;
}

// Two zero-extrapolated spectra (a source times a response: the common case). The limits lie inside both grids,
// so every node between them has a segment on each side and the loop needs no boundary tests: values come from
// the segment's right end, f = v[i] − (λ[i] − x)·slope, which is exact at the spectrum's own nodes.
// The weight is a template parameter: a test of it per node costs a fifth of the loop. Not inlined: inside
// band_integral the loop ran out of registers and kept x_prev on the stack (1.2 µs for E-490 × V(λ), 1.0 µs so).
template <Weight weight>
[[gnu::noinline]] double pair_integral(const Track& a, const Track& b, double lo, double hi) {
  auto weighted = [](double x, double y) { return weight == Weight::photons ? y * x * photons_per_joule_per_metre : y; };
  const double *wa = a.w, *va = a.v, *sa = a.slope, *wb = b.w, *vb = b.v, *sb = b.slope;
  Eigen::Index ia = std::upper_bound(wa, wa + a.n, lo) - wa, ib = std::upper_bound(wb, wb + b.n, lo) - wb;
  double x_prev = lo, y_prev = weighted(lo, a.at(lo) * b.at(lo)), sum = 0.0;
  // Nodes strictly inside (lo, hi): ia, ib < n because hi ≤ both grids' last points. Branches, not selects: the
  // grids interleave in patterns the predictor learns, and a predicted branch takes the index update off the
  // loop's critical path.
  while (true) {
    const double xa = wa[ia], xb = wb[ib];
    double x, y;
    if (xa < xb) {
      x = xa;
      y = va[ia] * (vb[ib] - (xb - x) * sb[ib - 1]);
      ++ia;
    } else if (xb < xa) {
      x = xb;
      y = (va[ia] - (xa - x) * sa[ia - 1]) * vb[ib];
      ++ib;
    } else {
      x = xa;
      y = va[ia] * vb[ib];
      ++ia, ++ib;
    }
    if (x >= hi) break;
    y = weighted(x, y);
    sum += (x - x_prev) * (y + y_prev);
    x_prev = x, y_prev = y;
  }
  const Track end_a(a, hi), end_b(b, hi);
  const double y_hi = weighted(hi, end_a.at(hi) * end_b.at(hi));
  return 0.5 * (sum + (hi - x_prev) * (y_hi + y_prev));
}

// Σ (x[i+1] − x[i]) (y[i+1] + y[i]) for i < m, with y = v, or y = v·x for photons. Sixteen partial sums in a fixed
// order, so every machine gets the same bits: the default build runs the 4-wide vectors as SSE2 pairs, and the
// AVX2 copy below runs them four at a time, chosen at run time (E-490's 1,697 points: 0.43 µs on this machine's
// EPYC, 0.63 µs through Eigen's SSE2 redux, whose packets are fixed when it is compiled). No FMA target: a fused
// multiply-add would round differently from the default build.
template <bool photons>
[[gnu::always_inline]] inline double trapezoid_sum(const double* x, const double* v, Eigen::Index m) {
  using v4 = double __attribute__((vector_size(32)));
  constexpr int block = 16;
  v4 sum[block / 4] = {};
  double x_tail[block + 1], v_tail[block + 1];
  for (Eigen::Index i = 0; i < m; i += block) {
    const double *xb = x + i, *vb = v + i;
    if (m - i < block) {  // the last, short block: the last node repeated adds terms (x − x)(…) = 0
      std::fill(std::copy(xb, x + m + 1, x_tail), x_tail + block + 1, x[m]);
      std::fill(std::copy(vb, v + m + 1, v_tail), v_tail + block + 1, v[m]);
      xb = x_tail, vb = v_tail;
    }
#pragma GCC unroll 4  // the partial sums stay in registers
    for (int k = 0; k < block / 4; ++k) {
      v4 x0, x1, v0, v1;  // unaligned loads (memcpy): the tables promise no alignment
      __builtin_memcpy(&x0, xb + 4 * k, sizeof x0), __builtin_memcpy(&x1, xb + 4 * k + 1, sizeof x1);
      __builtin_memcpy(&v0, vb + 4 * k, sizeof v0), __builtin_memcpy(&v1, vb + 4 * k + 1, sizeof v1);
      sum[k] += photons ? (x1 - x0) * (v1 * x1 + v0 * x0) : (x1 - x0) * (v1 + v0);
    }
  }
  const v4 s = (sum[0] + sum[1]) + (sum[2] + sum[3]);
  return (s[0] + s[1]) + (s[2] + s[3]);
}

template <bool photons>
double trapezoid_sum_default(const double* x, const double* v, Eigen::Index m) {
  return trapezoid_sum<photons>(x, v, m);
}

template <bool photons>
[[gnu::target("avx2")]] double trapezoid_sum_avx2(const double* x, const double* v, Eigen::Index m) {
  return trapezoid_sum<photons>(x, v, m);
}

template <bool photons>
double trapezoid_sum_dispatched(const double* x, const double* v, Eigen::Index m) {
  static const bool avx2 = __builtin_cpu_supports("avx2");
  return avx2 ? trapezoid_sum_avx2<photons>(x, v, m) : trapezoid_sum_default<photons>(x, v, m);
}

// One spectrum: its own grid between the limits, the end values interpolated; the inner sum runs over the table
// itself.
double single_integral(const Spectrum& s, const double* slopes, double lo, double hi, Weight weight) {
  const double* w = s.wavelength_m().data();
  const Eigen::Index n = s.size();
  const Track at_lo(s, lo, slopes), at_hi(s, hi, slopes);
  const double k = weight == Weight::photons ? photons_per_joule_per_metre : 0.0;
  auto weighted = [&](double x, double y) { return weight == Weight::photons ? y * x * k : y; };
  const double y_lo = weighted(lo, at_lo.at(lo)), y_hi = weighted(hi, at_hi.at(hi));
  const Eigen::Index first = std::upper_bound(w, w + n, lo) - w;  // interior nodes: lo < w[i] < hi
  const Eigen::Index last = at_hi.next;                           // first index with w ≥ hi
  if (first >= last) return 0.5 * (hi - lo) * (y_hi + y_lo);
  const Eigen::Index m = last - first;
  const double *x = w + first, *v = s.value().data() + first;
  const double inner = weight == Weight::photons ? trapezoid_sum_dispatched<true>(x, v, m - 1) * k
                                                 : trapezoid_sum_dispatched<false>(x, v, m - 1);
  const double y_first = weighted(x[0], v[0]), y_last = weighted(x[m - 1], v[m - 1]);
  return 0.5 * ((x[0] - lo) * (y_first + y_lo) + inner + (hi - x[m - 1]) * (y_hi + y_last));
}

}  // namespace

double band_integral(std::initializer_list<const Spectrum*> spectra, double lo_m, double hi_m, Weight weight) {
  // A zero-extrapolated spectrum is 0 outside its grid, and so is the product: integrate over the overlap
  // only. Otherwise the trapezoid from a node outside the grid to the grid's first point would ramp from 0
  // to the end value and add area the function does not have (a spectrum of 1 on [1, 2] integrated over
  // [0, 3] gave 2 instead of 1).
  double factor = 1.0;  // constant spectra (a flat transmittance) multiply; their grids add no nodes
  const Spectrum* varying[8];
  std::size_t k = 0;
  for (const Spectrum* s : spectra) {
    if (s->extrapolation() == Extrapolation::zero) {
      if (s->empty()) return 0.0;
      lo_m = std::max(lo_m, s->min_wavelength_m());
      hi_m = std::min(hi_m, s->max_wavelength_m());
    }
    if (is_constant(*s)) factor *= s->value()(0);
    else if (k < std::size(varying)) varying[k++] = s;
    else throw std::invalid_argument("band_integral: more than 8 spectra in one product");
  }
  if (!(hi_m > lo_m)) return 0.0;
  auto track = [&](std::size_t i) { return Track(*varying[i], lo_m, varying[i]->data().slope.data()); };
  switch (k) {
    case 0: {
      const double y_lo = weight == Weight::photons ? lo_m * photons_per_joule_per_metre : 1.0;
      const double y_hi = weight == Weight::photons ? hi_m * photons_per_joule_per_metre : 1.0;
      return factor * 0.5 * (hi_m - lo_m) * (y_lo + y_hi);
    }
    case 1: return factor * single_integral(*varying[0], varying[0]->data().slope.data(), lo_m, hi_m, weight);
    case 2: {
      Track t[2] = {track(0), track(1)};
      if (!t[0].clamp && !t[1].clamp)
        return factor * (weight == Weight::photons ? pair_integral<Weight::photons>(t[0], t[1], lo_m, hi_m)
                                                   : pair_integral<Weight::energy>(t[0], t[1], lo_m, hi_m));
      return factor * merged_integral(t, lo_m, hi_m, weight);
    }
    case 3: {
      Track t[3] = {track(0), track(1), track(2)};
      return factor * merged_integral(t, lo_m, hi_m, weight);
    }
    default: {
      double result = factor;  // rare: four or more varying factors; fold the last ones into a product first
      Spectrum rest = *varying[3];
      for (std::size_t i = 4; i < k; ++i) rest = rest.product(*varying[i]);
      Track t[4] = {track(0), track(1), track(2), Track(rest, lo_m, rest.data().slope.data())};
      return result * merged_integral(t, lo_m, hi_m, weight);
    }
  }
}

}  // namespace radchain

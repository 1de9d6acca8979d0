// ISO 12233-style slanted-edge MTF (checks.hpp).
#include "fftw.hpp"
#include "radchain/imaging/checks.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace radchain::render {

namespace {
constexpr double pi = std::numbers::pi;
double sinc(double x) { return std::abs(x) < 1e-12 ? 1.0 : std::sin(pi * x) / (pi * x); }
}  // namespace

EdgeMtf slanted_edge_mtf(const Image& image, int oversampling) {
  if (image.width < 16 || image.height < 8) throw std::invalid_argument("slanted_edge_mtf: the image must be at least 16 × 8 pixels");
  if (oversampling < 1 || oversampling > 16) throw std::invalid_argument("slanted_edge_mtf: oversampling must lie in 1..16");
  const int w = image.width, h = image.height;

  // 1. The edge in each row: centroid of the row's derivative (sign of the edge's polarity).
  double polarity = 0;
  for (int y = 0; y < h; ++y) polarity += image(w - 1, y) - image(0, y);
  const double sign = polarity >= 0 ? 1.0 : -1.0;
  std::vector<double> rows, centres;
  for (int y = 0; y < h; ++y) {
    double sum = 0, moment = 0;
    for (int x = 1; x < w - 1; ++x) {
      const double d = sign * 0.5 * (image(x + 1, y) - image(x - 1, y));
      sum += d;
      moment += d * x;
    }
    if (sum > 0) {
      rows.push_back(y);
      centres.push_back(moment / sum);
    }
  }
  if (rows.size() < 4) throw std::invalid_argument("slanted_edge_mtf: no edge found");
  // 2. Least-squares line x = a + b y.
  const double n = static_cast<double>(rows.size());
  double sy = 0, sx = 0, syy = 0, sxy = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    sy += rows[i];
    sx += centres[i];
    syy += rows[i] * rows[i];
    sxy += rows[i] * centres[i];
  }
  const double b = (n * sxy - sy * sx) / (n * syy - sy * sy), a = (sx - b * sy) / n;
  const double cos_theta = 1.0 / std::sqrt(1.0 + b * b);

  // 3. Every pixel's distance to the edge along its normal, binned `oversampling` times finer than a pixel.
  double reach = 1e300;  // the distance every row covers on both sides
  for (int y = 0; y < h; ++y) {
    const double c = a + b * y;
    reach = std::min({reach, c * cos_theta, (w - 1 - c) * cos_theta});
  }
  const int half_bins = static_cast<int>(std::floor(reach * oversampling)) - 1;
  if (half_bins < 8 * oversampling / 2) throw std::invalid_argument("slanted_edge_mtf: the edge is too close to the image side");
  const int bins = 2 * half_bins;
  std::vector<double> esf(static_cast<std::size_t>(bins), 0.0), count(esf.size(), 0.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double s = (x - (a + b * y)) * cos_theta;
      const auto bin = static_cast<int>(std::floor(s * oversampling)) + half_bins;
      if (bin < 0 || bin >= bins) continue;
      esf[static_cast<std::size_t>(bin)] += image(x, y);
      count[static_cast<std::size_t>(bin)] += 1.0;
    }
  for (int i = 0; i < bins; ++i)
    if (count[static_cast<std::size_t>(i)] > 0) esf[static_cast<std::size_t>(i)] /= count[static_cast<std::size_t>(i)];
  for (int i = 0; i < bins; ++i) {
    if (count[static_cast<std::size_t>(i)] > 0) continue;
    // An empty bin: the mean of its nearest filled neighbours.
    int l = i - 1, r = i + 1;
    while (l >= 0 && count[static_cast<std::size_t>(l)] == 0) --l;
    while (r < bins && count[static_cast<std::size_t>(r)] == 0) ++r;
    if (l < 0 && r >= bins) throw std::invalid_argument("slanted_edge_mtf: no samples");
    const double lv = l >= 0 ? esf[static_cast<std::size_t>(l)] : esf[static_cast<std::size_t>(r)];
    const double rv = r < bins ? esf[static_cast<std::size_t>(r)] : lv;
    esf[static_cast<std::size_t>(i)] = 0.5 * (lv + rv);
  }

  // 4. LSF by the central difference [−½, 0, ½], Hamming window centred on the LSF's centroid.
  auto lsf = detail::real_buffer(static_cast<std::size_t>(bins));
  double total = 0, moment = 0;
  for (int i = 0; i < bins; ++i) {
    const double d = (i == 0 || i == bins - 1) ? 0.0 : 0.5 * (esf[static_cast<std::size_t>(i + 1)] - esf[static_cast<std::size_t>(i - 1)]);
    lsf[static_cast<std::size_t>(i)] = sign * d;
    total += std::abs(d);
    moment += std::abs(d) * i;
  }
  const double centre = total > 0 ? moment / total : bins / 2.0;
  for (int i = 0; i < bins; ++i) {
    const double u = (i - centre) / bins;
    lsf[static_cast<std::size_t>(i)] *= std::abs(u) <= 0.5 ? 0.54 + 0.46 * std::cos(2.0 * pi * u) : 0.08;
  }

  // 5. |DFT| / DC, then the transfer of the difference and of the bin width divided out.
  auto spectrum = detail::complex_buffer(static_cast<std::size_t>(bins / 2 + 1));
  const detail::Plan plan = detail::Plan::r2c_1d(bins, lsf.get(), spectrum.get());
  plan.execute();
  const double dc = std::hypot(spectrum[0][0], spectrum[0][1]);
  const double bin_width = 1.0 / oversampling;  // pixels
  EdgeMtf out;
  out.angle_deg = std::atan(b) * 180.0 / pi;
  for (int j = 0; j <= bins / 2; ++j) {
    const double nu = j / (bins * bin_width);  // cycles per pixel
    if (nu > 1.0 + 1e-12) break;
    const double difference = std::abs(sinc(2.0 * nu * bin_width));  // sin(2πνΔ)/(2πνΔ)
    const double box = std::abs(sinc(nu * bin_width));
    out.frequency_per_px.push_back(nu);
    out.mtf.push_back(std::hypot(spectrum[static_cast<std::size_t>(j)][0], spectrum[static_cast<std::size_t>(j)][1]) / dc /
                      (difference * box));
  }
  return out;
}

}  // namespace radchain::render

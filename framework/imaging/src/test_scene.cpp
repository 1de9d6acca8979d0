// The project's test scene: bars, edges, low-contrast squares and a sector star (earth_scene.hpp).
#include "radchain/imaging/earth_scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace radchain::render {

namespace {

// ∫_{-∞}^{u} clamp(v, 0, 1) dv
double clamp_integral(double u) {
  if (u <= 0) return 0.0;
  if (u < 1) return 0.5 * u * u;
  return u - 0.5;
}

// Fraction of pixel [x, x+1] × [y, y+1] right of the line X = cx + (Y − cy) t.
double right_of_line(int x, int y, double cx, double cy, double t) {
  const double c0 = x + 1.0 - cx - (y - cy) * t;  // overlap width along X at Y = y is clamp(c0, 0, 1)
  if (std::abs(t) < 1e-12) return std::clamp(c0 - 0.5 * t, 0.0, 1.0);
  return (clamp_integral(c0) - clamp_integral(c0 - t)) / t;
}

// Area of [x, x+1] × [y, y+1] ∩ [x0, x1] × [y0, y1].
double rectangle_overlap(int x, int y, double x0, double y0, double x1, double y1) {
  const double w = std::max(0.0, std::min(x + 1.0, x1) - std::max(static_cast<double>(x), x0));
  const double h = std::max(0.0, std::min(y + 1.0, y1) - std::max(static_cast<double>(y), y0));
  return w * h;
}

void paint_rectangle(Image& image, double x0, double y0, double x1, double y1, double background, double value) {
  const int xa = std::max(0, static_cast<int>(std::floor(x0))), xb = std::min(image.width - 1, static_cast<int>(std::ceil(x1)));
  const int ya = std::max(0, static_cast<int>(std::floor(y0))), yb = std::min(image.height - 1, static_cast<int>(std::ceil(y1)));
  for (int y = ya; y <= yb; ++y)
    for (int x = xa; x <= xb; ++x) {
      const double a = rectangle_overlap(x, y, x0, y0, x1, y1);
      if (a > 0) image(x, y) = static_cast<float>(image(x, y) + a * (value - background));
    }
}

}  // namespace

Image make_flat_scene(int width_px, int height_px, double reflectance) {
  return Image(width_px, height_px, static_cast<float>(reflectance));
}

Image make_edge_scene(int width_px, int height_px, double angle_deg, double left, double right) {
  Image image(width_px, height_px);
  const double t = std::tan(angle_deg * std::numbers::pi / 180.0);
  for (int y = 0; y < height_px; ++y)
    for (int x = 0; x < width_px; ++x)
      image(x, y) = static_cast<float>(left + (right - left) * right_of_line(x, y, width_px / 2.0, height_px / 2.0, t));
  return image;
}

Image make_test_scene(const TestSceneOptions& o) {
  if (o.size_px < 64 || o.size_px > 16384) throw std::invalid_argument("test scene: size must lie in 64..16384 pixels");
  if (!(o.sampling_m > 0 && o.bar_unit_m > 0)) throw std::invalid_argument("test scene: sampling and bar unit must be > 0");
  const int n = o.size_px, q = n / 2;
  const double unit = o.bar_unit_m / o.sampling_m;  // pixels per bar unit
  Image image(n, n, static_cast<float>(o.background));

  // Top left: the slanted edge.
  const double t = std::tan(o.edge_angle_deg * std::numbers::pi / 180.0);
  for (int y = 0; y < q; ++y)
    for (int x = 0; x < q; ++x)
      image(x, y) = static_cast<float>(o.background + (o.bright - o.background) * right_of_line(x, y, q / 2.0, q / 2.0, t));

  // Top right: three-bar groups, vertical then horizontal, widths 0.5 … 4 bar units.
  double top = 2.0 * unit;
  for (double f : {0.5, 0.7, 1.0, 1.4, 2.0, 2.8, 4.0}) {
    const double w = f * unit, left = q + 2.0 * unit;
    if (top + 5 * w > q - unit || left + 10 * w + 2 * unit > n) break;
    for (int b = 0; b < 3; ++b) {
      paint_rectangle(image, left + 2 * b * w, top, left + (2 * b + 1) * w, top + 5 * w, o.background, o.bright);
      const double hx = left + 5 * w + 2 * unit;
      paint_rectangle(image, hx, top + 2 * b * w, hx + 5 * w, top + (2 * b + 1) * w, o.background, o.bright);
    }
    top += 5 * w + 2 * unit;
  }

  // Bottom left: low-contrast squares background + k Δρ, k = 1, 2, 4, 8.
  const double side = std::min(16.0 * unit, q / 2.5), gap = (q - 2 * side) / 3.0;
  int k = 0;
  for (int row = 0; row < 2; ++row)
    for (int col = 0; col < 2; ++col) {
      const double x0 = gap + col * (side + gap), y0 = q + gap + row * (side + gap);
      paint_rectangle(image, x0, y0, x0 + side, y0 + side, o.background, o.background + (1 << k++) * o.contrast);
    }

  // Bottom right: 16 sectors (alternating), 4 × 4 sub-samples per pixel.
  const double cx = q + q / 2.0, cy = q + q / 2.0, radius = 0.42 * q;
  for (int y = q; y < n; ++y)
    for (int x = q; x < n; ++x) {
      double sum = 0;
      for (int sy = 0; sy < 4; ++sy)
        for (int sx = 0; sx < 4; ++sx) {
          const double px = x + (sx + 0.5) / 4.0 - cx, py = y + (sy + 0.5) / 4.0 - cy;
          const bool inside = px * px + py * py < radius * radius;
          const double angle = std::atan2(py, px) + std::numbers::pi;
          const bool bright = inside && static_cast<int>(std::floor(angle / (2.0 * std::numbers::pi) * 16.0)) % 2 == 0;
          sum += bright ? o.bright : o.background;
        }
      image(x, y) = static_cast<float>(sum / 16.0);
    }
  return image;
}

}  // namespace radchain::render

// Inline SVG line plots and tornado bars for the HTML report (radchain/batch/svg_plot.hpp).
#include "radchain/batch/svg_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace radchain::svg {
namespace {

constexpr double char_width = 6.8;  // average advance of a 12 px sans-serif glyph: for layout estimates only
constexpr int legend_row = 20;
const char* const font = "font-family=\"DejaVu Sans, Liberation Sans, Arial, sans-serif\"";

double text_width(const std::string& text) {
  std::size_t glyphs = 0;  // UTF-8: count the bytes that start a code point
  for (unsigned char c : text) glyphs += (c & 0xC0) != 0x80;
  return static_cast<double>(glyphs) * char_width;
}

std::string number(double v) { return fmt::format("{:.2f}", v); }

// A tick value as text: no binary noise (0.30000000000000004), 6 significant digits at most.
std::string tick_text(double v, double step) {
  if (step > 0) v = std::round(v / step) * step;
  if (std::abs(v) < step * 1e-9) v = 0;
  return fmt::format("{:.6g}", v);
}

// A log axis's tick: plain for 10^-4 … 10^4 (and 2 and 5 times them), else m·10^k with a raised exponent.
std::string decade_text(double v) {
  const int k = static_cast<int>(std::floor(std::log10(v) + 1e-9));
  const long mantissa = std::lround(v / std::pow(10.0, k));
  if (k >= -4 && k <= 4) return fmt::format("{:g}", static_cast<double>(mantissa) * std::pow(10.0, k));
  return fmt::format("{}10<tspan dy=\"-5\" font-size=\"9\">{}</tspan>", mantissa == 1 ? "" : fmt::format("{}×", mantissa), k);
}

struct Scale {
  double lo = 0, hi = 1, px_lo = 0, px_hi = 1;
  bool log = false;
  std::vector<double> ticks;
  double step = 0;  // linear ticks' step
  double operator()(double v) const {
    const double t = log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo)) : (v - lo) / (hi - lo);
    return px_lo + t * (px_hi - px_lo);
  }
  bool contains(double v) const { return std::isfinite(v) && (!log || v > 0) && v >= lo && v <= hi; }
};

bool drawable(double v, bool log) { return std::isfinite(v) && (!log || v > 0); }

Scale make_scale(const Axis& axis, const std::vector<double>& data, double px_lo, double px_hi) {
  double lo = INFINITY, hi = -INFINITY;
  for (double v : data)
    if (drawable(v, axis.log)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!std::isfinite(lo)) lo = axis.log ? 0.1 : 0, hi = axis.log ? 10 : 1;  // no data: an empty frame
  Scale s;
  s.log = axis.log;
  s.px_lo = px_lo;
  s.px_hi = px_hi;
  if (axis.log) {
    if (!std::isnan(axis.min) && axis.min > 0) lo = axis.min;
    if (!std::isnan(axis.max) && axis.max > 0) hi = axis.max;
    const double decade_lo = std::floor(std::log10(lo) + 1e-9), decade_hi = std::ceil(std::log10(hi) - 1e-9);
    if (decade_hi - decade_lo > 3) {  // many decades: whole ones
      s.lo = std::isnan(axis.min) ? std::pow(10.0, decade_lo) : lo;
      s.hi = std::isnan(axis.max) ? std::pow(10.0, decade_hi) : hi;
    } else {  // a few: the data's range and a margin, so that the curve fills the plot
      const double pad = hi > lo ? std::pow(hi / lo, 0.03) : 2.0;
      s.lo = std::isnan(axis.min) ? lo / pad : lo;
      s.hi = std::isnan(axis.max) ? hi * pad : hi;
    }
    if (s.hi <= s.lo) s.hi = s.lo * 10;
    s.ticks = log_ticks(s.lo, s.hi);
    if (s.ticks.size() < 3) {  // label 1, 2 and 5 of each decade
      s.ticks.clear();
      for (double d = std::pow(10.0, std::floor(std::log10(s.lo))); d <= s.hi; d *= 10)
        for (double m : {1.0, 2.0, 5.0})
          if (d * m >= s.lo * (1 - 1e-9) && d * m <= s.hi * (1 + 1e-9)) s.ticks.push_back(d * m);
    }
  } else {
    if (!std::isnan(axis.min)) lo = axis.min;
    if (!std::isnan(axis.max)) hi = axis.max;
    if (hi <= lo) {
      const double pad = lo == 0 ? 1 : std::abs(lo) * 0.1;
      lo -= pad, hi += pad;
    }
    s.ticks = linear_ticks(lo, hi);
    s.step = s.ticks.size() > 1 ? s.ticks[1] - s.ticks[0] : hi - lo;
    // Out to the ticks around the data, unless the axis is fixed.
    s.lo = std::isnan(axis.min) ? std::min(lo, std::floor(lo / s.step + 1e-9) * s.step) : lo;
    s.hi = std::isnan(axis.max) ? std::max(hi, std::ceil(hi / s.step - 1e-9) * s.step) : hi;
    s.ticks = linear_ticks(s.lo, s.hi);
  }
  return s;
}

std::string text(double x, double y, const std::string& content, const char* anchor = "middle", const std::string& extra = "") {
  return fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"{}\"{}>{}</text>\n", number(x), number(y), anchor,
                     extra.empty() ? "" : " " + extra, content);
}

}  // namespace

std::string xml_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string series_colour(std::size_t index) {
  // Okabe & Ito 2008 without the yellow (too pale on white), black first.
  static const char* const colours[] = {"#000000", "#E69F00", "#0072B2", "#009E73", "#D55E00", "#CC79A7", "#56B4E9", "#7F7F7F"};
  return colours[index % std::size(colours)];
}

std::string series_dash(std::size_t index) {
  // Six patterns against eight colours: every (colour, dash) pair differs for the first 24 curves.
  static const char* const dashes[] = {"", "7 4", "2 3", "10 3 2 3", "4 2", "12 3 2 3 2 3"};
  return dashes[index % std::size(dashes)];
}

std::vector<double> linear_ticks(double lo, double hi, int target) {
  std::vector<double> ticks;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return {lo};
  const double raw = (hi - lo) / std::max(target, 2);
  const int exponent = static_cast<int>(std::floor(std::log10(raw)));
  const double magnitude = std::pow(10.0, exponent);
  double multiple = 10;
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * magnitude >= raw) {
      multiple = m;
      break;
    }
  const double step = multiple * magnitude;
  // k·m·10^e, divided by 10^-e for a negative e: 3 × 0.2 is 0.6000000000000001, 6 / 10 is 0.6.
  auto tick = [&](double k) { return exponent < 0 ? k * multiple / std::pow(10.0, -exponent) : k * multiple * magnitude; };
  for (double k = std::ceil(lo / step - 1e-9); tick(k) <= hi + step * 1e-9; ++k) ticks.push_back(k == 0 ? 0.0 : tick(k));
  return ticks;
}

std::vector<double> log_ticks(double lo, double hi) {
  std::vector<double> ticks;
  if (!(lo > 0) || !(hi > lo)) return {lo};
  const int first = static_cast<int>(std::ceil(std::log10(lo) - 1e-9)), last = static_cast<int>(std::floor(std::log10(hi) + 1e-9));
  const int every = std::max(1, (last - first + 7) / 8);  // at most ~8 labelled decades
  for (int k = first; k <= last; k += every) ticks.push_back(std::pow(10.0, k));
  return ticks;
}

std::string render_line_plot(const LinePlot& plot) {
  const double left = 78, right = plot.width - 24.0, top = 16, bottom = plot.height - 52.0;
  std::vector<double> xs, ys;
  for (const auto& s : plot.series) {
    xs.insert(xs.end(), s.x.begin(), s.x.end());
    ys.insert(ys.end(), s.y.begin(), s.y.end());
  }
  for (const auto& m : plot.x_marks) xs.push_back(m.value);
  for (const auto& m : plot.y_marks) ys.push_back(m.value);
  const Scale sx = make_scale(plot.x, xs, left, right);
  const Scale sy = make_scale(plot.y, ys, bottom, top);

  // The legend: entries flowed into rows under the x label, each a line sample in the curve's style and its label.
  struct Entry {
    double x, y;
  };
  std::vector<Entry> placed;
  double cx = left, cy = plot.height + 2.0;
  const bool any_failed = [&] {
    for (const auto& s : plot.series)
      for (double v : s.y)
        if (!drawable(v, plot.y.log)) return true;
    return false;
  }();
  std::vector<std::string> legend_labels;
  for (const auto& s : plot.series) legend_labels.push_back(s.label);
  if (any_failed) legend_labels.push_back("no value at this point (failed)");
  for (const auto& label : legend_labels) {
    const double w = 40 + text_width(label) + 22;
    if (cx > left && cx + w > right) cx = left, cy += legend_row;
    placed.push_back({cx, cy});
    cx += w;
  }
  const double total_height = placed.empty() ? plot.height : cy + legend_row;

  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"plot\" id=\"{0}\" viewBox=\"0 0 {1} {2}\" width=\"{1}\" "
      "height=\"{2}\" role=\"img\" {3} font-size=\"12\">\n<title>{4}</title>\n",
      xml_escape(plot.id), plot.width, number(total_height), font, xml_escape(plot.description));
  svg += fmt::format("<clipPath id=\"{}-area\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/></clipPath>\n",
                     xml_escape(plot.id), number(left), number(top), number(right - left), number(bottom - top));
  svg += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"#ffffff\" stroke=\"#555555\"/>\n", number(left),
                     number(top), number(right - left), number(bottom - top));

  // Grid, ticks and their labels.
  auto minor_decades = [](const Scale& s) {
    std::vector<double> minor;
    if (!s.log || std::log10(s.hi / s.lo) > 6) return minor;
    for (double d = std::pow(10.0, std::floor(std::log10(s.lo))); d < s.hi; d *= 10)
      for (int k = 2; k <= 9; ++k)
        if (s.contains(d * k) && std::find(s.ticks.begin(), s.ticks.end(), d * k) == s.ticks.end()) minor.push_back(d * k);
    return minor;
  };
  for (double v : minor_decades(sx))
    svg += fmt::format("<line class=\"minor\" x1=\"{0}\" x2=\"{0}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#555555\"/>\n", number(sx(v)),
                       number(bottom), number(bottom - 4));
  for (double v : minor_decades(sy))
    svg += fmt::format("<line class=\"minor\" x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"#555555\"/>\n", number(left),
                       number(left + 4), number(sy(v)));
  for (double v : sx.ticks) {
    if (!sx.contains(v)) continue;
    const double p = sx(v);
    svg += fmt::format("<line x1=\"{0}\" x2=\"{0}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#e3e3e3\"/>\n", number(p), number(top), number(bottom));
    svg += fmt::format("<line x1=\"{0}\" x2=\"{0}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#555555\"/>\n", number(p), number(bottom),
                       number(bottom + 5));
    svg += text(p, bottom + 18, sx.log ? decade_text(v) : tick_text(v, sx.step), "middle", "class=\"tick\"");
  }
  for (double v : sy.ticks) {
    if (!sy.contains(v)) continue;
    const double p = sy(v);
    svg += fmt::format("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"#e3e3e3\"/>\n", number(left), number(right), number(p));
    svg += fmt::format("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"#555555\"/>\n", number(left - 5), number(left), number(p));
    svg += text(left - 8, p + 4, sy.log ? decade_text(v) : tick_text(v, sy.step), "end", "class=\"tick\"");
  }
  svg += text((left + right) / 2, bottom + 38, xml_escape(plot.x.label), "middle", "class=\"axis-label\"");
  svg += fmt::format("<text x=\"{0}\" y=\"{1}\" text-anchor=\"middle\" class=\"axis-label\" transform=\"rotate(-90 {0} {1})\">{2}</text>\n",
                     number(16), number((top + bottom) / 2), xml_escape(plot.y.label));

  // Reference lines, their labels on a white halo so that a curve under them stays readable.
  const std::string halo = "paint-order=\"stroke\" stroke=\"#ffffff\" stroke-width=\"4\" stroke-linejoin=\"round\"";
  for (const auto& m : plot.x_marks) {
    if (!sx.contains(m.value)) continue;
    const double p = sx(m.value);
    svg += fmt::format("<line class=\"mark\" x1=\"{0}\" x2=\"{0}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#B2182B\" stroke-dasharray=\"5 3\"/>\n",
                       number(p), number(top), number(bottom));
    const bool to_left = p + 8 + text_width(m.label) > right;
    svg += text(to_left ? p - 5 : p + 5, top + 14, xml_escape(m.label), to_left ? "end" : "start", "fill=\"#B2182B\" " + halo);
  }
  for (const auto& m : plot.y_marks) {
    if (!sy.contains(m.value)) continue;
    const double p = sy(m.value);
    svg += fmt::format("<line class=\"mark\" x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"#B2182B\" stroke-dasharray=\"5 3\"/>\n",
                       number(left), number(right), number(p));
    const bool below = p - 18 < top;
    svg += text(right - 6, below ? p + 15 : p - 5, xml_escape(m.label), "end", "fill=\"#B2182B\" " + halo);
  }

  // Styles: the emphasised curve (the one the plot is about) black and solid, the others the next styles in turn.
  std::vector<std::size_t> style(plot.series.size());
  std::size_t next_style = 1;
  bool any_emphasis = false;
  for (const auto& s : plot.series) any_emphasis = any_emphasis || s.emphasis;
  for (std::size_t i = 0; i < plot.series.size(); ++i) style[i] = !any_emphasis ? i : plot.series[i].emphasis ? 0 : next_style++;

  // The curves: one path each, broken where a point has no value; such points crossed on the x axis.
  std::string failed_marks;
  for (std::size_t i = 0; i < plot.series.size(); ++i) {
    const Series& s = plot.series[i];
    std::string d;
    std::size_t drawn = 0;
    bool pen_down = false;
    std::string dots;
    for (std::size_t k = 0; k < s.x.size() && k < s.y.size(); ++k) {
      const bool ok = drawable(s.x[k], plot.x.log) && drawable(s.y[k], plot.y.log);
      if (!ok) {
        pen_down = false;
        if (drawable(s.x[k], plot.x.log) && sx.contains(s.x[k]))
          failed_marks += fmt::format("<path class=\"failed\" d=\"M{0} {1}l8 8m0 -8l-8 8\" stroke=\"#D7191C\" stroke-width=\"2\"/>\n",
                                      number(sx(s.x[k]) - 4), number(bottom - 12));
        continue;
      }
      d += fmt::format("{}{} {}", pen_down ? " L" : (d.empty() ? "M" : " M"), number(sx(s.x[k])), number(sy(s.y[k])));
      pen_down = true;
      ++drawn;
      if (s.markers)
        dots += fmt::format("<circle cx=\"{}\" cy=\"{}\" r=\"3.2\" fill=\"{}\"/>", number(sx(s.x[k])), number(sy(s.y[k])),
                            series_colour(style[i]));
    }
    const std::string dash = series_dash(style[i]);
    svg += fmt::format(
        "<g clip-path=\"url(#{0}-area)\"><path class=\"curve\" data-series=\"{1}\" data-points=\"{2}\" d=\"{3}\" fill=\"none\" "
        "stroke=\"{4}\" stroke-width=\"{5}\"{6} stroke-linejoin=\"round\"/>{7}</g>\n",
        xml_escape(plot.id), xml_escape(s.label), drawn, d, series_colour(style[i]), s.emphasis ? "3" : "1.8",
        dash.empty() ? "" : fmt::format(" stroke-dasharray=\"{}\"", dash), dots);
  }
  svg += failed_marks;

  for (std::size_t i = 0; i < placed.size(); ++i) {
    const auto [ex, ey] = placed[i];
    if (i < plot.series.size()) {
      const std::string dash = series_dash(style[i]);
      svg += fmt::format("<line x1=\"{}\" x2=\"{}\" y1=\"{}\" y2=\"{}\" stroke=\"{}\" stroke-width=\"{}\"{}/>\n", number(ex),
                         number(ex + 34), number(ey + 10), number(ey + 10), series_colour(style[i]), plot.series[i].emphasis ? "3" : "1.8",
                         dash.empty() ? "" : fmt::format(" stroke-dasharray=\"{}\"", dash));
    } else {
      svg += fmt::format("<path d=\"M{0} {1}l8 8m0 -8l-8 8\" stroke=\"#D7191C\" stroke-width=\"2\"/>\n", number(ex + 13), number(ey + 6));
    }
    svg += text(ex + 40, ey + 14, xml_escape(legend_labels[i]), "start", "class=\"legend\"");
  }
  svg += "</svg>\n";
  return svg;
}

std::string render_tornado(const TornadoPlot& plot) {
  constexpr double row = 24, top = 10;
  double label_width = 60;
  for (const auto& b : plot.bars) label_width = std::max(label_width, text_width(b.label) + 12);
  label_width = std::min(label_width, plot.width * 0.45);
  const double left = label_width + 8, right = plot.width - 8.0;
  const double bottom = top + row * static_cast<double>(std::max<std::size_t>(plot.bars.size(), 1));
  const double height = bottom + 52;
  double extent = 0;
  for (const auto& b : plot.bars)
    if (std::isfinite(b.value)) extent = std::max(extent, std::abs(b.value));
  if (extent == 0) extent = 1;
  Axis axis;
  axis.min = -extent, axis.max = extent;
  // Room on both sides of the bars for the value printed at a bar's end.
  const Scale sx = make_scale(axis, {}, left + 70, right - 70);

  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"plot tornado\" id=\"{0}\" viewBox=\"0 0 {1} {2}\" width=\"{1}\" "
      "height=\"{2}\" role=\"img\" {3} font-size=\"12\">\n<title>{4}</title>\n",
      xml_escape(plot.id), plot.width, number(height), font, xml_escape(plot.description));
  for (double v : linear_ticks(-extent, extent, 8)) {
    const double p = sx(v);
    svg += fmt::format("<line x1=\"{0}\" x2=\"{0}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#e3e3e3\"/>\n", number(p), number(top), number(bottom));
    svg += text(p, bottom + 18, tick_text(v, 0), "middle", "class=\"tick\"");
  }
  const double zero = sx(0);
  for (std::size_t i = 0; i < plot.bars.size(); ++i) {
    const Bar& b = plot.bars[i];
    const double y = top + row * static_cast<double>(i);
    // A label too long for its column is cut, with the whole of it in the row's tooltip.
    std::string label = b.label;
    const auto max_chars = static_cast<std::size_t>((label_width - 12) / char_width);
    if (label.size() > max_chars && max_chars > 1) label = label.substr(0, max_chars - 1) + "…";
    const bool failed = !b.failure.empty() || !std::isfinite(b.value);
    svg += fmt::format("<g class=\"bar{}\" data-label=\"{}\"><title>{}</title>\n", failed ? " failed" : "", xml_escape(b.label),
                       xml_escape(failed ? b.label + ": " + b.failure : fmt::format("{}: {:.6g}", b.label, b.value)));
    svg += text(left - 8, y + 16, xml_escape(label), "end", failed ? "fill=\"#B2182B\"" : "");
    if (failed) {
      svg += text(zero, y + 16, xml_escape("failed: " + b.failure), "middle", "fill=\"#B2182B\" font-style=\"italic\"");
    } else {
      const double p = sx(b.value);
      const double x0 = std::min(p, zero), w = std::max(std::abs(p - zero), 0.5);
      svg += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{}\" data-value=\"{}\"/>\n", number(x0), number(y + 4),
                         number(w), number(row - 8), b.value >= 0 ? "#0072B2" : "#D55E00", fmt::format("{}", b.value));
      const bool right_side = b.value >= 0;
      svg += text(right_side ? p + 5 : p - 5, y + 16, fmt::format("{:+.3g}", b.value), right_side ? "start" : "end", "class=\"value\"");
    }
    svg += "</g>\n";
  }
  svg += fmt::format("<line x1=\"{0}\" x2=\"{0}\" y1=\"{1}\" y2=\"{2}\" stroke=\"#333333\"/>\n", number(zero), number(top), number(bottom));
  svg += fmt::format("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"#555555\"/>\n", number(left), number(right), number(bottom));
  svg += text((left + right) / 2, bottom + 38, xml_escape(plot.x_label), "middle", "class=\"axis-label\"");
  svg += "</svg>\n";
  return svg;
}

}  // namespace radchain::svg

// The plot of a 1-D sweep: a generated gnuplot script run by the gnuplot binary (Debian gnuplot-nox has the
// pngcairo terminal; the plain png terminal, libgd, is the fallback).
#include "radchain/sweep.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <unistd.h>

namespace radchain {
namespace fs = std::filesystem;
namespace {

// A gnuplot single-quoted string ('' is a quote inside).
std::string gp_quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

// A shell single-quoted word.
std::string sh_quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string label(const std::string& name, const std::string& unit) {
  return unit.empty() || unit == "1" ? name : name + " [" + unit + "]";
}

// A series that is constant up to rounding (an SNR held at the threshold by a solve) would be drawn as
// noise over a range of 1e-14: give it a range of ±0.1 % around its mean instead.
std::string y_range(const std::vector<double>& y) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, sum = 0;
  std::size_t n = 0;
  for (double v : y)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v), sum += v, ++n;
  if (n == 0) return "set autoscale y";
  const double mean = sum / static_cast<double>(n);
  if (hi - lo > 1e-9 * std::max(std::abs(mean), 1e-300)) return "set autoscale y";
  const double half = mean != 0 ? 1e-3 * std::abs(mean) : 1.0;
  return fmt::format("set yrange [{:.17g}:{:.17g}]", mean - half, mean + half);
}

}  // namespace

void plot_sweep(const std::string& png_path, const std::string& title, const std::string& x_label,
                const std::vector<double>& x, const std::vector<PlotSeries>& series) {
  if (series.empty()) throw std::runtime_error("nothing to plot");
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0)
    throw std::runtime_error("gnuplot is not installed (Debian: apt-get install gnuplot-nox)");
  static std::atomic<int> counter{0};
  const fs::path dir = fs::temp_directory_path() / fmt::format("radchain-plot-{}-{}", ::getpid(), counter++);
  fs::create_directories(dir);
  const fs::path data = dir / "data.tsv", script = dir / "plot.gp", log = dir / "gnuplot.log";
  {
    std::ofstream out(data);
    for (std::size_t i = 0; i < x.size(); ++i) {
      out << fmt::format("{:.17g}", x[i]);
      for (const auto& s : series) out << '\t' << (std::isfinite(s.y[i]) ? fmt::format("{:.17g}", s.y[i]) : "NaN");
      out << '\n';
    }
  }
  auto run = [&](const std::string& terminal) {
    std::ofstream gp(script);
    const int height = static_cast<int>(std::max<std::size_t>(1, series.size())) * 320 + 60;
    gp << fmt::format("set terminal {} noenhanced size 900,{}\n", terminal, height);
    gp << "set output " << gp_quoted(png_path) << "\n";
    gp << "set datafile missing 'NaN'\nset grid\nset key off\n";
    gp << fmt::format("set multiplot layout {},1 title {}\n", series.size(), gp_quoted(title));
    for (std::size_t i = 0; i < series.size(); ++i) {
      gp << "set xlabel " << gp_quoted(x_label) << "\n";
      gp << "set ylabel " << gp_quoted(label(series[i].label, series[i].unit)) << "\n";
      gp << y_range(series[i].y) << "\n";
      gp << fmt::format("plot {} using 1:{} with linespoints pointtype 7 pointsize 0.6\n", gp_quoted(data.string()), i + 2);
    }
    gp << "unset multiplot\nset output\n";
    gp.close();
    const std::string command = "gnuplot " + sh_quoted(script.string()) + " >" + sh_quoted(log.string()) + " 2>&1";
    return std::system(command.c_str()) == 0;
  };
  const bool drawn = run("pngcairo") || run("png");
  std::string why;
  if (!drawn) {
    std::ifstream in(log);
    std::getline(in, why);
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
  if (!drawn) throw std::runtime_error("gnuplot failed to draw " + png_path + (why.empty() ? "" : ": " + why));
}

}  // namespace radchain

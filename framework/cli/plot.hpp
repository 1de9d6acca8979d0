#pragma once
// Plots for the command line (sweep --plot, mtf --plot, budget --plot): gnuplot draws them; see plot.cpp for the trust rule.
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace radchain::cli {

// Draws a 1-D sweep with gnuplot (pngcairo, else png): one panel per series against the axis, logarithmic where it
// spans more than two decades, its points without a value (a failed solve) marked along the bottom. Throws
// std::runtime_error when gnuplot is missing or fails.
struct PlotSeries {
  std::string label;  // "target.magnitude"
  std::string unit;   // display unit ("" for none)
  std::vector<double> y;
};
void plot_sweep(const std::string& png_path, const std::string& title, const std::string& x_label,
                const std::vector<double>& x, const std::vector<PlotSeries>& series);

// Draws a 2-D sweep: one heat map per series over x × y with contour lines (series[k].y[i * y.size() + j] at
// x[i], y[j]); points without a value are grey and counted in the panel's title.
void plot_heatmaps(const std::string& png_path, const std::string& title, const std::string& x_label,
                   const std::string& y_label, const std::vector<double>& x, const std::vector<double>& y,
                   const std::vector<PlotSeries>& series);

// Curves overlaid in one panel with a key (radchain mtf --plot): y from 0 (or 1e-3 on a log axis) to 1.05, and
// a dashed vertical line at mark_x labelled mark_label (NaN: none).
struct CurveOptions {
  bool log_y = false;
  double mark_x = std::numeric_limits<double>::quiet_NaN();
  std::string mark_label;
};
void plot_curves(const std::string& png_path, const std::string& title, const std::string& x_label,
                 const std::string& y_label, const std::vector<double>& x, const std::vector<PlotSeries>& curves,
                 const CurveOptions& options);

// Horizontal bars about zero, one panel per x label (radchain budget --plot). Bars are listed bottom first.
struct TornadoPanel {
  std::string x_label;
  std::vector<std::pair<std::string, double>> bars;  // label, value
};
void plot_tornado(const std::string& png_path, const std::string& title, const std::vector<TornadoPanel>& panels);

// Histograms, one panel per result (radchain uncertainty --plot), with dashed lines at `marks` (5/50/95 %).
struct HistogramPanel {
  std::string label, unit;
  std::vector<double> edges;          // bins + 1, display unit
  std::vector<std::size_t> counts;
  std::vector<double> marks;          // display unit
};
void plot_histograms(const std::string& png_path, const std::string& title, const std::vector<HistogramPanel>& panels);

}  // namespace radchain::cli

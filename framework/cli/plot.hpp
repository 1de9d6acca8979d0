#pragma once
// Plots for the command line (sweep --plot, mtf --plot): gnuplot draws them; see plot.cpp for the trust rule.
#include <string>
#include <vector>

namespace radchain::cli {

// Draws a 1-D sweep with gnuplot (pngcairo, else png): one panel per series against the axis. Throws
// std::runtime_error when gnuplot is missing or fails.
struct PlotSeries {
  std::string label;  // "target.magnitude"
  std::string unit;   // display unit ("" for none)
  std::vector<double> y;
};
void plot_sweep(const std::string& png_path, const std::string& title, const std::string& x_label,
                const std::vector<double>& x, const std::vector<PlotSeries>& series);

}  // namespace radchain::cli

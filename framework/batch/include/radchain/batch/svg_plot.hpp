#pragma once
// Inline SVG plots for the HTML report (radchain/batch/html_report.hpp): line plots with ticked, labelled axes
// (linear or logarithmic), a colour AND a dash pattern per curve (so curves stay apart in grey print and for
// colour-blind readers), a legend below the plot area (never over the data) and a tornado of bars about zero.
// Text is XML-escaped; the SVG has a viewBox and scales to its container's width. No drawing library: the
// report must stay self-contained and the batch library links no imaging code.
//
// Each curve is one <path class="curve" data-series="…" data-points="N"> with N finite points drawn; a point
// with no value (NaN, or ≤ 0 on a log axis) is not joined to its neighbours and is marked on the x axis with a
// red cross (class "failed"), so a failed point is visible rather than dropped.
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace radchain::svg {

struct Axis {
  std::string label;  // "target magnitude", "SNR", with the unit: "integration time (s)"
  bool log = false;
  // Fixed limits; NaN: from the data (a log axis to whole decades, a linear one to the nearest ticks).
  double min = std::numeric_limits<double>::quiet_NaN();
  double max = std::numeric_limits<double>::quiet_NaN();
};

struct Series {
  std::string label;
  std::vector<double> x, y;
  bool emphasis = false;  // drawn black, solid and thicker (the system MTF, the curve the plot is about)
  bool markers = false;   // a dot at each point (a few table rows rather than a dense sweep)
};

// A reference line across the plot area at a value of one axis, labelled beside it ("Nyquist 35.7 mm-1",
// "threshold T = 5").
struct Mark {
  double value = 0;
  std::string label;
};

struct LinePlot {
  std::string id;           // unique in the page (clip-path ids are derived from it)
  std::string description;  // the <title> of the SVG (what a screen reader says)
  Axis x, y;
  std::vector<Series> series;
  std::vector<Mark> x_marks;  // vertical lines
  std::vector<Mark> y_marks;  // horizontal lines
  int width = 880, height = 420;  // of the plot with its axes, before the legend rows below it
};

std::string render_line_plot(const LinePlot& plot);

struct Bar {
  std::string label;
  double value = 0;     // NaN for a failed bar
  std::string failure;  // why there is no value ("" for a bar)
};

// Horizontal bars about zero, the first bar on top, value printed at each bar's end; a failed bar is a red row
// with its reason instead of a bar.
struct TornadoPlot {
  std::string id, description;
  std::string x_label;
  std::vector<Bar> bars;
  int width = 880;
};

std::string render_tornado(const TornadoPlot& plot);

// The colours and dash patterns, in order, that the i-th curve gets (exposed for the tests and the legend of
// HTML tables): Okabe & Ito's colour-blind-safe palette (Okabe & Ito 2008, "Color Universal Design").
std::string series_colour(std::size_t index);
std::string series_dash(std::size_t index);  // "" for solid

// Tick values of an axis between lo and hi: about `target` "nice" linear steps (1, 2, 2.5, 5 × 10^k) or, on a log
// axis, the decades (every k-th decade when there are many). Exposed for the tests.
std::vector<double> linear_ticks(double lo, double hi, int target = 6);
std::vector<double> log_ticks(double lo, double hi);

std::string xml_escape(const std::string& text);

}  // namespace radchain::svg

// Plots of the command line (a 1-D sweep, a 2-D sweep's heat maps, MTF curves, a budget's tornado), drawn by the gnuplot binary (Debian gnuplot-nox has the pngcairo terminal; the plain
// png terminal, libgd, is the fallback).
//
// Trust: every text that comes from outside (sensor names and paths in titles, result names, units, the output
// path) reaches gnuplot as data, never as script text. The script below is a constant; the texts are passed as
// `gnuplot -c script ARG1 …` arguments (string variables, never evaluated) and gnuplot is started with
// posix_spawnp, so no shell sees them either. gnuplot 5.4 passes at most nine arguments, so the y-axis labels
// travel as one argument, separated by the unit separator (control characters are replaced by spaces first).
#include "plot.hpp"

#include "radchain/atomic_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <stdexcept>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace radchain::cli {
namespace fs = std::filesystem;
namespace {

constexpr char label_separator = '\x1f';

// The plotting script: fixed text. ARG1 output PNG, ARG2 data file, ARG3 title, ARG4 x label, ARG5 y labels
// (separated by \037); the terminal, the panel count and the y ranges are written before it by plot_sweep.
constexpr const char* plot_script = R"gp(set output ARG1
set datafile missing 'NaN'
set datafile separator "\t"
set grid
set key outside top right horizontal
set y2range [0:1]
unset y2tics
set multiplot layout panels, 1 title ARG3
labels = ARG5
do for [i = 1:panels] {
  cut = strstrt(labels, "\037")
  ylab = (cut > 0) ? labels[1:cut - 1] : labels
  labels = (cut > 0) ? labels[cut + 1:*] : ""
  set xlabel ARG4
  set ylabel ylab
  if (logy[i]) { set logscale y } else { unset logscale y }
  if (fixed[i]) { set yrange [low[i]:high[i]] } else { set autoscale y }
  # points without a value (a failed solve: NaN) are marked along the bottom, not dropped without a trace
  if (failed[i] > 0) {
    plot ARG2 using 1:(column(i + 1)) with linespoints pointtype 7 pointsize 0.6 lc rgb "#1f77b4" notitle, \
         ARG2 using 1:(column(panels + i + 1) > 0 ? 0.04 : NaN) axes x1y2 with points pointtype 2 pointsize 1.5 lw 2 \
              lc rgb "#d62728" title sprintf("no value (the solve failed): %d point%s", failed[i], failed[i] > 1 ? "s" : "")
  } else {
    plot ARG2 using 1:(column(i + 1)) with linespoints pointtype 7 pointsize 0.6 lc rgb "#1f77b4" notitle
  }
}
unset multiplot
set output
)gp";

// A 2-D sweep (radchain sweep --plot with two axes): one heat map per series (the axes are evenly spaced: an
// image) with labelled contour lines; points without a value (a failed solve) are left grey and counted in the
// title; a series that is constant up to rounding (an SNR held by a solve) gets a ±0.1 % colour range and no
// contours. Fixed text. ARG1 output PNG, ARG2 data file (x, y, one column per series; a blank line after each x),
// ARG3 title, ARG4 x label, ARG5 y label, ARG6 the series' labels separated by \037. The terminal, the panel
// count, the fixed ranges and the failed counts are written before it by plot_heatmaps.
constexpr const char* heatmap_script = R"gp(set output ARG1
# (NaN is not declared missing: an image leaves an undefined value's pixel undrawn, so the grey behind shows)
set datafile separator whitespace
set key off
set palette rgb 33,13,10
set object 1 rectangle from graph 0, graph 0 to graph 1, graph 1 behind fillcolor rgb "#b0b0b0" fillstyle solid noborder
set multiplot layout panels, 1 title ARG3
labels = ARG6
do for [i = 1:panels] {
  cut = strstrt(labels, "\037")
  zlab = (cut > 0) ? labels[1:cut - 1] : labels
  labels = (cut > 0) ? labels[cut + 1:*] : ""
  # the contour lines, traced by gnuplot into a table beside the data (a file of the private folder)
  contours = ARG2 . ".contours"
  if (!fixed[i]) {
    set contour base
    set cntrparam levels auto 8
    unset surface
    set view map
    set table contours
    splot ARG2 using 1:2:(column(i + 2)) with lines
    unset table
    unset contour
    set view
  }
  set autoscale fix
  if (fixed[i]) { set cbrange [low[i]:high[i]] } else { set autoscale cb }
  set xlabel ARG4
  set ylabel ARG5
  set cblabel zlab
  set title zlab . (failed[i] > 0 ? sprintf("  (grey: no value, the solve failed: %d point%s)", failed[i], failed[i] > 1 ? "s" : "") : "")
  if (fixed[i]) {
    plot ARG2 using 1:2:(column(i + 2)) with image
  } else {
    plot ARG2 using 1:2:(column(i + 2)) with image, contours using 1:2 with lines lc rgb "black" lw 1, \
         contours using 1:2:(sprintf("%.4g", $3)) every 40 with labels boxed
  }
}
unset multiplot
set output
)gp";

// Curves in one panel (radchain mtf --plot): fixed text. ARG1 output PNG, ARG2 data file (x, then one column per
// curve), ARG3 title, ARG4 x label, ARG5 y label, ARG6 the curves' names separated by \037, ARG7 the mark's label.
// The terminal, the curve count, log_y and mark (NaN: none) are written before it by plot_curves.
constexpr const char* curves_script = R"gp(set output ARG1
set datafile missing 'NaN'
set datafile separator "\t"
set grid
set key outside center bottom horizontal maxrows 3 samplen 3
set title ARG3 font ",11"
set xlabel ARG4
set ylabel ARG5
if (log_y) { set logscale y; set yrange [1e-3:1.05] } else { set yrange [0:1.05] }
if (mark == mark) { set arrow 1 from mark, graph 0 to mark, graph 1 nohead dt 2 lw 1.5; set label 1 ARG7 at mark, graph 0.04 left offset 0.5, 0 front }
# ten colours (Tableau 10) and five dash patterns: no two curves of a budget (nine) look alike
array colours[10] = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"]
do for [k = 1:10] { d = (k - 1) % 5 + 1; set linetype k linecolor rgb colours[k] linewidth 2 dashtype d }
array names[curves]
labels = ARG6
do for [i = 1:curves] {
  cut = strstrt(labels, "\037")
  names[i] = (cut > 0) ? labels[1:cut - 1] : labels
  labels = (cut > 0) ? labels[cut + 1:*] : ""
}
plot for [i = 1:curves] ARG2 using 1:(column(i + 1)) with lines linetype ((i - 1) % 10 + 1) lw (i == curves ? 3 : 2) \
     title names[i]
set output
)gp";

// The tornado (radchain budget --plot): fixed text. ARG1 output PNG, ARG2 data file (one block per panel, separated
// by two blank lines: label TAB value, bottom bar first), ARG3 title, ARG4 the x labels separated by \037. The
// terminal, the panel count and each panel's row count are written before it by plot_tornado.
constexpr const char* tornado_script = R"gp(set output ARG1
set datafile separator "\t"
set style fill solid 0.75 border -1
set grid x
set key off
set yzeroaxis lt -1 lw 1.5
set offsets graph 0.06, graph 0.06, 0, 0
set ytics scale 0 noenhanced
set multiplot layout panels, 1 title ARG3
labels = ARG4
do for [i = 1:panels] {
  cut = strstrt(labels, "\037")
  xlab = (cut > 0) ? labels[1:cut - 1] : labels
  labels = (cut > 0) ? labels[cut + 1:*] : ""
  set xlabel xlab
  set yrange [-0.6:rows[i] - 0.4]
  plot ARG2 index (i - 1) using (0):0:(($2 < 0) ? $2 : 0):(($2 < 0) ? 0 : $2):($0 - 0.35):($0 + 0.35):(($2 < 0) ? 0xc0504d : 0x4f81bd):ytic(1) with boxxyerror lc rgb variable
}
unset multiplot
set output
)gp";

// Histograms (radchain uncertainty --plot): fixed text. ARG1 output PNG, ARG2 data file (one block per panel,
// separated by two blank lines: bin centre TAB count TAB bin width), ARG3 title, ARG4 the x labels separated by
// \037. The terminal, the panel count and three marks per panel are written before it by plot_histograms.
constexpr const char* histogram_script = R"gp(set output ARG1
set datafile separator "\t"
set style fill solid 0.5 border -1
set grid y
set key off
set ylabel "samples"
set multiplot layout panels, 1 title ARG3
labels = ARG4
do for [i = 1:panels] {
  cut = strstrt(labels, "\037")
  xlab = (cut > 0) ? labels[1:cut - 1] : labels
  labels = (cut > 0) ? labels[cut + 1:*] : ""
  set xlabel xlab
  do for [m = 1:3] { set arrow m from marks[3 * (i - 1) + m], graph 0 to marks[3 * (i - 1) + m], graph 1 nohead dt 2 lw 1.5 }
  plot ARG2 index (i - 1) using 1:2:3 with boxes
  unset arrow
}
unset multiplot
set output
)gp";

// Text for gnuplot's arguments: control characters (a newline above all) become spaces.
std::string plain_text(std::string text) {
  for (char& c : text)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
  return text;
}

std::string label(const std::string& name, const std::string& unit) {
  return unit.empty() || unit == "1" ? name : name + " [" + unit + "]";
}

// The panels' axis labels as one gnuplot argument (see the trust note at the top), each made plain text.
template <class Panel, class Text>
std::string joined_labels(const std::vector<Panel>& panels, Text text_of) {
  std::string joined;
  for (std::size_t i = 0; i < panels.size(); ++i) {
    if (i) joined += label_separator;
    joined += plain_text(text_of(panels[i]));
  }
  return joined;
}

// A series that is constant up to rounding (an SNR held at the threshold by a solve) would be drawn as
// noise over a range of 1e-14: give it a range of ±0.1 % around its mean instead. Returns {fixed, low, high}.
struct YRange {
  bool fixed = false;
  double low = 0, high = 0;
};
YRange y_range(const std::vector<double>& y) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, sum = 0;
  std::size_t n = 0;
  for (double v : y)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v), sum += v, ++n;
  if (n == 0) return {};
  const double mean = sum / static_cast<double>(n);
  if (hi - lo > 1e-9 * std::max(std::abs(mean), 1e-300)) return {};
  const double half = mean != 0 ? 1e-3 * std::abs(mean) : 1.0;
  return {true, mean - half, mean + half};
}

// The data file of a sweep or of curves: x, then one column per series (NaN where not finite), tab-separated;
// with `flags`, then one column per series that is 1 where it has no value (the failed points the plot marks).
void write_columns(std::ostream& out, const std::vector<double>& x, const std::vector<PlotSeries>& series,
                   bool flags = false) {
  for (std::size_t i = 0; i < x.size(); ++i) {
    out << fmt::format("{:.17g}", x[i]);
    for (const auto& s : series) out << '\t' << (std::isfinite(s.y[i]) ? fmt::format("{:.17g}", s.y[i]) : "NaN");
    if (flags)
      for (const auto& s : series) out << '\t' << (std::isfinite(s.y[i]) ? 0 : 1);
    out << '\n';
  }
}

std::size_t failed_points(const std::vector<double>& y) {
  return static_cast<std::size_t>(std::count_if(y.begin(), y.end(), [](double v) { return !std::isfinite(v); }));
}

// A log axis where the values span more than two decades and are all positive (an SNR from 1 to 1000).
bool spans_decades(const std::vector<double>& y) {
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (double v : y) {
    if (!std::isfinite(v)) continue;
    if (v <= 0) return false;
    lo = std::min(lo, v), hi = std::max(hi, v);
  }
  return hi > 0 && hi / lo > 100;
}

// A PNG ends with the IEND chunk: length 0, "IEND", its CRC AE 42 60 82 (PNG specification, ISO/IEC 15948 §5.6, §11.2.5).
bool is_complete_png(const std::string& path) {
  static constexpr unsigned char iend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in || in.tellg() < 8 + 12) return false;
  in.seekg(-12, std::ios::end);
  unsigned char tail[12];
  in.read(reinterpret_cast<char*>(tail), 12);
  return in && std::equal(std::begin(tail), std::end(tail), std::begin(iend));
}

// A folder only this process's user can enter, under TMPDIR, with a name nobody can predict (mkdtemp: created
// exclusively, mode 0700). A predictable name that merely had to exist let another local user pre-create it, swap
// the script before gnuplot read it (commands run as us) or plant the log as a link to one of our files.
fs::path private_folder() {
  std::string pattern = (fs::temp_directory_path() / "radchain-plot-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr)
    throw WriteError("cannot create a private folder for gnuplot under " + fs::temp_directory_path().string() + ": " +
                     std::strerror(errno));
  return pattern;
}

// Runs `gnuplot -c script args…` without a shell, its output into `log`. Returns false when gnuplot fails;
// throws when it cannot be started at all.
bool run_gnuplot(const std::vector<std::string>& arguments, const fs::path& log) {
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>("gnuplot"));
  for (const auto& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0600);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned == ENOENT) throw std::runtime_error("gnuplot is not installed (Debian: apt-get install gnuplot-nox)");
  if (spawned != 0) throw std::runtime_error(std::string("cannot start gnuplot: ") + std::strerror(spawned));
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw std::runtime_error(std::string("waiting for gnuplot: ") + std::strerror(errno));
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

// Draws png_path with gnuplot: write_data fills the data file, head(terminal) is the part of the script radchain
// chose itself (terminal, sizes, counts), followed by the constant `script`; arguments follow ARG1 (the PNG,
// a temporary until gnuplot succeeded) and ARG2 (the data file). pngcairo first, plain png as the fallback.
void draw(const std::string& png_path, const std::function<void(std::ostream&)>& write_data,
          const std::function<std::string(const std::string& terminal)>& head, const char* script,
          const std::vector<std::string>& arguments) {
  AtomicFile png(png_path, "--plot");
  const fs::path dir = private_folder();
  const fs::path data = dir / "data.tsv", log = dir / "gnuplot.log";
  auto script_path = [&](const std::string& terminal) { return dir / ("plot-" + terminal + ".gp"); };
  // The data and the scripts (one per terminal tried), all written before gnuplot runs: a write that fails (a full
  // /tmp, a file size limit) would make gnuplot draw a cut curve without complaint, so each goes through
  // AtomicFile, and its failure is reported as the plot's (naming the PNG asked for), with the reason.
  auto written = [&](const fs::path& path, const std::function<void(std::ostream&)>& fill) {
    try {
      AtomicFile file(path.string(), "--plot");
      fill(file.stream());
      file.commit();
    } catch (const WriteError& error) {
      std::error_code ec;
      fs::remove_all(dir, ec);
      throw WriteError("cannot write " + png_path + ": its " + path.filename().string() + " for gnuplot: " + error.what());
    } catch (...) {
      std::error_code ec;
      fs::remove_all(dir, ec);
      throw;
    }
  };
  written(data, write_data);
  for (const char* terminal : {"pngcairo", "png"})
    written(script_path(terminal), [&](std::ostream& gp) { gp << head(terminal) << script; });
  auto run = [&](const std::string& terminal) {
    std::vector<std::string> all = {"-c", script_path(terminal).string(), png.temporary_path(), data.string()};
    all.insert(all.end(), arguments.begin(), arguments.end());
    return run_gnuplot(all, log);
  };
  bool drawn = false;
  std::string why;
  try {
    drawn = run("pngcairo") || run("png");
  } catch (const std::runtime_error& error) {
    why = error.what();
  }
  if (!drawn && why.empty()) {
    std::ifstream in(log);
    std::getline(in, why);
    why = "gnuplot failed to draw " + png_path + (why.empty() ? "" : ": " + why);
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
  if (!drawn) throw std::runtime_error(why);
  // gnuplot's PNG writers ignore write errors (a full disk or a file size limit leaves a cut file and exit status
  // 0), so the file is checked for the PNG's last chunk, IEND, before it replaces the target.
  if (!is_complete_png(png.temporary_path()))
    throw WriteError("cannot write " + png_path + ": gnuplot's PNG is incomplete (no IEND chunk): the disk is full or a file "
                     "size limit was reached");
  png.commit();
}

}  // namespace

void plot_sweep(const std::string& png_path, const std::string& title, const std::string& x_label,
                const std::vector<double>& x, const std::vector<PlotSeries>& series) {
  if (series.empty()) throw std::runtime_error("nothing to plot");
  const std::string y_labels = joined_labels(series, [](const PlotSeries& s) { return label(s.label, s.unit); });
  draw(
      png_path,
      [&](std::ostream& out) { write_columns(out, x, series, true); },
      [&](const std::string& terminal) {
        const std::size_t n = series.size();
        std::string head = fmt::format("set terminal {} noenhanced size 900,{}\n", terminal, n * 320 + 60);
        head += fmt::format("panels = {0}\narray fixed[{0}]\narray low[{0}]\narray high[{0}]\narray logy[{0}]\narray failed[{0}]\n", n);
        for (std::size_t i = 0; i < n; ++i) {
          const YRange r = y_range(series[i].y);
          head += fmt::format("fixed[{0}] = {1}; low[{0}] = {2:.17g}; high[{0}] = {3:.17g}; logy[{0}] = {4}; failed[{0}] = {5}\n",
                              i + 1, r.fixed ? 1 : 0, r.low, r.high, !r.fixed && spans_decades(series[i].y) ? 1 : 0,
                              failed_points(series[i].y));
        }
        return head;
      },
      plot_script, {plain_text(title), plain_text(x_label), y_labels});
}

void plot_heatmaps(const std::string& png_path, const std::string& title, const std::string& x_label,
                   const std::string& y_label, const std::vector<double>& x, const std::vector<double>& y,
                   const std::vector<PlotSeries>& series) {
  if (series.empty() || x.empty() || y.empty()) throw std::runtime_error("nothing to plot");
  for (const auto& s : series)
    if (s.y.size() != x.size() * y.size()) throw std::logic_error("plot_heatmaps: a series is not x × y points");
  draw(
      png_path,
      [&](std::ostream& out) {
        for (std::size_t i = 0; i < x.size(); ++i) {  // gnuplot's grid: one scan per x, a blank line after each
          for (std::size_t j = 0; j < y.size(); ++j) {
            out << fmt::format("{:.17g}\t{:.17g}", x[i], y[j]);
            for (const auto& s : series) {
              const double v = s.y[i * y.size() + j];
              out << '\t' << (std::isfinite(v) ? fmt::format("{:.17g}", v) : "NaN");
            }
            out << '\n';
          }
          out << '\n';
        }
      },
      [&](const std::string& terminal) {
        const std::size_t n = series.size();
        std::string head = fmt::format("set terminal {0} noenhanced size 900,{1}\npanels = {2}\narray failed[{2}]\n"
                                       "array fixed[{2}]\narray low[{2}]\narray high[{2}]\n",
                                       terminal, n * 560 + 60, n);
        for (std::size_t i = 0; i < n; ++i) {
          const YRange r = y_range(series[i].y);
          head += fmt::format("failed[{0}] = {1}; fixed[{0}] = {2}; low[{0}] = {3:.17g}; high[{0}] = {4:.17g}\n", i + 1,
                              failed_points(series[i].y), r.fixed ? 1 : 0, r.low, r.high);
        }
        return head;
      },
      heatmap_script,
      {plain_text(title), plain_text(x_label), plain_text(y_label),
       joined_labels(series, [](const PlotSeries& s) { return label(s.label, s.unit); })});
}

void plot_curves(const std::string& png_path, const std::string& title, const std::string& x_label,
                 const std::string& y_label, const std::vector<double>& x, const std::vector<PlotSeries>& curves,
                 const CurveOptions& options) {
  if (curves.empty()) throw std::runtime_error("nothing to plot");
  draw(
      png_path,
      [&](std::ostream& out) { write_columns(out, x, curves); },
      [&](const std::string& terminal) {
        return fmt::format("set terminal {} noenhanced size 1000,620\ncurves = {}\nlog_y = {}\nmark = {}\n", terminal,
                           curves.size(), options.log_y ? 1 : 0,
                           std::isfinite(options.mark_x) ? fmt::format("{:.17g}", options.mark_x) : "NaN");
      },
      curves_script,
      {plain_text(title), plain_text(x_label), plain_text(y_label),
       joined_labels(curves, [](const PlotSeries& c) { return c.label; }), plain_text(options.mark_label)});
}

void plot_tornado(const std::string& png_path, const std::string& title, const std::vector<TornadoPanel>& panels) {
  if (panels.empty()) throw std::runtime_error("nothing to plot");
  const std::string x_labels = joined_labels(panels, [](const TornadoPanel& p) { return p.x_label; });
  draw(
      png_path,
      [&](std::ostream& out) {
        for (std::size_t k = 0; k < panels.size(); ++k) {
          if (k) out << "\n\n";
          if (panels[k].bars.empty()) out << "(none)\t0\n";
          for (const auto& [name, value] : panels[k].bars) out << plain_text(name) << '\t' << fmt::format("{:.17g}", value) << '\n';
        }
      },
      [&](const std::string& terminal) {
        std::size_t height = 60;
        for (const auto& p : panels) height += 90 + 26 * std::max<std::size_t>(p.bars.size(), 1);
        std::string head = fmt::format("set terminal {} noenhanced size 1100,{}\n", terminal, height);
        head += fmt::format("panels = {}\narray rows[{}]\n", panels.size(), panels.size());
        for (std::size_t i = 0; i < panels.size(); ++i)
          head += fmt::format("rows[{}] = {}\n", i + 1, std::max<std::size_t>(panels[i].bars.size(), 1));
        return head;
      },
      tornado_script, {plain_text(title), x_labels});
}

void plot_histograms(const std::string& png_path, const std::string& title, const std::vector<HistogramPanel>& panels) {
  if (panels.empty()) throw std::runtime_error("nothing to plot");
  const std::string x_labels = joined_labels(panels, [](const HistogramPanel& p) { return label(p.label, p.unit); });
  draw(
      png_path,
      [&](std::ostream& out) {
        for (std::size_t k = 0; k < panels.size(); ++k) {
          if (k) out << "\n\n";
          const auto& p = panels[k];
          for (std::size_t b = 0; b < p.counts.size(); ++b)
            out << fmt::format("{:.17g}\t{}\t{:.17g}\n", 0.5 * (p.edges[b] + p.edges[b + 1]), p.counts[b], p.edges[b + 1] - p.edges[b]);
          if (p.counts.empty()) out << "0\t0\t1\n";
        }
      },
      [&](const std::string& terminal) {
        std::string head = fmt::format("set terminal {} noenhanced size 900,{}\n", terminal, panels.size() * 320 + 60);
        head += fmt::format("panels = {}\narray marks[{}]\n", panels.size(), 3 * panels.size());
        for (std::size_t i = 0; i < panels.size(); ++i)
          for (std::size_t m = 0; m < 3; ++m) {
            const double v = m < panels[i].marks.size() && std::isfinite(panels[i].marks[m]) ? panels[i].marks[m] : 0.0;
            head += fmt::format("marks[{}] = {:.17g}\n", 3 * i + m + 1, v);
          }
        return head;
      },
      histogram_script, {plain_text(title), x_labels});
}

}  // namespace radchain::cli

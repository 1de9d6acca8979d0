// The plot of a 1-D sweep, drawn by the gnuplot binary (Debian gnuplot-nox has the pngcairo terminal; the plain
// png terminal, libgd, is the fallback).
//
// Trust: every text that comes from outside (sensor names and paths in titles, result names, units, the output
// path) reaches gnuplot as data, never as script text. The script below is a constant; the texts are passed as
// `gnuplot -c script ARG1 … ARG6` arguments (string variables, never evaluated) and gnuplot is started with
// posix_spawnp, so no shell sees them either. gnuplot 5.4 passes at most nine arguments, so the y-axis labels
// travel as one argument, separated by the unit separator (control characters are replaced by spaces first).
#include "plot.hpp"

#include "radchain/atomic_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
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
set key off
set multiplot layout panels, 1 title ARG3
labels = ARG5
do for [i = 1:panels] {
  cut = strstrt(labels, "\037")
  ylab = (cut > 0) ? labels[1:cut - 1] : labels
  labels = (cut > 0) ? labels[cut + 1:*] : ""
  set xlabel ARG4
  set ylabel ylab
  if (fixed[i]) { set yrange [low[i]:high[i]] } else { set autoscale y }
  plot ARG2 using 1:(column(i + 1)) with linespoints pointtype 7 pointsize 0.6
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
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
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

}  // namespace

void plot_sweep(const std::string& png_path, const std::string& title, const std::string& x_label,
                const std::vector<double>& x, const std::vector<PlotSeries>& series) {
  if (series.empty()) throw std::runtime_error("nothing to plot");
  AtomicFile png(png_path, "--plot");  // gnuplot draws into a temporary; renamed only once it succeeded
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
  std::string y_labels;
  for (std::size_t i = 0; i < series.size(); ++i) {
    if (i) y_labels += label_separator;
    y_labels += plain_text(label(series[i].label, series[i].unit));
  }
  // The script's head holds only what radchain chose itself: the terminal, the panel count and the y ranges.
  auto write_script = [&](const std::string& terminal) {
    std::ofstream gp(script);
    const std::size_t height = series.size() * 320 + 60;
    gp << fmt::format("set terminal {} noenhanced size 900,{}\n", terminal, height);
    gp << fmt::format("panels = {}\narray fixed[{}]\narray low[{}]\narray high[{}]\n", series.size(), series.size(),
                      series.size(), series.size());
    for (std::size_t i = 0; i < series.size(); ++i) {
      const YRange r = y_range(series[i].y);
      gp << fmt::format("fixed[{0}] = {1}; low[{0}] = {2:.17g}; high[{0}] = {3:.17g}\n", i + 1, r.fixed ? 1 : 0,
                        r.low, r.high);
    }
    gp << plot_script;
  };
  auto run = [&](const std::string& terminal) {
    write_script(terminal);
    return run_gnuplot({"-c", script.string(), png.temporary_path(), data.string(), plain_text(title), plain_text(x_label), y_labels},
                       log);
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
  png.commit();
}

}  // namespace radchain::cli

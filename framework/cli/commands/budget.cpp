// `radchain budget`: the sensitivity (error) budget of named results, and optionally its tornado plot.
//
// The plot follows plot.cpp's trust rule: the gnuplot script is constant text; everything from outside (sensor
// name and path, parameter and result names, units, the output path) reaches gnuplot as data: `gnuplot -c
// script ARG1 … ARG4` string arguments and the tab-separated data file, never as script text; gnuplot is started
// with posix_spawnp, no shell. (plot.cpp keeps its spawner private, so the few lines of it are repeated here.)
#include "../commands.hpp"
#include "../common.hpp"
#include "../overrides.hpp"

#include "radchain/atomic_file.hpp"
#include "radchain/batch/budget.hpp"
#include "radchain/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace radchain::cli {
namespace {
namespace fs = std::filesystem;

constexpr char label_separator = '\x1f';
constexpr std::size_t tornado_rows = 15;  // the largest |elasticity| per result

// ARG1 output PNG, ARG2 data file (one block per result, separated by two blank lines: label TAB elasticity,
// smallest first so that the largest bar is on top), ARG3 title, ARG4 the x labels separated by \037. The
// terminal, the panel count and each panel's row count are written before it by radchain.
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

std::string plain_text(std::string text) {
  for (char& c : text)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
  return text;
}

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

// One panel per result: the elasticities ∂r/∂ln x of its largest entries as horizontal bars about zero.
void plot_tornado(const std::string& png_path, const Budget& budget) {
  AtomicFile png(png_path, "--plot");
  static std::atomic<int> counter{0};
  const fs::path dir = fs::temp_directory_path() / fmt::format("radchain-budget-{}-{}", ::getpid(), counter++);
  fs::create_directories(dir);
  const fs::path data = dir / "data.tsv", script = dir / "tornado.gp", log = dir / "gnuplot.log";
  std::vector<std::size_t> rows;
  std::string x_labels;
  {
    std::ofstream out(data);
    for (std::size_t k = 0; k < budget.results.size(); ++k) {
      std::vector<const BudgetEntry*> entries;
      for (const auto& e : budget.entries)
        if (e.result == budget.results[k] && e.ok && entries.size() < tornado_rows) entries.push_back(&e);
      std::reverse(entries.begin(), entries.end());  // smallest at the bottom
      if (k) out << "\n\n";
      if (entries.empty()) out << "(none)\t0\n";
      for (const BudgetEntry* e : entries)
        out << plain_text(e->parameter) << '\t' << fmt::format("{:.17g}", e->elasticity) << '\n';
      rows.push_back(std::max<std::size_t>(entries.size(), 1));
      const std::string unit = budget.entries.empty() ? "" : [&] {
        for (const auto& e : budget.entries)
          if (e.result == budget.results[k]) return e.result_unit;
        return std::string();
      }();
      if (k) x_labels += label_separator;
      x_labels += plain_text(fmt::format("∂ {} / ∂ ln x{}   (change for +1 % of x: 0.01 × bar)", budget.results[k],
                                         unit.empty() || unit == "1" ? "" : " [" + unit + "]"));
    }
  }
  auto write_script = [&](const std::string& terminal) {
    std::ofstream gp(script);
    std::size_t height = 60;
    for (std::size_t r : rows) height += 90 + 26 * r;
    gp << fmt::format("set terminal {} noenhanced size 900,{}\n", terminal, height);
    gp << fmt::format("panels = {}\narray rows[{}]\n", rows.size(), rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) gp << fmt::format("rows[{}] = {}\n", i + 1, rows[i]);
    gp << tornado_script;
  };
  const std::string title = plain_text(budget.sensor_name + " — " + budget.sensor_file);
  auto run = [&](const std::string& terminal) {
    write_script(terminal);
    return run_gnuplot({"-c", script.string(), png.temporary_path(), data.string(), title, x_labels}, log);
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

}  // namespace

int budget(const BudgetCommand& command) {
  const TableFormat format = format_of(command.output, TableFormat::text);
  if (format != TableFormat::text && format != TableFormat::csv && format != TableFormat::json)
    throw InputError(SourceLocation{"--format", 0, 0}, "", to_string(format), "the budget is written as text, csv or json");
  Chain chain = load_sensor_of(command.sensor);
  BudgetOptions options;
  options.results = command.results;
  Budget result;
  try {
    result = compute_budget(chain, options);
  } catch (const InputError&) {
    throw;
  } catch (const std::runtime_error& error) {
    std::cerr << "radchain budget: " << command.sensor.sensor << ": " << error.what() << "\n";
    return 1;
  }
  Sink sink(command.output.out);
  write_budget(result, format, sink.stream());
  sink.commit();
  if (!command.plot.empty()) {
    try {
      plot_tornado(command.plot, result);
    } catch (const std::runtime_error& error) {
      if (dynamic_cast<const InputError*>(&error) || dynamic_cast<const WriteError*>(&error)) throw;
      throw InputError(SourceLocation{"--plot", 0, 0}, "", command.plot, error.what());
    }
  }
  // A derivative that could not be computed is a failed check: the budget is incomplete.
  const bool failed = std::any_of(result.entries.begin(), result.entries.end(), [](const BudgetEntry& e) { return !e.ok; });
  if (failed) std::cerr << "radchain budget: some derivatives failed (see the note column)\n";
  return failed ? 1 : 0;
}

}  // namespace radchain::cli

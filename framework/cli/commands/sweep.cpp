// `radchain sweep`: a grid of parameter values, solves at every point; optionally a plot (curves of a 1-D sweep,
// heat maps of a 2-D one).
#include "../commands.hpp"
#include "../common.hpp"
#include "../plot.hpp"
#include "../progress.hpp"

#include "radchain/error.hpp"
#include "radchain/batch/sweep.hpp"
#include "radchain/batch/thread_pool.hpp"
#include "radchain/strings.hpp"
#include "radchain/vocabulary.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iostream>

namespace radchain::cli {

int sweep(const SweepCommand& command) {
  SweepOptions options;
  options.sensor_file = command.sensor.sensor;
  for (const auto& s : command.sensor.sets) {
    Override o = parse_override(s);
    if (is_sweep_range(strings::unquoted(o.value)))
      options.axes.emplace_back(o.key, strings::unquoted(o.value));
    else
      options.overrides.push_back(o);
  }
  if (options.axes.empty())
    throw InputError(SourceLocation{"sweep", 0, 0}, "", "",
                     "no axis: give at least one --set <section>.<key>=from:to:steps, e.g. --set optics.aperture=\"15 cm:30 cm:16\"");
  options.results = command.results;
  options.no_solve = command.sensor.no_solve;
  options.solver = command.sensor.solver == "root" ? SolverChoice::root : SolverChoice::automatic;
  options.allow_large = command.allow_large;
  options.shard = shard_of(command.batch);
  const TableFormat format = format_of(command.output, TableFormat::csv);
  if (!command.plot.empty() && options.axes.size() > 2)
    throw InputError(SourceLocation{"--plot", 0, 0}, "", command.plot,
                     fmt::format("plots are drawn for sweeps of one axis (curves) or two (heat maps); this sweep has {} axes "
                                 "(plot the CSV instead)", options.axes.size()));
  if (!command.plot.empty() && options.shard.active())
    throw InputError(SourceLocation{"--plot", 0, 0}, "", command.plot, "a shard has part of the sweep: plot the merged output");
  limit_threads(command.batch.threads);

  Progress progress("sweep");
  options.progress = progress.counter();
  Sweep sweep(options);
  // The file as swept (fixed overrides applied): its solves and its name, and a warning for a fixed --set on an
  // unknown that a [[solve]] overwrites at every point (Sweep refuses an axis on one).
  Chain chain = load_sensor(options.sensor_file, options.overrides,
                            options.no_solve ? Solving::forward_only : Solving::as_written);
  warn_about_solved_overrides(chain.solves, options.overrides, std::cerr);

  // The plotted series: --results, else the solved unknowns, else the SNR, else the first result.
  std::vector<std::size_t> plotted;
  if (!command.plot.empty()) {
    const auto& names = sweep.results();
    auto index_of = [&](const std::string& name) {
      return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
    };
    if (!command.results.empty()) {
      for (std::size_t i = 0; i < names.size(); ++i) plotted.push_back(i);
    } else {
      for (const auto& s : chain.solves)
        if (index_of(s.unknown) < names.size()) plotted.push_back(index_of(s.unknown));
      const std::string snr(vocabulary::detector_snr.name);
      if (plotted.empty() && index_of(snr) < names.size()) plotted.push_back(index_of(snr));
      if (plotted.empty() && !names.empty()) plotted.push_back(0);
    }
  }
  std::vector<double> x;
  std::vector<PlotSeries> series;
  for (std::size_t i : plotted) series.push_back(PlotSeries{sweep.results()[i], sweep.result_units()[i], {}});
  auto observer = [&](std::size_t, const double* values) {
    x.push_back(values[0]);
    for (std::size_t s = 0; s < plotted.size(); ++s) series[s].y.push_back(values[sweep.axes().size() + plotted[s]]);
  };

  Sink sink(command.output.out);
  TableWriter writer(sink.stream(), format, sweep.layout(), sweep.points(), options.shard, sweep.job());
  progress.start(shard_points(options.shard, sweep.points()).count);
  std::string failure;
  const int code = sweep.run(writer, &failure, plotted.empty() ? std::function<void(std::size_t, const double*)>() : observer);
  progress.stop();
  writer.finish(code);
  sink.commit();
  if (command.explain) std::cerr << "radchain sweep: " << sweep.method() << "\n";
  if (code != 0) std::cerr << "radchain sweep: " << failure << "\n";
  if (!command.plot.empty()) {
    auto axis_label = [](const SweepAxis& axis) { return axis.unit.empty() ? axis.key : axis.key + " [" + axis.unit + "]"; };
    auto axis_values = [](const SweepAxis& axis) {
      std::vector<double> v;
      for (std::size_t i = 0; i < axis.steps; ++i) v.push_back(axis.value(i));
      return v;
    };
    const std::string title = chain.sensor_name + " — " + options.sensor_file;
    try {
      if (sweep.axes().size() == 2)
        plot_heatmaps(command.plot, title, axis_label(sweep.axes()[0]), axis_label(sweep.axes()[1]),
                      axis_values(sweep.axes()[0]), axis_values(sweep.axes()[1]), series);
      else
        plot_sweep(command.plot, title, axis_label(sweep.axes().front()), x, series);
    } catch (const std::runtime_error& error) {
      if (dynamic_cast<const InputError*>(&error) || dynamic_cast<const WriteError*>(&error)) throw;
      throw InputError(SourceLocation{"--plot", 0, 0}, "", command.plot, error.what());
    }
  }
  return code;
}

}  // namespace radchain::cli

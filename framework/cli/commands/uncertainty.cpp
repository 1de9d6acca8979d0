// `radchain uncertainty`: Monte Carlo propagation of input distributions (radchain/batch/uncertainty.hpp).
#include "../commands.hpp"
#include "../common.hpp"
#include "../overrides.hpp"
#include "../plot.hpp"

#include "radchain/batch/thread_pool.hpp"
#include "radchain/batch/uncertainty.hpp"
#include "radchain/atomic_file.hpp"
#include "radchain/error.hpp"

#include <fmt/format.h>

#include <iostream>

namespace radchain::cli {

int uncertainty(const UncertaintyCommand& command) {
  const TableFormat format = format_of(command.output, TableFormat::text);
  if (format != TableFormat::text && format != TableFormat::csv && format != TableFormat::json)
    throw InputError(SourceLocation{"--format", 0, 0}, "", to_string(format), "the uncertainty table is written as text, csv or json");
  UncertaintyOptions options;
  options.sensor_file = command.sensor.sensor;
  options.overrides = parse_overrides(command.sensor.sets);
  options.no_solve = command.sensor.no_solve;
  options.solver = command.sensor.solver == "root" ? SolverChoice::root : SolverChoice::automatic;
  options.vary = command.vary;
  options.results = command.results;
  options.samples = command.samples;
  options.seed = command.seed;
  if (!options.no_solve) {  // a --set on a solved unknown is overwritten at every sample: say so, as run does
    const Chain chain = load_sensor(options.sensor_file, options.overrides);
    warn_about_solved_overrides(chain.solves, options.overrides, std::cerr);
  }
  limit_threads(command.threads);
  const Uncertainty result = run_uncertainty(options);
  if (!command.plot.empty()) {  // drawn before the table is written: a failed plot leaves no partial output
    std::vector<HistogramPanel> panels;
    const Chain chain = load_sensor(options.sensor_file, options.overrides);
    for (const auto& s : result.results) {
      const ResultInfo& info = chain.results().info(*chain.results().find(s.name));
      const Histogram h = histogram_of(s.values);
      HistogramPanel panel{s.name, info.display_unit, {}, h.counts, {}};
      for (const double e : h.edges) panel.edges.push_back(e * info.display_factor);
      for (const double m : {s.p5, s.p50, s.p95}) panel.marks.push_back(m * info.display_factor);
      panels.push_back(std::move(panel));
    }
    try {
      plot_histograms(command.plot, fmt::format("{} — {} samples (dashed: 5, 50, 95 %)", result.sensor_name, result.used), panels);
    } catch (const std::runtime_error& error) {
      if (dynamic_cast<const InputError*>(&error) || dynamic_cast<const WriteError*>(&error)) throw;
      throw InputError(SourceLocation{"--plot", 0, 0}, "", command.plot, error.what());
    }
  }
  Sink sink(command.output.out);
  write_uncertainty(result, format, sink.stream());
  sink.commit();
  if (result.failed > 0) std::cerr << "radchain uncertainty: " << result.failed << " samples failed; first: " << result.first_failure << "\n";
  return result.failed > 0 ? 1 : 0;
}

}  // namespace radchain::cli

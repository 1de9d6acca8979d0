// `radchain uncertainty`: Monte Carlo propagation of input distributions (radchain/batch/uncertainty.hpp).
#include "../commands.hpp"
#include "../common.hpp"
#include "../overrides.hpp"

#include "radchain/batch/thread_pool.hpp"
#include "radchain/batch/uncertainty.hpp"
#include "radchain/error.hpp"

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
  Sink sink(command.output.out);
  write_uncertainty(result, format, sink.stream());
  sink.commit();
  if (result.failed > 0) std::cerr << "radchain uncertainty: " << result.failed << " samples failed; first: " << result.first_failure << "\n";
  return result.failed > 0 ? 1 : 0;
}

}  // namespace radchain::cli

// `radchain catalogue`: many sensor files, key results against their [expected] references.
#include "../commands.hpp"
#include "../common.hpp"
#include "../progress.hpp"

#include "radchain/batch/catalogue.hpp"
#include "radchain/batch/thread_pool.hpp"

#include <iostream>

namespace radchain::cli {

int catalogue(const CatalogueCommand& command) {
  CatalogueOptions options;
  options.overrides = parse_overrides(command.sets);
  options.extra_results = command.results;
  options.no_solve = command.no_solve;
  options.tables = command.tables;
  options.uncertainty_samples = command.uncertainty;
  options.solver = command.solver == "root" ? SolverChoice::root : SolverChoice::automatic;
  options.shard = shard_of(command.batch);
  const TableFormat format = format_of(command.output, TableFormat::text);
  const std::vector<std::string> files = catalogue_files(command.inputs);
  limit_threads(command.batch.threads);

  Progress progress("catalogue");
  options.progress = progress.counter();
  Sink sink(command.output.out);
  TableWriter writer(sink.stream(), format, command.wide ? wide_text(catalogue_layout()) : catalogue_layout(), files.size(), options.shard,
                     catalogue_job(files, options));
  progress.start(shard_points(options.shard, files.size()).count);
  std::vector<std::string> errors;
  const int code = run_catalogue(files, options, writer, &errors);
  progress.stop();
  writer.finish(code);
  sink.commit();
  for (const auto& e : errors) std::cerr << e << "\n";
  return code;
}

}  // namespace radchain::cli

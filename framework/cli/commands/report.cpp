// `radchain report`: the static HTML report of sensor files (radchain/batch/html_report.hpp).
#include "../commands.hpp"
#include "../overrides.hpp"
#include "../progress.hpp"

#include "radchain/batch/catalogue.hpp"
#include "radchain/batch/html_report.hpp"
#include "radchain/batch/thread_pool.hpp"
#include "radchain/version.hpp"

#include <fmt/format.h>

#include <iostream>

namespace radchain::cli {

int report(const ReportCommand& command) {
  HtmlReportOptions options;
  options.overrides = parse_overrides(command.sets);
  options.solver = command.solver == "root" ? SolverChoice::root : SolverChoice::automatic;
  options.budget = !command.no_budget;
  options.generator = fmt::format("radchain {} (plugin ABI {})", framework_version, plugin_abi_version);
  const std::vector<std::string> files = catalogue_files(command.inputs);
  limit_threads(command.threads);

  Progress progress("report");
  options.progress = progress.counter();
  progress.start(files.size());
  const HtmlReportOutcome outcome = write_html_report(files, command.out, options);
  progress.stop();
  for (const auto& e : outcome.errors) std::cerr << e << "\n";
  std::cout << fmt::format("{}/index.html: {} sensor page{} and report.json\n{}\n", outcome.folder, outcome.pages,
                           outcome.pages == 1 ? "" : "s", outcome.summary);
  return outcome.exit_code;
}

}  // namespace radchain::cli

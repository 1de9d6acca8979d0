// `radchain run`: one sensor file forward, its solves (unless --no-solve) and its [expected] checks, as text or JSON.
#include "../commands.hpp"
#include "../overrides.hpp"

#include "radchain/report.hpp"

#include <iostream>

namespace radchain::cli {

int run(const RunCommand& options) {
  Chain chain = load_sensor_of(options.sensor);
  const Report report = chain.run();
  std::cout << (options.format == "json" ? format_report_json(report) : format_report_text(report));
  return report.all_passed() ? 0 : 1;
}

}  // namespace radchain::cli

// `radchain run`: one sensor file forward, its solves and its [expected] checks, as text or JSON.
#include "../common.hpp"
#include "radchain/chain.hpp"
#include "radchain/error.hpp"
#include "radchain/report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <iostream>

namespace radchain::cli {

int run(const RunOptions& options) {
  Chain chain = load_sensor(options.sensor, parse_overrides(options.sets));
  const Report report = chain.run();
  std::cout << (options.format == "json" ? format_report_json(report) : format_report_text(report));
  return report.all_passed() ? 0 : 1;
}

}  // namespace radchain::cli

// `radchain compare`: two sensor files or saved results side by side.
#include "../common.hpp"
#include "radchain/chain.hpp"
#include "radchain/error.hpp"
#include "radchain/batch/compare.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <iostream>

namespace radchain::cli {

int compare(const CompareCommand& command) {
  std::optional<double> tolerance;
  if (!command.tolerance.empty()) tolerance = parse_tolerance(command.tolerance);
  const TableFormat format = format_of(command.output, TableFormat::text);
  const auto overrides = parse_overrides(command.sets);
  const CompareInput a = load_compare_input(command.a, overrides);
  const CompareInput b = load_compare_input(command.b, overrides);
  const Comparison comparison = radchain::compare(a, b);
  Sink sink(command.output.out);
  write_comparison(comparison, format, sink.stream(), tolerance);
  return tolerance && count_exceeding(comparison, *tolerance) > 0 ? 1 : 0;
}

}  // namespace radchain::cli

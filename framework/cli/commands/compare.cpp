// `radchain compare`: two sensor files or saved results side by side.
#include "../commands.hpp"
#include "../common.hpp"

#include "radchain/batch/compare.hpp"

#include <algorithm>
#include <iostream>

namespace radchain::cli {

int compare(const CompareCommand& command) {
  std::optional<double> tolerance;
  if (!command.tolerance.empty()) tolerance = parse_tolerance(command.tolerance);
  const TableFormat format = format_of(command.output, TableFormat::text);
  const auto overrides = parse_overrides(command.sets);
  const CompareInput a = load_compare_input(command.a, overrides, !command.no_solve);
  const CompareInput b = load_compare_input(command.b, overrides, !command.no_solve);
  // One warning per --set that a [[solve]] overwrites, in A or in B.
  std::vector<SolveSpec> solves;
  for (const CompareInput* input : {&a, &b})
    if (input->chain)
      for (const auto& s : input->chain->solves)
        if (std::none_of(solves.begin(), solves.end(), [&](const SolveSpec& x) { return x.unknown == s.unknown; }))
          solves.push_back(s);
  warn_about_solved_overrides(solves, overrides, std::cerr);
  const Comparison comparison = radchain::compare(a, b);
  Sink sink(command.output.out);
  write_comparison(comparison, format, sink.stream(), tolerance);
  sink.commit();
  return tolerance && count_exceeding(comparison, *tolerance) > 0 ? 1 : 0;
}

}  // namespace radchain::cli

// `radchain budget`: the sensitivity (error) budget of named results, and optionally its tornado plot (plot.cpp:
// names and units reach gnuplot as data, never as script text).
#include "../commands.hpp"
#include "../common.hpp"
#include "../overrides.hpp"
#include "../plot.hpp"

#include "radchain/batch/budget.hpp"
#include "radchain/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <stdexcept>

namespace radchain::cli {
namespace {

constexpr std::size_t tornado_rows = 15;  // the largest |elasticity| per result

// One panel per result: the elasticities ∂r/∂ln x of its largest entries as horizontal bars about zero. Inputs the
// result does not depend on (a zero bar) are counted in the axis label instead of filling rows; an input whose
// derivative failed keeps a row, labelled so, with no bar: it is not silently left out.
void plot_budget(const std::string& png_path, const Budget& budget) {
  std::vector<TornadoPanel> panels;
  for (const std::string& result : budget.results) {
    TornadoPanel panel;
    std::string unit;
    double largest = 0;
    for (const auto& e : budget.entries)
      if (e.result == result && e.ok) largest = std::max(largest, std::abs(e.elasticity));
    std::size_t no_effect = 0, failed = 0;
    for (const auto& e : budget.entries) {
      if (e.result != result) continue;
      unit = e.result_unit;
      if (!e.ok) {
        ++failed;
        if (panel.bars.size() < tornado_rows) panel.bars.emplace_back(e.parameter + ": no derivative (failed)", 0.0);
        continue;
      }
      if (std::abs(e.elasticity) <= 1e-12 * largest) {
        ++no_effect;
        continue;
      }
      // A magnitude's bar is per ln of the flux it stands for (BudgetEntry::per_flux): its label says so.
      if (panel.bars.size() < tornado_rows) panel.bars.emplace_back(e.parameter + (e.per_flux ? " (per ln flux)" : ""), e.elasticity);
    }
    std::reverse(panel.bars.begin(), panel.bars.end());  // ranked largest first: the largest bar on top
    std::string notes;
    if (no_effect) notes += fmt::format("; {} without effect not shown", no_effect);
    if (failed) notes += fmt::format("; {} failed", failed);
    panel.x_label = fmt::format("∂ {} / ∂ ln x{}   (change for +1 % of x: 0.01 × bar{})", result,
                                unit.empty() || unit == "1" ? "" : " [" + unit + "]", notes);
    panels.push_back(std::move(panel));
  }
  plot_tornado(png_path, budget.sensor_name + " — " + budget.sensor_file, panels);
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
      plot_budget(command.plot, result);
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

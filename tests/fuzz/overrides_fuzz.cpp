// Command-line values: `--set section.key=value` overrides (fixed values through load + run, as `radchain run
// --set`), sweep ranges `--set key=from:to:steps` (parsed and checked as `radchain sweep` does, then the grid's
// first and last points evaluated), and `--shard k/n`. One input line per option: a line starting "--shard "
// is a shard, any other line a --set, against sensors/msx-sbv.toml.
#include "fuzz_input.hpp"

#include "overrides.hpp"

#include "radchain/error.hpp"
#include "radchain/batch/shard.hpp"
#include "radchain/batch/sweep.hpp"
#include "radchain/strings.hpp"

#include <sstream>
#include <vector>

namespace {
const std::string sensor = RADCHAIN_SOURCE_DIR "/sensors/msx-sbv.toml";
}

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  radchain::fuzz::configure_host();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    radchain::SweepOptions options;
    options.sensor_file = sensor;
    std::istringstream lines{std::string(radchain::fuzz::as_text(data, size))};
    const std::string shard_prefix = "--shard ";
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind(shard_prefix, 0) == 0) {
        options.shard = radchain::parse_shard(line.substr(shard_prefix.size()), "round-robin");
        continue;
      }
      // As `radchain sweep` sorts its --set options (framework/cli/commands/sweep.cpp).
      radchain::Override o = radchain::cli::parse_override(line);
      if (radchain::is_sweep_range(radchain::strings::unquoted(o.value)))
        options.axes.emplace_back(o.key, radchain::strings::unquoted(o.value));
      else
        options.overrides.push_back(o);
    }
    if (options.axes.empty()) {
      radchain::Chain chain = radchain::load_sensor(sensor, options.overrides);
      (void)chain.run();
      return 0;
    }
    const radchain::Sweep sweep(options);
    radchain::SweepWorker worker(sweep);
    std::vector<double> row(sweep.columns());
    (void)worker.evaluate(0, row.data());
    (void)worker.evaluate(sweep.points() - 1, row.data());
  } catch (const radchain::InputError&) {
  }
  return 0;
}

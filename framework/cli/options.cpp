// The options that several subcommands share, declared once (the structs are in options.hpp).
#include "options.hpp"

#include <CLI/CLI.hpp>

namespace radchain::cli {

void add_sets(CLI::App* command, std::vector<std::string>& sets, const std::string& help) {
  command->add_option("--set", sets, help);
}

void add_sensor(CLI::App* command, SensorArgs& sensor, const std::string& help) {
  command->add_option("sensor", sensor.sensor, "sensor TOML file")->required();
  add_sets(command, sensor.sets, help);
}

void add_no_solve(CLI::App* command, bool& no_solve) {
  command->add_flag("--no-solve", no_solve, "evaluate forward only: skip the [[solve]] entries (the unknowns keep their values)");
}

void add_solver(CLI::App* command, std::string& solver) {
  command->add_option("--solver", solver,
                      "auto: closed form where the chain declares it (checked), else bracketing; root: always bracketing")
      ->check(CLI::IsMember({"auto", "root"}));
}

void add_output(CLI::App* command, Output& output, const std::string& formats) {
  command->add_option("--out", output.out, "write to this file instead of stdout (.csv/.json/.txt also set the format)");
  command->add_option("--format", output.format, formats);
}

// A count is never negative: CLI11 would read "-1" into a std::size_t as 2⁶⁴ − 1.
void add_threads(CLI::App* command, std::size_t& threads, const std::string& description) {
  command->add_option("--threads", threads, description)->check(CLI::Range(std::size_t{0}, max_threads));
}

void add_samples(CLI::App* command, std::size_t& samples, const std::string& description) {
  command->add_option("--samples", samples, description)->check(CLI::NonNegativeNumber);
}

void add_batch(CLI::App* command, Batch& batch) {
  command->add_option("--shard", batch.shard, "run part k of n of the job (k/n) and write a shard file for `radchain merge`");
  command->add_option("--shard-order", batch.shard_order, "how points are dealt to shards: block (contiguous) or round-robin");
  add_threads(command, batch.threads, "threads to use (default: all cores)");
}

void add_seed(CLI::App* command, std::uint64_t& seed) {
  command->add_option("--seed", seed, "noise seed (same seed, same image)");
}

}  // namespace radchain::cli

#pragma once
// The subcommands of the `radchain` CLI. main.cpp parses the command line into these option structs; each
// command calls the framework (catalogue.hpp, compare.hpp, sweep.hpp, shard.hpp) and returns the exit code:
// 0 ok, 1 a failed check, 2 bad input. Bad input is thrown as InputError and printed by main as one line.
#include "radchain/chain.hpp"

#include <string>
#include <vector>

namespace radchain::cli {

// `--set section.key=value` options as overrides (one clear error line for a malformed one).
std::vector<Override> parse_overrides(const std::vector<std::string>& sets);

struct Output {
  std::string out;     // --out file ("" = stdout)
  std::string format;  // --format ("" = from --out's extension, else the command's default)
};

struct Batch {
  std::string shard;                 // --shard k/n
  std::string shard_order = "block"; // --shard-order block|round-robin
  std::size_t threads = 0;           // --threads (0 = all cores)
};

struct RunOptions {
  std::string sensor;
  std::vector<std::string> sets;
  std::string format = "text";
};
int run(const RunOptions& options);

struct CatalogueCommand {
  std::vector<std::string> inputs;
  std::vector<std::string> sets;
  std::vector<std::string> results;
  Output output;
  Batch batch;
};
int catalogue(const CatalogueCommand& options);

struct CompareCommand {
  std::string a, b;
  std::vector<std::string> sets;
  std::string tolerance;
  Output output;
};
int compare(const CompareCommand& options);

struct SweepCommand {
  std::string sensor;
  std::vector<std::string> sets;
  std::vector<std::string> results;
  std::string plot;
  Output output;
  Batch batch;
};
int sweep(const SweepCommand& options);

// MTF curves of a pushbroom design (Kolobrodov 1996 Fig. 2) as CSV (stdout or --out) and optionally a PNG.
struct MtfCommand {
  std::string sensor;
  std::vector<std::string> sets;
  std::string out;
  std::string plot;
};
int mtf(const MtfCommand& options);

struct MergeCommand {
  std::vector<std::string> shards;
  Output output;
};
int merge(const MergeCommand& options);

int plugins();
int describe(const std::string& name);

}  // namespace radchain::cli

#pragma once
// `radchain catalogue`: every sensor file evaluated (solves included), one table of its key results against
// the [expected] references in the file: computed value, reference, delta in the reference's unit and in
// percent, ok / FAIL. Exit code 0 when every check holds, 1 when one fails, 2 when a file is bad input.
//
// Rows per sensor file, in this order: each [expected] check; each solved unknown that no check covers; each
// result asked for with --results; with --tables, each cell of its [[table]] entries; with --uncertainty N, the
// 5 % and 95 % points of each solved unknown and checked result under the file's [uncertainty] tolerances. A file that does not load gives one ERROR row (and its one-line message).
#include "radchain/chain.hpp"
#include "radchain/batch/table.hpp"

#include <atomic>
#include <memory>
#include <string>
#include <vector>

namespace radchain {

// Sensor files from files and folders (a folder: its *.toml, sorted), in the order given. Throws InputError
// for a path that does not exist or a folder without sensor files.
std::vector<std::string> catalogue_files(const std::vector<std::string>& inputs);

struct CatalogueOptions {
  std::vector<Override> overrides;         // --set, applied to every file
  std::vector<std::string> extra_results;  // --results: more rows per file
  bool no_solve = false;                   // --no-solve: every file forward only, its [[solve]] entries skipped
  bool tables = false;                     // --tables: each file's [[table]] entries too, a row per cell
  std::size_t uncertainty_samples = 0;     // --uncertainty N: 5 % and 95 % rows from the file's [uncertainty]
  SolverChoice solver = SolverChoice::automatic;  // --solver
  ShardSpec shard;
  std::atomic<std::size_t>* progress = nullptr;  // counts finished files
};

// Columns: sensor, instrument, result, kind, computed, reference, tolerance, unit, delta, delta_pct, check, note.
TableLayout catalogue_layout();

// The rows of one evaluated sensor file (the sensor column is the file's stem).
std::vector<std::vector<std::string>> catalogue_rows(const std::string& file, const Report& report,
                                                     const std::vector<std::string>& extra_results = {});
// The row of a file that could not be evaluated.
std::vector<std::string> catalogue_error_row(const std::string& file, const std::string& message);

// Evaluates the files of the shard on all cores (one file per task; a Chain per file) and writes their rows
// in file order. One-line messages of files that are bad input are appended to `errors` (in file order).
// Returns the exit code: 2 if a file was bad input, else 1 if a check or a solve failed, else 0.
int run_catalogue(const std::vector<std::string>& files, const CatalogueOptions& options, TableWriter& writer,
                  std::vector<std::string>* errors = nullptr);

// What identifies a catalogue job for merge: files, overrides, extra results (the shard header adds the format).
std::string catalogue_job(const std::vector<std::string>& files, const CatalogueOptions& options);

// Text footer / JSON summary: "4 sensor files, 17 checks: all passed".
std::unique_ptr<TableSummary> catalogue_summary();

// Loads every plugin on the search path once, before a parallel job: the plugin host then only reads its
// tables while workers build chains.
void preload_plugins();

}  // namespace radchain

#pragma once
// The subcommands of the `radchain` executable. main.cpp parses the command line into the option structs
// (options.hpp); each command calls one library function (radchain::batch, radchain::core) and prints, and
// returns the exit code: 0 ok, 1 a failed check, 2 bad input. Bad input is thrown as InputError and printed
// by main as one line. render, validate and mtf run in the imaging module (imaging_module.hpp), loaded only
// for them: the executable does not link OpenImageIO or FFTW.
#include "options.hpp"

#include <string>
#include <vector>

namespace radchain::cli {

int run(const RunCommand& options);
int catalogue(const CatalogueCommand& options);
int compare(const CompareCommand& options);
int sweep(const SweepCommand& options);
int merge(const MergeCommand& options);
int plugins();
int describe(const std::string& name);

// radchain report FILE|DIR... --out DIR [--set k=v] [--no-budget] [--threads N]: a static HTML report (an index of
// instruments and checks, a page per sensor with its inputs, results, checks and plots) and report.json, written
// whole or not at all (radchain/batch/html_report.hpp). Exit as the catalogue: 1 a failed check, 2 a bad file.
struct ReportCommand {
  std::vector<std::string> inputs;  // sensor files or folders
  std::string out;                  // --out DIR (required)
  std::vector<std::string> sets;    // --set, every file
  bool no_budget = false;           // --no-budget: no sensitivity tornado (the slowest part)
  std::string solver = "auto";      // --solver
  std::size_t threads = 0;          // --threads
};
int report(const ReportCommand& options);  // commands/report.cpp

// Through the imaging module (imaging_loader.cpp); exit 2 with one line when it cannot be loaded.
int render(const RenderCommand& options);
int validate(const ValidateCommand& options);
int mtf(const MtfCommand& options);

}  // namespace radchain::cli

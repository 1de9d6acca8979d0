#pragma once
// `radchain report FILE|DIR... --out DIR`: a self-contained static HTML report of sensor files — no network, no
// server, no external script or style; plots are inline SVG (radchain/batch/svg_plot.hpp).
//
//   DIR/index.html          the instruments (name, file, kinds of check, key results, status) and every check
//                           (kind, computed, reference, tolerance, status), each table sortable by its headers
//   DIR/sensors/<stem>.html one page per sensor file: what the instrument is ([sensor]), the chain of plugins,
//                           every input as written with its unit and provenance (line, default, --set, solved),
//                           every result with value, unit, stage and equation, the solves and what binds, the
//                           [expected] checks, the criteria, the warnings, the [[table]] entries, and the plots:
//                           SNR vs the target's brightness (a forward sweep), limiting magnitude vs exposure (the
//                           file's [[table]], else a sweep), the MTF budget, the sensitivity tornado
//   DIR/report.json         every number the pages show; each number on a page names its place here
//                           (data-json="/sensors/3/results/12/value", a JSON pointer)
//
// Every number is the chain's own: results, solves and checks from Chain::run(), the brightness sweep by
// Chain::set/evaluate, the exposure sweep by Chain::tabulate, the tornado by compute_budget (budget.hpp), the
// MTF curves by the core's physics/mtf_budget.hpp and physics/mtf.hpp from the parameters the chain reports.
//
// The folder is written whole or not at all: the files go to a hidden folder beside DIR, which is renamed to DIR
// (or, when DIR holds an earlier report, exchanged with it atomically and the old one removed). DIR may not be an
// input or hold one, and a folder that is not an earlier radchain report is refused rather than replaced.
#include "radchain/chain.hpp"

#include <atomic>
#include <string>
#include <vector>

namespace radchain {

struct HtmlReportOptions {
  std::vector<Override> overrides;  // --set, applied to every file
  SolverChoice solver = SolverChoice::automatic;
  bool budget = true;               // the sensitivity tornado (compute_budget: the slowest part)
  std::size_t sweep_points = 41;    // points of the brightness and exposure sweeps
  std::string generator;            // "radchain 0.9.0 (plugin ABI 7)": shown in the footer and in report.json
  std::atomic<std::size_t>* progress = nullptr;  // counts finished files
};

struct HtmlReportOutcome {
  std::string folder;              // DIR as written
  std::size_t files = 0, pages = 0, checks = 0, failed = 0, bad_files = 0, warnings = 0;
  std::string summary;             // "37 sensor files, 70 checks (…): all passed", as the catalogue counts
  std::vector<std::string> errors;  // one located line per file that is bad input (its page shows it too)
  // 2 if a file was bad input, else 1 if a check, a solve or a criterion failed, else 0 (as `radchain catalogue`).
  int exit_code = 0;
};

// Evaluates the files (on all cores, one file per task) and writes the report into `out_dir`. Throws
// InputError for an unusable --out (an input, a non-report folder, a missing parent) and WriteError when a
// write fails; a sensor file that is bad input is not thrown but reported (its row and page say why).
HtmlReportOutcome write_html_report(const std::vector<std::string>& files, const std::string& out_dir,
                                    const HtmlReportOptions& options);

}  // namespace radchain

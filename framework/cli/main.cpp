// radchain: the command-line host. Subcommands: run, catalogue, report, compare, sweep, merge, budget, uncertainty, mtf,
// render, validate, plugins, describe. This file only declares the options (CLI11; the shared ones in options.cpp) and dispatches;
// commands/<name>.cpp run one subcommand each through one library call.
// Exit codes: 0 ok, 1 a failed check ([expected], a solve, a compare tolerance), 2 bad input (one line on
// stderr), 3 an internal error.
#include "commands.hpp"
#include "terminal.hpp"
#include "radchain/atomic_file.hpp"
#include "radchain/error.hpp"
#include "radchain/plugin_host.hpp"
#include "radchain/version.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <csignal>
#include <cstring>
#include <iostream>

#include <unistd.h>

namespace {
using namespace radchain;

// Every signal whose default action ends the process and that a program may catch (SIGKILL and SIGSTOP cannot be;
// SIGXFSZ is left to make the write fail, which the output reports; SIGPIPE ends a pipeline quietly).
struct StopSignal {
  int number;
  const char* message;  // written from the handler: a literal (async-signal-safe)
};
constexpr StopSignal stop_signals[] = {
    {SIGINT, "radchain: interrupted (SIGINT); no output file was written\n"},
    {SIGTERM, "radchain: terminated (SIGTERM); no output file was written\n"},
    {SIGHUP, "radchain: hung up (SIGHUP); no output file was written\n"},
    {SIGQUIT, "radchain: quit (SIGQUIT); no output file was written\n"},
    {SIGUSR1, "radchain: stopped by SIGUSR1; no output file was written\n"},
    {SIGUSR2, "radchain: stopped by SIGUSR2; no output file was written\n"},
    {SIGALRM, "radchain: stopped by SIGALRM; no output file was written\n"},
    {SIGVTALRM, "radchain: stopped by SIGVTALRM; no output file was written\n"},
    {SIGXCPU, "radchain: CPU time limit reached (SIGXCPU); no output file was written\n"},
};

// Remove every output not yet complete (its temporary), say so, and die of the signal.
extern "C" void stop_on_signal(int signal) {
  AtomicFile::remove_pending();
  for (const StopSignal& s : stop_signals) {
    if (s.number != signal) continue;
    [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, s.message, std::strlen(s.message));
  }
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

void stop_cleanly_on_signals() {
  struct sigaction action {};
  action.sa_handler = stop_on_signal;
  sigemptyset(&action.sa_mask);
  for (const StopSignal& s : stop_signals) {
    struct sigaction previous {};
    // A signal the caller ignores (nohup's SIGHUP) stays ignored.
    if (sigaction(s.number, nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN) continue;
    sigaction(s.number, &action, nullptr);
  }
}

int dispatch_checked(int code) {
  check_standard_output();  // `radchain run ... >/dev/full` is an error, not exit 0
  return code;
}

void add_render_options(CLI::App* cmd, cli::RenderCommand& render) {
  cli::add_sensor(cmd, render.sensor);
  cmd->add_option("--out", render.out, "the data: FITS (sensor parameters in the header), or 32-bit float .tif/.exr");
  cmd->add_option("--png,--preview", render.preview, "display-stretched preview (.png or .tif)");
  cmd->add_option("--scene", render.scene, "ground reflectance map (png, tif, exr; 0..1); default: the built-in test scene");
  cmd->add_option("--target", render.targets, "\"x,y,mag\", \"mag\" or \"limit\" (repeatable; default: one at the limit)");
  cli::add_seed(cmd, render.seed);
  cmd->add_option("--star-seed", render.star_seed, "seed of the star field");
  cli::add_schema_options(cmd, render_option_schema(), render.values);
}

void add_validate_options(CLI::App* cmd, cli::ValidateCommand& validate) {
  cli::add_sensor(cmd, validate.sensor);
  cli::add_seed(cmd, validate.seed);
  cli::add_schema_options(cmd, validate_option_schema(), validate.values);
}

}  // namespace

int main(int argc, char** argv) {
  cli::escape_control_characters_on_terminals();
  CLI::App app{"radchain — end-to-end radiometry of electro-optical sensors"};
  app.require_subcommand(1);
  app.set_version_flag("--version", fmt::format("radchain {} (plugin ABI {})", framework_version, plugin_abi_version),
                       "print the framework version and the plugin ABI, then exit");
  std::vector<std::string> plugin_path;
  app.add_option("--plugin-path", plugin_path, "extra plugin folders (searched first; colon-separated allowed)");

  cli::RunCommand run;
  auto* run_cmd = app.add_subcommand("run", "evaluate one sensor file forward, perform its solves, check [expected]");
  cli::add_sensor(run_cmd, run.sensor);
  cli::add_no_solve(run_cmd, run.sensor.no_solve);
  cli::add_solver(run_cmd, run.sensor.solver);
  run_cmd->add_option("--format", run.format, "text or json")->check(CLI::IsMember({"text", "json"}));

  cli::CatalogueCommand catalogue;
  auto* cat_cmd = app.add_subcommand("catalogue", "run many sensor files: key results vs their [expected] references");
  cat_cmd->add_option("inputs", catalogue.inputs, "sensor files or folders")->required();
  cli::add_sets(cat_cmd, catalogue.sets, "override a key in every file: section.key=value (repeatable)");
  cat_cmd->add_option("--results", catalogue.results, "more results to show per sensor (comma-separated)")->delimiter(',');
  cli::add_output(cat_cmd, catalogue.output, "text (default), csv or json");
  cli::add_no_solve(cat_cmd, catalogue.no_solve);
  cat_cmd->add_flag("--tables", catalogue.tables, "also compute each file's [[table]] entries (e.g. limiting magnitude vs exposure), a row per cell");
  cat_cmd->add_flag("--wide", catalogue.wide,
                    "text: every column (instrument, delta) and whole notes; by default the table fits 160 columns");
  cat_cmd->add_option("--uncertainty", catalogue.uncertainty,
                      "N Monte Carlo samples of each file's [uncertainty]: 5 % and 95 % rows per solved or checked result")
      ->check(CLI::Range(std::size_t{2}, std::size_t{10000000}));
  cli::add_solver(cat_cmd, catalogue.solver);
  cli::add_batch(cat_cmd, catalogue.batch);

  cli::ReportCommand report;
  auto* report_cmd = app.add_subcommand("report", "a static HTML report of sensor files: an index of instruments and checks, a page per sensor with plots");
  report_cmd->add_option("inputs", report.inputs, "sensor files or folders")->required();
  report_cmd->add_option("--out", report.out, "the report's folder (new, or an earlier report's: replaced whole)")->required();
  cli::add_sets(report_cmd, report.sets, "override a key in every file: section.key=value (repeatable)");
  report_cmd->add_flag("--no-budget", report.no_budget, "leave out the sensitivity tornado (the slowest part)");
  cli::add_solver(report_cmd, report.solver);
  cli::add_threads(report_cmd, report.threads, "threads to use (default: all cores; same report for any count)");

  cli::CompareCommand compare;
  auto* cmp_cmd = app.add_subcommand("compare", "two sensor files or saved JSON results side by side, and their input differences");
  cmp_cmd->add_option("a", compare.a, "sensor file or `radchain run --format json` output")->required();
  cmp_cmd->add_option("b", compare.b, "sensor file or `radchain run --format json` output")->required();
  cli::add_sets(cmp_cmd, compare.sets, "override a key in both sensor files (repeatable)");
  cli::add_no_solve(cmp_cmd, compare.no_solve);
  cmp_cmd->add_option("--tolerance", compare.tolerance,
                      "relative tolerance (1e-6, 0.1%): exit 1 when a result moves more (default: report only; "
                      "moves within 1e-9 count as rounding)");
  cli::add_output(cmp_cmd, compare.output, "text (default), csv or json");

  cli::SweepCommand sweep;
  auto* sweep_cmd = app.add_subcommand("sweep", "evaluate a sensor over a grid of parameter values, solves at every point");
  cli::add_sensor(sweep_cmd, sweep.sensor,
                  "an axis section.key=from:to:steps (\"optics.aperture=15 cm:30 cm:16\"), or a fixed value (repeatable)");
  sweep_cmd->add_option("--results", sweep.results, "result columns (comma-separated; default: every result)")->delimiter(',');
  sweep_cmd->add_option("--plot", sweep.plot, "draw a 1-D sweep to this PNG with gnuplot");
  cli::add_output(sweep_cmd, sweep.output, "csv (default), text, json or npy (a NumPy structured array; needs --out)");
  cli::add_batch(sweep_cmd, sweep.batch);
  cli::add_no_solve(sweep_cmd, sweep.sensor.no_solve);
  cli::add_solver(sweep_cmd, sweep.sensor.solver);
  sweep_cmd->add_flag("--allow-large", sweep.allow_large, "run a grid of more than 10^8 points (refused otherwise)");
  sweep_cmd->add_flag("--explain", sweep.explain,
                      "say on stderr how the points were solved (factored over the grid, or per point and why)");

  cli::BudgetCommand budget;
  auto* budget_cmd = app.add_subcommand("budget", "sensitivities: ∂result/∂input and elasticities for every numeric input, ranked (error budget)");
  cli::add_sensor(budget_cmd, budget.sensor);
  budget_cmd->add_option("--results", budget.results, "results to differentiate (comma-separated), e.g. target.magnitude,detector.snr")
      ->delimiter(',')
      ->required();
  budget_cmd->add_option("--plot", budget.plot, "draw a tornado plot of the elasticities to this PNG with gnuplot");
  cli::add_output(budget_cmd, budget.output, "text (default), csv or json");
  cli::add_no_solve(budget_cmd, budget.sensor.no_solve);
  cli::add_solver(budget_cmd, budget.sensor.solver);

  cli::UncertaintyCommand uncertainty;
  auto* uncertainty_cmd = app.add_subcommand("uncertainty", "Monte Carlo propagation of input distributions, beside the linear propagation");
  cli::add_sensor(uncertainty_cmd, uncertainty.sensor);
  uncertainty_cmd->add_option("--vary", uncertainty.vary,
                              "an input's distribution in its units: key=normal(mean, sd) | uniform(lo, hi) | lognormal(mean, sd) | "
                              "triangular(lo, mode, hi) | truncated(<one of these>, lo, hi) (repeatable; adds to or replaces the "
                              "file's [uncertainty])");
  uncertainty_cmd->add_option("--results", uncertainty.results, "results (comma-separated), e.g. target.magnitude")
      ->delimiter(',')
      ->required();
  cli::add_samples(uncertainty_cmd, uncertainty.samples, "Monte Carlo samples (default 1000)");
  uncertainty_cmd->add_option("--plot", uncertainty.plot, "draw each result's histogram with its 5/50/95 % points to this PNG (gnuplot)");
  cli::add_seed(uncertainty_cmd, uncertainty.seed);
  cli::add_threads(uncertainty_cmd, uncertainty.threads, "threads to use (default: all cores; same output for any count)");
  cli::add_output(uncertainty_cmd, uncertainty.output, "text (default), csv or json");
  cli::add_no_solve(uncertainty_cmd, uncertainty.sensor.no_solve);
  cli::add_solver(uncertainty_cmd, uncertainty.sensor.solver);

  cli::MtfCommand mtf;
  auto* mtf_cmd = app.add_subcommand("mtf", "MTF curves of a pushbroom design (objective, detector, system) as CSV and a plot");
  cli::add_sensor(mtf_cmd, mtf.sensor);
  mtf_cmd->add_option("--out", mtf.out, "CSV file (default: standard output)");
  mtf_cmd->add_option("--plot", mtf.plot, "draw the curves to this PNG with gnuplot (one panel, Nyquist marked)");
  mtf_cmd->add_flag("--log", mtf.log, "plot the MTF on a logarithmic axis (1e-3 to 1)");

  cli::RenderCommand render;
  auto* render_cmd = app.add_subcommand("render", "render what the sensor sees: a detector frame (point targets) or an Earth scene (pushbroom)");
  add_render_options(render_cmd, render);

  cli::ValidateCommand validate;
  auto* validate_cmd = app.add_subcommand("validate", "closed-loop checks: render, measure, compare with the model");
  add_validate_options(validate_cmd, validate);

  cli::MergeCommand merge;
  auto* merge_cmd = app.add_subcommand("merge", "join shard files into the output of the unsharded job");
  merge_cmd->add_option("shards", merge.shards, "shard files written with --shard k/n")->required();
  cli::add_output(merge_cmd, merge.output, "the job's format (default), text, csv or json");

  auto* plugins_cmd = app.add_subcommand("plugins", "list the plugins found on the search path");
  std::string describe_name;
  auto* describe_cmd = app.add_subcommand(
      "describe", "a plugin's keys, units, defaults, ranges, results and a TOML example; a kind's plugins; a sensor-file table");
  describe_cmd->add_option("what", describe_name, "plugin name, path to a plugin .so, kind (criterion, ...), sensor, solve, expected, table, render or validate")
      ->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);  // --help, --version
  } catch (const CLI::ParseError& e) {
    std::cerr << "radchain: " << e.what() << " (see radchain --help)\n";
    return static_cast<int>(ExitCode::bad_input);
  }

  stop_cleanly_on_signals();
  try {
    PluginHost::instance().configure(plugin_path);
    if (*run_cmd) return dispatch_checked(cli::run(run));
    if (*cat_cmd) return dispatch_checked(cli::catalogue(catalogue));
    if (*report_cmd) return dispatch_checked(cli::report(report));
    if (*cmp_cmd) return dispatch_checked(cli::compare(compare));
    if (*sweep_cmd) return dispatch_checked(cli::sweep(sweep));
    if (*merge_cmd) return dispatch_checked(cli::merge(merge));
    if (*budget_cmd) return dispatch_checked(cli::budget(budget));
    if (*uncertainty_cmd) return dispatch_checked(cli::uncertainty(uncertainty));
    if (*mtf_cmd) return dispatch_checked(cli::mtf(mtf));
    if (*render_cmd) return dispatch_checked(cli::render(render));
    if (*validate_cmd) return dispatch_checked(cli::validate(validate));
    if (*plugins_cmd) return dispatch_checked(cli::plugins());
    if (*describe_cmd) return dispatch_checked(cli::describe(describe_name));
  } catch (const InputError& error) {
    std::cerr << error.what() << "\n";
    return static_cast<int>(ExitCode::bad_input);
  } catch (const WriteError& error) {
    std::cerr << "radchain: " << error.what() << "\n";
    return 3;
  } catch (const std::exception& error) {
    std::cerr << "radchain: internal error: " << error.what() << "\n";
    return 3;
  } catch (...) {
    // A plugin may throw anything; that must not abort the process.
    std::cerr << "radchain: internal error: an exception that is not a std::exception (thrown by a plugin?)\n";
    return 3;
  }
  return dispatch_checked(0);
}

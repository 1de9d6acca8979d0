// radchain: the command-line host. Subcommands: run, catalogue, compare, sweep, merge, plugins, describe.
// This file only parses the command line (CLI11); the commands are in commands.cpp, the work in the framework.
// Exit codes: 0 ok, 1 a failed check ([expected], a solve, a compare tolerance), 2 bad input (one line on
// stderr), 3 an internal error.
#include "commands.hpp"
#include "render_commands.hpp"
#include "radchain/error.hpp"
#include "radchain/plugin_host.hpp"

#include <CLI/CLI.hpp>

#include <iostream>

namespace {
using namespace radchain;

void add_output(CLI::App* command, cli::Output& output, const std::string& formats) {
  command->add_option("--out", output.out, "write to this file instead of stdout (.csv/.json/.txt also set the format)");
  command->add_option("--format", output.format, formats);
}

void add_batch(CLI::App* command, cli::Batch& batch) {
  command->add_option("--shard", batch.shard, "run part k of n of the job (k/n) and write a shard file for `radchain merge`");
  command->add_option("--shard-order", batch.shard_order, "how points are dealt to shards: block (contiguous) or round-robin");
  command->add_option("--threads", batch.threads, "threads to use (default: all cores)");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"radchain — end-to-end radiometry of electro-optical sensors"};
  app.require_subcommand(1);
  std::vector<std::string> plugin_path;
  app.add_option("--plugin-path", plugin_path, "extra plugin folders (searched first; colon-separated allowed)");

  cli::RunOptions run;
  auto* run_cmd = app.add_subcommand("run", "evaluate one sensor file forward, perform its solves, check [expected]");
  run_cmd->add_option("sensor", run.sensor, "sensor TOML file")->required();
  run_cmd->add_option("--set", run.sets, "override a key: section.key=value (repeatable)");
  run_cmd->add_option("--format", run.format, "text or json")->check(CLI::IsMember({"text", "json"}));

  cli::CatalogueCommand catalogue;
  auto* cat_cmd = app.add_subcommand("catalogue", "run many sensor files: key results vs their [expected] references");
  cat_cmd->add_option("inputs", catalogue.inputs, "sensor files or folders")->required();
  cat_cmd->add_option("--set", catalogue.sets, "override a key in every file: section.key=value (repeatable)");
  cat_cmd->add_option("--results", catalogue.results, "more results to show per sensor (comma-separated)")->delimiter(',');
  add_output(cat_cmd, catalogue.output, "text (default), csv or json");
  add_batch(cat_cmd, catalogue.batch);

  cli::CompareCommand compare;
  auto* cmp_cmd = app.add_subcommand("compare", "two sensor files or saved JSON results side by side, and their input differences");
  cmp_cmd->add_option("a", compare.a, "sensor file or `radchain run --format json` output")->required();
  cmp_cmd->add_option("b", compare.b, "sensor file or `radchain run --format json` output")->required();
  cmp_cmd->add_option("--set", compare.sets, "override a key in both sensor files (repeatable)");
  cmp_cmd->add_option("--tolerance", compare.tolerance, "relative tolerance (1e-6, 0.1%): exit 1 when a result moves more");
  add_output(cmp_cmd, compare.output, "text (default), csv or json");

  cli::SweepCommand sweep;
  auto* sweep_cmd = app.add_subcommand("sweep", "evaluate a sensor over a grid of parameter values, solves at every point");
  sweep_cmd->add_option("sensor", sweep.sensor, "sensor TOML file")->required();
  sweep_cmd->add_option("--set", sweep.sets,
                        "an axis section.key=from:to:steps (\"optics.aperture=15 cm:30 cm:16\"), or a fixed value (repeatable)");
  sweep_cmd->add_option("--results", sweep.results, "result columns (comma-separated; default: every result)")->delimiter(',');
  sweep_cmd->add_option("--plot", sweep.plot, "draw a 1-D sweep to this PNG with gnuplot");
  add_output(sweep_cmd, sweep.output, "csv (default), text or json");
  add_batch(sweep_cmd, sweep.batch);

  cli::MtfCommand mtf;
  auto* mtf_cmd = app.add_subcommand("mtf", "MTF curves of a pushbroom design (objective, detector, system) as CSV and a plot");
  mtf_cmd->add_option("sensor", mtf.sensor, "sensor TOML file with a ccd_line detector and an mtf_match criterion")->required();
  mtf_cmd->add_option("--set", mtf.sets, "override a key: section.key=value (repeatable)");
  mtf_cmd->add_option("--out", mtf.out, "CSV file (default: standard output)");
  mtf_cmd->add_option("--plot", mtf.plot, "draw the curves to this PNG with gnuplot");

  cli::RenderCommand render;
  auto* render_cmd = app.add_subcommand("render", "render what the sensor sees: a detector frame (point targets) or an Earth scene (pushbroom)");
  render_cmd->add_option("sensor", render.sensor, "sensor TOML file")->required();
  render_cmd->add_option("--set", render.sets, "override a key: section.key=value (repeatable)");
  render_cmd->add_option("--out", render.out, "FITS file with the sensor parameters in its header");
  render_cmd->add_option("--png,--preview", render.preview, "display-stretched preview (.png or .tif)");
  render_cmd->add_option("--fits-type", render.fits_type, "auto, float, int16 or int32");
  render_cmd->add_option("--seed", render.seed, "noise seed (same seed, same image)");
  render_cmd->add_option("--no-noise", render.no_noise, "switch terms off: shot,dark,read,saturation,adc or all")->delimiter(',');
  render_cmd->add_option("--width", render.width, "frame width (pixels)");
  render_cmd->add_option("--height", render.height, "frame height (pixels)");
  render_cmd->add_option("--target", render.targets, "\"x,y,mag\", \"mag\" or \"limit\" (repeatable; default: one at the limit)");
  render_cmd->add_option("--stars", render.stars, "number of synthetic field stars");
  render_cmd->add_option("--star-magnitudes", render.star_magnitudes, "bright:faint (default 8:limit+1)");
  render_cmd->add_option("--star-slope", render.star_slope, "d log10 N / dm of the star counts");
  render_cmd->add_option("--star-seed", render.star_seed, "seed of the star field");
  render_cmd->add_option("--focal-length", render.focal_length, "when the sensor has none, e.g. \"45 cm\"");
  render_cmd->add_option("--pixel-pitch", render.pixel_pitch, "when the sensor has none, e.g. \"27 um\"");
  render_cmd->add_option("--psf", render.psf, "pixel, airy or gaussian");
  render_cmd->add_option("--psf-wavelength", render.psf_wavelength, "Airy wavelength, e.g. \"0.6 um\"");
  render_cmd->add_option("--psf-fwhm", render.psf_fwhm, "Gaussian FWHM, e.g. \"20 um\"");
  render_cmd->add_option("--obscuration", render.obscuration, "central obscuration (linear ratio) of the Airy PSF");
  render_cmd->add_option("--sky", render.sky, "sky background per pixel and frame, e.g. \"40 e-\"");
  render_cmd->add_option("--oversampling", render.oversampling, "PSF phases per pixel");
  render_cmd->add_option("--offset", render.offset_dn, "ADC pedestal (DN)");
  render_cmd->add_option("--scene", render.scene, "ground reflectance map (png, tif, exr; 0..1); default: the built-in test scene");
  render_cmd->add_option("--scene-sampling", render.scene_sampling, "ground size of one map pixel, e.g. \"1.25 m\"");
  render_cmd->add_option("--gsd", render.gsd, "output ground sampling (default: the design's ground element)");
  render_cmd->add_option("--optics-mtf", render.optics_mtf, "diffraction, eq7 or none");
  render_cmd->add_option("--wavelength", render.wavelength, "MTF wavelength (default: the mtf_match criterion's)");
  render_cmd->add_flag("--no-detector-mtf", render.no_detector_mtf, "leave out the element MTF (eq. 8)");
  render_cmd->add_option("--adc-bits", render.adc_bits, "ADC of an Earth scene (ccd_line has none of its own)");
  render_cmd->add_option("--stretch", render.stretch, "preview stretch: asinh or linear");
  render_cmd->add_option("--upscale", render.upscale, "preview upscale (nearest neighbour)");

  cli::ValidateCommand validate;
  auto* validate_cmd = app.add_subcommand("validate", "closed-loop checks: render, measure, compare with the model");
  validate_cmd->add_option("sensor", validate.sensor, "sensor TOML file")->required();
  validate_cmd->add_option("--set", validate.sets, "override a key: section.key=value (repeatable)");
  validate_cmd->add_option("--trials", validate.trials, "detection Monte-Carlo frames");
  validate_cmd->add_option("--size", validate.size, "flat-field size (pixels)");
  validate_cmd->add_option("--seed", validate.seed, "noise seed");
  validate_cmd->add_option("--threshold", validate.threshold_sigma, "detector threshold in noise units");
  validate_cmd->add_option("--max-z", validate.max_z, "binomial standard errors allowed");
  validate_cmd->add_option("--focal-length", validate.focal_length, "when the sensor has none");
  validate_cmd->add_option("--pixel-pitch", validate.pixel_pitch, "when the sensor has none");
  validate_cmd->add_option("--psf", validate.psf, "pixel, airy or gaussian");
  validate_cmd->add_option("--psf-wavelength", validate.psf_wavelength, "Airy wavelength");
  validate_cmd->add_option("--psf-fwhm", validate.psf_fwhm, "Gaussian FWHM");

  cli::MergeCommand merge;
  auto* merge_cmd = app.add_subcommand("merge", "join shard files into the output of the unsharded job");
  merge_cmd->add_option("shards", merge.shards, "shard files written with --shard k/n")->required();
  add_output(merge_cmd, merge.output, "the job's format (default), text, csv or json");

  auto* plugins_cmd = app.add_subcommand("plugins", "list the plugins found on the search path");
  std::string describe_name;
  auto* describe_cmd = app.add_subcommand("describe", "show a plugin's keys, units, defaults, ranges and a TOML example");
  describe_cmd->add_option("plugin", describe_name, "plugin name (or path to a plugin .so)")->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);  // --help
  } catch (const CLI::ParseError& e) {
    std::cerr << "radchain: " << e.what() << " (see radchain --help)\n";
    return static_cast<int>(ExitCode::bad_input);
  }

  try {
    PluginHost::instance().configure(plugin_path);
    if (*run_cmd) return cli::run(run);
    if (*cat_cmd) return cli::catalogue(catalogue);
    if (*cmp_cmd) return cli::compare(compare);
    if (*sweep_cmd) return cli::sweep(sweep);
    if (*merge_cmd) return cli::merge(merge);
    if (*mtf_cmd) return cli::mtf(mtf);
    if (*render_cmd) return cli::render_command(render);
    if (*validate_cmd) return cli::validate_command(validate);
    if (*plugins_cmd) return cli::plugins();
    if (*describe_cmd) return cli::describe(describe_name);
  } catch (const InputError& error) {
    std::cerr << error.what() << "\n";
    return static_cast<int>(ExitCode::bad_input);
  } catch (const std::exception& error) {
    std::cerr << "radchain: internal error: " << error.what() << "\n";
    return 3;
  }
  return 0;
}

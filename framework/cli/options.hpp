#pragma once
// The option structs of the `radchain` subcommands, and the CLI11 declarations that several of them share
// (declared once here, in options.cpp). main.cpp parses into the structs; the executable's commands and the
// imaging module (imaging_module.hpp) read them, so the structs hold plain std types only.
#include "option_schema.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace radchain::cli {

// The sensor file and what is changed in it: every command that loads one sensor.
struct SensorArgs {
  std::string sensor;              // the sensor TOML file
  std::vector<std::string> sets;   // --set section.key=value (repeatable)
  bool no_solve = false;           // --no-solve: forward only, the [[solve]] entries skipped
  std::string solver = "auto";     // --solver auto|root (run, sweep)
};

struct Output {
  std::string out;     // --out file ("" = stdout)
  std::string format;  // --format ("" = from --out's extension, else the command's default)
};

struct Batch {
  std::string shard;                 // --shard k/n
  std::string shard_order = "block"; // --shard-order block|round-robin
  std::size_t threads = 0;           // --threads (0 = all cores)
};

struct RunCommand {
  SensorArgs sensor;
  std::string format = "text";
};

struct CatalogueCommand {
  std::vector<std::string> inputs;
  std::vector<std::string> sets;
  bool no_solve = false;
  bool tables = false;
  bool wide = false;
  std::size_t uncertainty = 0;
  std::string solver = "auto";
  std::vector<std::string> results;
  Output output;
  Batch batch;
};

struct CompareCommand {
  std::string a, b;
  std::vector<std::string> sets;
  bool no_solve = false;
  std::string tolerance;
  Output output;
};

struct SweepCommand {
  SensorArgs sensor;
  std::vector<std::string> results;
  std::string plot;
  Output output;
  Batch batch;
  bool allow_large = false;  // --allow-large: a grid above SweepOptions::large_points
  bool explain = false;      // --explain: Sweep::method() on stderr
};

// radchain budget SENSOR --results a,b [--set k=v] [--format text|csv|json] [--out F] [--plot tornado.png]:
// ∂result/∂input and the elasticities for every numeric input (radchain/batch/budget.hpp), ranked; a tornado plot.
struct BudgetCommand {
  SensorArgs sensor;
  std::vector<std::string> results;  // --results (comma-separated; required)
  std::string plot;                  // --plot tornado.png
  Output output;
};
int budget(const BudgetCommand& options);  // commands/budget.cpp

// radchain uncertainty SENSOR --vary "key=normal(m, sd)" ... --results a,b [--samples N] [--seed S] [--threads N]:
// Monte Carlo propagation (radchain/batch/uncertainty.hpp) beside the linear one from the budget's derivatives.
struct UncertaintyCommand {
  SensorArgs sensor;
  std::vector<std::string> vary;     // --vary key=dist(args) (repeatable)
  std::vector<std::string> results;  // --results (comma-separated; required)
  std::size_t samples = 1000;        // --samples
  std::uint64_t seed = 1;            // --seed
  std::size_t threads = 0;           // --threads (0 = all cores; the output does not depend on it)
  std::string plot;                  // --plot: histograms of the results to this PNG
  Output output;
};
int uncertainty(const UncertaintyCommand& options);  // commands/uncertainty.cpp

struct MergeCommand {
  std::vector<std::string> shards;
  Output output;
};

// MTF curves of a pushbroom design (Kolobrodov 1996 Fig. 2) as CSV (stdout or --out) and optionally a PNG.
struct MtfCommand {
  SensorArgs sensor;
  std::string out;
  std::string plot;
  bool log = false;  // --log: the plot's MTF axis logarithmic (10^-3 to 1)
};

// radchain render SENSOR [options]: a point-target sensor (ccd_frame) renders a detector frame, a pushbroom
// sensor (ccd_line) an Earth scene. Writes the data as FITS/TIFF/EXR (--out) and/or a display-stretched
// preview (--png/--preview .png/.tif); prints what it rendered. The values with units, limits or fixed choices
// are in `values`, checked against render_option_schema() (radchain/command_options.hpp).
struct RenderCommand {
  SensorArgs sensor;
  std::string out;                  // --out frame.fits | frame.tif | frame.exr
  std::string preview;              // --png, --preview frame.png | frame.tif
  std::string scene;                // --scene map.png (reflectance 0..1; default: the built-in test scene)
  std::vector<std::string> targets; // --target "x,y,mag" (pixels, row 0 at the top) or "mag" (centre); mag may be
                                    // "limit"; none given: one at the limiting magnitude in the centre
  std::uint64_t seed = 1;           // --seed (noise)
  std::uint64_t star_seed = 1;      // --star-seed
  OptionValues values;
};

// radchain validate SENSOR [options]: the closed-loop checks at full size. Point-target sensors: detection
// Monte Carlo at the limiting magnitude and a flat field; pushbroom sensors: slanted-edge MTF and flat fields.
// Prints measured vs predicted; exit 1 when a check fails. Values: validate_option_schema().
struct ValidateCommand {
  SensorArgs sensor;
  std::uint64_t seed = 1;  // --seed
  OptionValues values;
};

// The shared declarations (options.cpp).
inline constexpr const char* set_help = "override a key: section.key=value (repeatable)";
void add_sets(CLI::App* command, std::vector<std::string>& sets, const std::string& help = set_help);
void add_sensor(CLI::App* command, SensorArgs& sensor, const std::string& help = set_help);  // SENSOR and --set
void add_no_solve(CLI::App* command, bool& no_solve);
void add_solver(CLI::App* command, std::string& solver);
void add_output(CLI::App* command, Output& output, const std::string& formats);
void add_batch(CLI::App* command, Batch& batch);
// More threads than this is a typo, not a machine (each thread loads a chain of its own).
inline constexpr std::size_t max_threads = 4096;
void add_threads(CLI::App* command, std::size_t& threads, const std::string& description);
void add_samples(CLI::App* command, std::size_t& samples, const std::string& description);
void add_seed(CLI::App* command, std::uint64_t& seed);

}  // namespace radchain::cli

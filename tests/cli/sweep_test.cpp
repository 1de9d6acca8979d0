// `radchain sweep`: range parsing with units, the grid, equality with `run --set` at every point, bad ranges.
#include "cli_helpers.hpp"
#include "radchain/error.hpp"
#include "radchain/batch/sweep.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <sstream>

namespace {
using namespace radchain;
using namespace radchain::test;

TEST(SweepAxis, RangeWithUnits) {
  Chain chain = load_sensor(sbv_file);
  const SweepAxis axis = parse_sweep_axis(chain, "optics.aperture", "15 cm:30 cm:16");
  EXPECT_EQ(axis.steps, 16u);
  EXPECT_EQ(axis.unit, "cm");
  EXPECT_DOUBLE_EQ(axis.value_si(0), 0.15);
  EXPECT_DOUBLE_EQ(axis.value_si(15), 0.30);
  EXPECT_EQ(axis.value(0), 15.0);
  EXPECT_EQ(axis.value(5), 20.0);  // evenly spaced in the unit written: exactly 20
  EXPECT_EQ(axis.value(15), 30.0);
  // The value `--set optics.aperture="20 cm"` gives, to the bit.
  Chain set = load_sensor(sbv_file, {{"optics.aperture", "20 cm"}});
  EXPECT_EQ(axis.value_si(5), set.parameter("optics.aperture").value());
}

TEST(SweepAxis, MixedUnitsAndPlainNumbers) {
  Chain chain = load_sensor(sbv_file);
  const SweepAxis mixed = parse_sweep_axis(chain, "optics.aperture", "150 mm:0.3 m:4");
  EXPECT_EQ(mixed.unit, "mm");
  EXPECT_DOUBLE_EQ(mixed.value(3), 300.0);
  EXPECT_DOUBLE_EQ(mixed.value_si(1), 0.2);
  const SweepAxis qe = parse_sweep_axis(chain, "detector.qe", "0.2:0.8:7");
  EXPECT_EQ(qe.unit, "");
  EXPECT_DOUBLE_EQ(qe.value_si(3), 0.5);
  const SweepAxis one = parse_sweep_axis(chain, "detector.qe", "0.5:0.5:1");
  EXPECT_EQ(one.steps, 1u);
  EXPECT_EQ(one.value_si(0), 0.5);
}

TEST(SweepAxis, BadRangesAreInputErrors) {
  Chain chain = load_sensor(sbv_file);
  for (const char* range : {"15 cm:30 cm", "15:30:16", "15 cm:30 kg:16", "15 cm:30 cm:0", "15 cm:30 cm:2.5",
                            "cm:30 cm:4", "-5 cm:30 cm:4", "15 cm:30 cm:16:2"})
    EXPECT_THROW(parse_sweep_axis(chain, "optics.aperture", range), InputError) << range;
  EXPECT_THROW(parse_sweep_axis(chain, "optics.apperture", "1 cm:2 cm:3"), InputError);
  EXPECT_THROW(parse_sweep_axis(chain, "detector.quantisation", "1:2:3"), InputError);  // not a number
  EXPECT_THROW(parse_sweep_axis(chain, "target.magnitude", "10:12:3"), InputError);     // solved
  EXPECT_THROW(parse_sweep_axis(chain, "detector.adc_bits", "8:16:4"), InputError);     // 10.67 bits
  EXPECT_NO_THROW(parse_sweep_axis(chain, "detector.adc_bits", "8:16:5"));
}

TEST(SweepAxis, AGainIsSweptInDnPerElectron) {
  // Steps even in e-/DN would be uneven in K: the reciprocal spelling a file accepts is refused for an axis, with why.
  Chain chain = load_sensor(source_dir + "/sensors/rubin-lsst-r-m5.toml");
  try {
    parse_sweep_axis(chain, "detector.gain", "1 e-/DN:2 e-/DN:3");
    ADD_FAILURE() << "a sweep of the gain in e-/DN was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("stated in DN/e-"), std::string::npos) << e.what();
  }
  const SweepAxis axis = parse_sweep_axis(chain, "detector.gain", "0.5 ADU/e-:1 DN/e-:3");
  EXPECT_EQ(axis.value_si(1), 0.75);
}

TEST(Sweep, GridOrderLastAxisFastest) {
  SweepOptions options;
  options.sensor_file = sbv_file;
  options.axes = {{"optics.aperture", "15 cm:30 cm:4"}, {"detector.integration_time", "0.5 s:1 s:3"}};
  options.results = {"target.magnitude"};
  const Sweep sweep(options);
  EXPECT_EQ(sweep.points(), 12u);
  EXPECT_EQ(sweep.indices(0), (std::vector<std::size_t>{0, 0}));
  EXPECT_EQ(sweep.indices(2), (std::vector<std::size_t>{0, 2}));
  EXPECT_EQ(sweep.indices(3), (std::vector<std::size_t>{1, 0}));
  EXPECT_EQ(sweep.indices(11), (std::vector<std::size_t>{3, 2}));
  EXPECT_EQ(sweep.layout().columns,
            (std::vector<std::string>{"optics.aperture_cm", "detector.integration_time_s", "target.magnitude"}));
}

TEST(Sweep, EveryPointEqualsRunWithSet) {
  SweepOptions options;
  options.sensor_file = sbv_file;
  options.axes = {{"optics.aperture", "15 cm:30 cm:4"}, {"detector.band_min", "0.3 um:0.5 um:3"}};  // one spectral axis
  options.results = {"target.magnitude", "detector.signal_electrons", "detector.snr"};
  const Sweep sweep(options);
  SweepWorker worker(sweep);
  std::vector<double> out(sweep.columns());
  // Points out of order: a point must not depend on the ones before it.
  for (std::size_t point : {7u, 0u, 11u, 3u, 4u}) {
    ASSERT_TRUE(worker.evaluate(point, out.data())) << worker.failure();
    const auto index = sweep.indices(point);
    const std::string aperture = fmt::format("{:.17g} cm", sweep.axes()[0].value(index[0]));
    const std::string band = fmt::format("{:.17g} um", sweep.axes()[1].value(index[1]));
    Chain chain = load_sensor(sbv_file, {{"optics.aperture", aperture}, {"detector.band_min", band}});
    const Report report = chain.run();
    EXPECT_EQ(out[2], report.value("target.magnitude").value()) << point;
    EXPECT_EQ(out[3], report.value("detector.signal_electrons").value()) << point;
    EXPECT_EQ(out[4], report.value("detector.snr").value()) << point;
  }
}

// Sweeps over non-spectral axes run in lanes (Chain::solve_lanes, Dekker in lockstep); `run` solves one point with
// TOMS 748. Both bracket the root to 2^-47 relative, so they agree to ~1e-14; every other result follows from the
// root. Checked on every bundled sensor with one [[solve]], including a target without a lane form (the sphere,
// evaluated lane by lane), in groups that are full, short (13 points = 8 + 5) and out of order.
TEST(Sweep, LanesAgreeWithRunAtEveryPoint) {
  struct Case {
    std::string file, axis, range;
    std::vector<std::string> results;
  };
  const std::string sensors = std::string(RADCHAIN_SOURCE_DIR) + "/sensors/";
  const std::vector<Case> cases = {
      {sbv_file, "optics.aperture", "10 cm:40 cm:13", {"target.magnitude", "detector.snr", "detector.shot_noise"}},
      {sensors + "pan2010-auxiliary-sensor.toml", "detector.integration_time", "0.1 s:2 s:13", {"target.magnitude", "detector.noise_electrons"}},
      {sensors + "sbv-smallest-sphere.toml", "target.range", "500 km:2000 km:13", {"target.diameter", "detector.signal_electrons"}},
  };
  for (const Case& c : cases) {
    SweepOptions options;
    options.sensor_file = c.file;
    options.axes = {{c.axis, c.range}};
    options.results = c.results;
    const Sweep sweep(options);
    SweepWorker worker(sweep);
    const std::size_t n = sweep.columns();
    const std::vector<std::size_t> groups[] = {{0, 1, 2, 3, 4, 5, 6, 7}, {12, 8, 10, 9, 11}};
    for (const auto& group : groups) {
      std::vector<double> out(group.size() * n);
      std::vector<char> ok(group.size());
      worker.evaluate_group(group.data(), group.size(), out.data(), ok.data());
      for (std::size_t k = 0; k < group.size(); ++k) {
        ASSERT_TRUE(ok[k]) << c.file << " point " << group[k] << ": " << worker.failure_of(k);
        const std::string value = fmt::format("{:.17g} {}", sweep.axes()[0].value(group[k]), sweep.axes()[0].unit);
        Chain chain = load_sensor(c.file, {{c.axis, value}});
        const Report report = chain.run();
        EXPECT_EQ(out[k * n], sweep.axes()[0].value(group[k]));
        for (std::size_t r = 0; r < c.results.size(); ++r) {
          const double expected = report.value(c.results[r]).value() * chain.results().info(*chain.results().find(c.results[r])).display_factor;
          EXPECT_NEAR(out[k * n + 1 + r], expected, 1e-12 * std::abs(expected)) << c.file << " point " << group[k] << " " << c.results[r];
        }
      }
    }
  }
}

// A lane whose bracket holds no root fails alone: the others are solved, its solved column is nan, and the message
// names the point.
TEST(Sweep, ALaneWithoutARootFailsAlone) {
  SweepOptions options;
  options.sensor_file = std::string(RADCHAIN_SOURCE_DIR) + "/sensors/sbv-smallest-sphere.toml";
  options.axes = {{"target.range", "1000 km:1e9 km:8"}};  // far ranges need a sphere larger than the bracket's 100 m
  options.results = {"target.diameter"};
  const Sweep sweep(options);
  SweepWorker worker(sweep);
  const std::size_t group[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  std::vector<double> out(8 * sweep.columns());
  std::vector<char> ok(8);
  worker.evaluate_group(group, 8, out.data(), ok.data());
  EXPECT_TRUE(ok[0]);
  EXPECT_NEAR(out[1], 3.387, 0.001);  // cm: the 1000 km sphere of the sensor file
  EXPECT_FALSE(ok[7]);
  EXPECT_TRUE(std::isnan(out[7 * 2 + 1]));
  EXPECT_NE(worker.failure_of(7).find("at target.range = 1e+09 km: the solve for target.diameter failed: criterion "
                                      "\"detection\" has the same sign at both ends of the bracket"),
            std::string::npos)
      << worker.failure_of(7);
}

TEST(SweepCli, CsvOfAOneAxisSweep) {
  Scratch scratch;
  const CliResult r = run_cli(scratch, "sweep '" + sbv_file +
                                           "' --set 'optics.aperture=15 cm:30 cm:16' --results target.magnitude,detector.snr");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  std::istringstream lines(r.out);
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line, "optics.aperture_cm,target.magnitude,detector.snr");
  std::vector<std::string> rows;
  while (std::getline(lines, line)) rows.push_back(line);
  ASSERT_EQ(rows.size(), 16u);
  EXPECT_EQ(rows.front().substr(0, 15), "15,15.55650451,");  // Pan 2010 Table 2: 15.55 at 15 cm
  EXPECT_EQ(rows.back().substr(0, 3), "30,");
}

TEST(SweepCli, BadRangeIsOneLineAndExit2) {
  Scratch scratch;
  for (const char* range : {"15 cm:30 cm"}) {  // (the other bad ranges: SweepAxis.BadRangesAreInputErrors)
    const CliResult r = run_cli(scratch, "sweep '" + sbv_file + "' --set 'optics.aperture=" + range + "'");
    EXPECT_EQ(r.exit_code, 2) << range;
    EXPECT_EQ(r.out, "") << range;
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("--set optics.aperture: ", 0), 0u) << r.err;
  }
  const CliResult no_axis = run_cli(scratch, "sweep '" + sbv_file + "' --set 'optics.aperture=20 cm'");
  EXPECT_EQ(no_axis.exit_code, 2);
  EXPECT_EQ(count_lines(no_axis.err), 1u) << no_axis.err;
}

TEST(SweepCli, FailedSolveExitsWith1AndLeavesNan) {
  Scratch scratch;
  const CliResult r = run_cli(scratch, "sweep '" + sbv_file + "' --set 'optics.aperture=0.01 mm:15 cm:2' --results target.magnitude");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.out, "optics.aperture_mm,target.magnitude\n0.01,nan\n150,15.55650451\n");
  EXPECT_NE(r.err.find("at optics.aperture = 0.01 mm: the solve for target.magnitude failed"), std::string::npos) << r.err;
}

// A point the chain refuses (a look past the horizon, in the lanes or the scalar path) stops the sweep: one line
// naming the point and the stage, exit 2, no --out file.
TEST(SweepCli, PointPastTheHorizonIsOneLineAndExit2) {
  Scratch scratch;
  const std::string wv2 = source_dir + "/sensors/worldview-2-pan-20deg.toml";
  const std::string out = (scratch / "roll.csv").string();
  const CliResult r = run_cli(scratch, "sweep '" + wv2 + "' --set 'platform.roll=0 deg:80 deg:5' --out '" + out + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("at platform.roll = 80 deg, platform (plugin \"earth_orbit\"): a line of sight 80 deg off nadir "
                       "misses the Earth"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

// The width and height of a PNG (its IHDR chunk), or {0, 0} when the file is not a PNG.
std::pair<unsigned, unsigned> png_size(const fs::path& png) {
  const std::string head = read_text(png).substr(0, 24);
  if (head.size() < 24 || head.substr(0, 8) != std::string("\x89PNG\r\n\x1a\n", 8)) return {0, 0};
  auto be32 = [&](std::size_t at) {
    unsigned v = 0;
    for (std::size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(head[at + k]);
    return v;
  };
  return {be32(16), be32(20)};
}

// One axis: a panel per series; two: a heat map per series (900 × 560 each, with contours); three: refused.
// Points without a value (a failed solve) are drawn too: marked on the curve's panel, grey on the map.
TEST(SweepCli, PlotsCurvesOfOneAxisAndHeatMapsOfTwo) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot is not installed";
  Scratch scratch;
  const fs::path png = scratch / "sweep.png", map = scratch / "map.png";
  const CliResult r = run_cli(scratch, "sweep '" + sbv_file + "' --set 'optics.aperture=15 cm:30 cm:16' --out '" +
                                           (scratch / "sweep.csv").string() + "' --plot '" + png.string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(png_size(png), std::make_pair(900u, 380u));
  // the first aperture's limit is fainter than the bracket allows: a failed solve, exit 1, still plotted
  const CliResult failed = run_cli(scratch, "sweep '" + sbv_file + "' --set 'optics.aperture=0.001 cm:30 cm:8' "
                                                "--results target.magnitude,detector.noise_electrons --out /dev/null --plot '" +
                                                png.string() + "'");
  EXPECT_EQ(failed.exit_code, 1) << failed.err;
  EXPECT_EQ(png_size(png), std::make_pair(900u, 700u)) << failed.err;
  const CliResult two_axes = run_cli(scratch, "sweep '" + sbv_file + "' --set 'optics.aperture=0.001 cm:30 cm:6' "
                                                  "--set 'detector.integration_time=0.1 s:1 s:5' --results target.magnitude,detector.snr "
                                                  "--out /dev/null --plot '" + map.string() + "'");
  EXPECT_EQ(two_axes.exit_code, 1) << two_axes.err;
  EXPECT_EQ(png_size(map), std::make_pair(900u, 1180u)) << two_axes.err;
  const CliResult three_axes = run_cli(scratch, "sweep '" + sbv_file + "' --set 'optics.aperture=15 cm:30 cm:2' "
                                                    "--set 'detector.qe=0.2:0.3:2' --set 'detector.integration_time=1 s:2 s:2' --plot '" +
                                                    png.string() + "'");
  EXPECT_EQ(three_axes.exit_code, 2);
  EXPECT_NE(three_axes.err.find("one axis (curves) or two (heat maps); this sweep has 3 axes"), std::string::npos) << three_axes.err;
}

// A sweep evaluates only what its columns need, says so with --explain, and gives the same SNR as a full sweep.
TEST(Sweep, ExplainNamesTheStagesNoAskedResultNeeds) {
  Scratch scratch;
  const std::string s2 = source_dir + "/sensors/sentinel-2a-msi-b4.toml";
  const std::string grid = "sweep '" + s2 + "' --set 'target.reflectance=0.05:0.6:12' --format csv ";
  const CliResult focused = run_cli(scratch, grid + "--results detector.snr --explain");
  EXPECT_EQ(focused.exit_code, 0) << focused.err;
  EXPECT_EQ(focused.err, "radchain sweep: per point: no [[solve]], and the grid's 12 points are too few for factoring to "
                         "pay; not evaluated (no asked result or solve needs them): criteria.gsd, criteria.iq\n");
  const CliResult everything = run_cli(scratch, grid + "--results detector.snr,criteria.iq.niirs --explain");
  EXPECT_EQ(everything.err, "radchain sweep: per point: no [[solve]], and a result other than the detector's signal, "
                            "noise or SNR is read (criteria.iq.niirs); not evaluated (no asked result or solve needs "
                            "them): criteria.gsd\n");
  // The SNR column is the same text either way.
  auto column = [](const std::string& csv, std::size_t index) {
    std::istringstream in(csv);
    std::string line, out;
    while (std::getline(in, line)) {
      std::istringstream cells(line);
      std::string cell;
      for (std::size_t i = 0; i <= index && std::getline(cells, cell, ','); ++i) {}
      out += cell + "\n";
    }
    return out;
  };
  EXPECT_EQ(column(focused.out, 1), column(everything.out, 1));
}

}  // namespace

// Regression: a sensor name with a newline and a gnuplot system() line ran that command when a plot
// was drawn. Every outside text now reaches gnuplot as an argument, never as script text.
namespace {
std::string hostile_name(const radchain::test::fs::path& marker) {
  return "name = \"x'\\nsystem(\\\"touch " + marker.string() + "\\\")\\nprint \\\"@ARG1\\\" `touch " + marker.string() +
         "`\"";
}
}  // namespace

TEST(SweepCli, PlotTextsAreDataNotScript) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot is not installed";
  Scratch scratch;
  const fs::path marker = scratch / "injected";
  const fs::path sensor = scratch / "hostile.toml";
  write_text(sensor, sbv_with("name = \"MSX SBV (Pan 2010, Table 1)\"", hostile_name(marker)));
  const fs::path png = scratch / "plot\n system(\"touch x\").png";  // a path is data too
  const CliResult r = run_cli(scratch, "sweep '" + sensor.string() + "' --set 'optics.aperture=15 cm:30 cm:3' --plot '" +
                                           png.string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(marker)) << "the sensor name ran a command through gnuplot";
  EXPECT_EQ(read_text(png).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
}

TEST(MtfCli, PlotTextsAreDataNotScript) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot is not installed";
  Scratch scratch;
  const fs::path marker = scratch / "injected";
  const fs::path sensor = scratch / "hostile.toml";
  std::string text = read_text(source_dir + "/sensors/kolobrodov-1996-ccd151-computed.toml");
  const std::string name = "name = \"Kolobrodov 1996 CCD151 camera (computed from spectra)\"";
  ASSERT_NE(text.find(name), std::string::npos);
  write_text(sensor, text.replace(text.find(name), name.size(), hostile_name(marker)));
  const fs::path png = scratch / "mtf.png";
  const CliResult r = run_cli(scratch, "mtf '" + sensor.string() + "' --out '" + (scratch / "mtf.csv").string() +
                                           "' --plot '" + png.string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(marker)) << "the sensor name ran a command through gnuplot";
  EXPECT_EQ(read_text(png).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
}

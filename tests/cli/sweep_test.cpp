// `radchain sweep`: range parsing with units, the grid, equality with `run --set` at every point, bad ranges.
#include "cli_helpers.hpp"
#include "radchain/error.hpp"
#include "radchain/sweep.hpp"

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

TEST(SweepCli, PlotIsAPng) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot is not installed";
  Scratch scratch;
  const fs::path png = scratch / "sweep.png";
  const CliResult r = run_cli(scratch, "sweep '" + sbv_file + "' --set 'optics.aperture=15 cm:30 cm:16' --out '" +
                                           (scratch / "sweep.csv").string() + "' --plot '" + png.string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_text(png).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  const CliResult two_axes = run_cli(scratch, "sweep '" + sbv_file +
                                                  "' --set 'optics.aperture=15 cm:30 cm:2' --set 'detector.qe=0.2:0.3:2' --plot '" +
                                                  png.string() + "'");
  EXPECT_EQ(two_axes.exit_code, 2);
}

}  // namespace

// `radchain catalogue`: rows per sensor, pass/fail logic, exit codes (0 ok, 1 a failed check, 2 bad input) and
// the three formats. References: sensors/msx-sbv.toml (Pan 2010 Table 2: 15.55 ± 0.05; the chain gives 15.5565).
#include "cli_helpers.hpp"
#include "radchain/batch/catalogue.hpp"
#include "radchain/error.hpp"
#include "radchain/sensor_file.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sstream>

namespace {
using namespace radchain;
using namespace radchain::test;

enum { sensor, instrument, result, kind, computed, reference, tolerance, unit, delta, delta_pct, check, note };

TEST(Catalogue, RowsOfTheSbvSensor) {
  Chain chain = load_sensor(sbv_file);
  const Report report = chain.run();
  const auto rows = catalogue_rows(sbv_file, report, {"detector.snr", "no.such_result"});
  ASSERT_EQ(rows.size(), 3u);  // the [expected] check (it covers the solve), then the two extra results
  EXPECT_EQ(rows[0][sensor], "msx-sbv");
  EXPECT_EQ(rows[0][result], "target.magnitude");
  // To the last bit (the text table shows 6 digits; CSV, JSON and shards carry the double).
  EXPECT_EQ(std::stod(rows[0][computed]), report.value("target.magnitude").value());
  EXPECT_EQ(rows[0][reference], "15.55");
  EXPECT_EQ(rows[0][kind], "paper");       // the file says: kind = "paper"
  EXPECT_EQ(rows[0][tolerance], "0.05");   // the deviation the check allows
  EXPECT_EQ(rows[0][unit], "");
  EXPECT_EQ(rows[0][check], "ok");
  EXPECT_EQ(rows[0][note], "Pan 2010 Table 2 (design spec 15.5)");
  // delta = 15.5565 - 15.55 in the reference's unit (none), and in percent of the reference.
  EXPECT_NEAR(std::stod(rows[0][delta]), report.value("target.magnitude").value() - 15.55, 1e-6);
  EXPECT_NEAR(std::stod(rows[0][delta_pct]), 100 * (report.value("target.magnitude").value() - 15.55) / 15.55, 1e-3);
  EXPECT_EQ(rows[1][result], "detector.snr");
  EXPECT_EQ(std::stod(rows[1][computed]), report.value("detector.snr").value());
  EXPECT_EQ(rows[1][check], "");
  EXPECT_EQ(rows[2][note], "not computed by this sensor");
}

TEST(Catalogue, FailingExpectationExitsWith1) {
  Scratch scratch;
  write_text(scratch / "good.toml", read_text(sbv_file));
  write_text(scratch / "wrong.toml", sbv_with("value = 15.55, tolerance = 0.05", "value = 14.0, tolerance = 0.05"));
  const CliResult r = run_cli(scratch, "catalogue '" + scratch.path().string() + "'");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_NE(r.out.find("good "), std::string::npos) << r.out;
  // The failing row names the sensor, its computed value, the reference and FAIL.
  std::istringstream lines(r.out);
  std::string line, wrong;
  while (std::getline(lines, line))
    if (line.rfind("wrong ", 0) == 0) wrong = line;
  EXPECT_NE(wrong.find("15.5565"), std::string::npos) << wrong;
  EXPECT_NE(wrong.find("14"), std::string::npos) << wrong;
  EXPECT_NE(wrong.find("FAIL"), std::string::npos) << wrong;
  EXPECT_NE(r.out.find("2 sensor files, 2 checks (2 paper): 1 FAILED"), std::string::npos) << r.out;
}

TEST(Catalogue, AllPassingExitsWith0) {
  Scratch scratch;
  const CliResult r = run_cli(scratch, "catalogue '" + sbv_file + "' --format csv");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const std::string header = "sensor,instrument,result,kind,computed,reference,tolerance,unit,delta,delta_pct,check,note\n";
  EXPECT_EQ(r.out.substr(0, header.size()), header);
  const std::string start = "msx-sbv,\"MSX SBV (Pan 2010, Table 1)\",target.magnitude,paper,15.5565";
  EXPECT_EQ(r.out.substr(header.size(), start.size()), start);  // 15.55650450641426: every digit
  EXPECT_NE(r.out.find(",15.55,0.05,,+0.006505,+0.0418,ok,Pan 2010 Table 2 (design spec 15.5)\n"), std::string::npos) << r.out;
  EXPECT_EQ(count_lines(r.out), 2u);
}

TEST(Catalogue, BadInputFileExitsWith2AndTheOthersStillRun) {
  Scratch scratch;
  write_text(scratch / "a_good.toml", read_text(sbv_file));
  write_text(scratch / "b_bad.toml", sbv_with("aperture = \"15 cm\"", "aperture = \"15 kg\""));
  write_text(scratch / "c_wrong.toml", sbv_with("value = 15.55, tolerance = 0.05", "value = 14.0, tolerance = 0.05"));
  const CliResult r = run_cli(scratch, "catalogue '" + scratch.path().string() + "' --format json");
  EXPECT_EQ(r.exit_code, 2);
  // One line on stderr: the file's message.
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("b_bad.toml:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("expected a length"), std::string::npos) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["rows"].size(), 3u);
  EXPECT_EQ(j["rows"][0]["check"], "ok");
  EXPECT_NEAR(j["rows"][0]["computed"].get<double>(), 15.5565045, 1e-7);
  EXPECT_EQ(j["rows"][1]["sensor"], "b_bad");
  EXPECT_EQ(j["rows"][1]["check"], "ERROR");
  EXPECT_TRUE(j["rows"][1]["computed"].is_null());
  EXPECT_EQ(j["rows"][2]["check"], "FAIL");
  EXPECT_EQ(j["exit_code"], 2);
  EXPECT_EQ(j["summary"], "3 sensor files, 2 checks (2 paper): 1 FAILED, 1 file with bad input");
}

// The tolerance column is the deviation the check allows: the larger of the absolute and the relative tolerance,
// in the row's unit; a file that does not say what its reference is shows "unstated".
TEST(Catalogue, ToleranceAndKindColumns) {
  Chain relative = load_sensor_text(
      sbv_with("tolerance = 0.05, kind = \"paper\",", "rel_tolerance = 0.01,"), sbv_file);
  const auto rows = catalogue_rows(sbv_file, relative.run());
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(rows[0][kind], "unstated");
  EXPECT_NEAR(std::stod(rows[0][tolerance]), 0.01 * 15.55, 1e-12);
  Chain both = load_sensor_text(sbv_with("tolerance = 0.05,", "tolerance = 0.2, rel_tolerance = 0.01,"), sbv_file);
  EXPECT_NEAR(std::stod(catalogue_rows(sbv_file, both.run())[0][tolerance]), 0.2, 1e-12);
}

// Every check of a bundled file says what its reference is (the catalogue's summary counts them by kind); the
// validation cases are peers' computations.
TEST(Catalogue, EveryBundledCheckSaysWhatItIs) {
  std::size_t checks = 0;
  for (const char* folder : {"sensors", "examples", "validation"})
    for (const auto& file : catalogue_files({source_dir + "/" + folder})) {
      const Chain chain = load_sensor(file);
      for (const auto& e : chain.expected) {
        ++checks;
        EXPECT_NE(e.kind, "") << file << ": " << e.result;
        if (std::string(folder) == "validation") {
          EXPECT_EQ(e.kind, "peer") << file << ": " << e.result;
        }
      }
    }
  EXPECT_GT(checks, 150u);
}

// The text table a person reads fits 160 columns (the file stands for the instrument, the percentage for the delta,
// the note is cut with "…"); --wide shows every column and whole notes, as CSV and JSON have them.
TEST(Catalogue, TheTextTableFits160ColumnsAndWideShowsEverything) {
  Scratch scratch;
  const std::string folder = source_dir + "/sensors";
  const CliResult text = run_cli(scratch, "catalogue '" + folder + "'");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  std::istringstream lines(text.out);
  std::string line;
  std::size_t longest = 0, cut = 0;
  while (std::getline(lines, line)) {
    std::size_t columns = 0;
    for (unsigned char c : line) columns += (c & 0xC0) != 0x80 ? 1 : 0;
    longest = std::max(longest, columns);
    cut += line.find("…") != std::string::npos ? 1 : 0;
  }
  EXPECT_LE(longest, 160u);
  EXPECT_GT(cut, 0u);
  EXPECT_EQ(text.out.substr(0, text.out.find('\n')).find("instrument"), std::string::npos);  // not a column
  const CliResult wide = run_cli(scratch, "catalogue --wide '" + folder + "'");
  ASSERT_EQ(wide.exit_code, 0) << wide.err;
  EXPECT_NE(wide.out.find("instrument"), std::string::npos);
  EXPECT_NE(wide.out.find("MSX SBV (Pan 2010, Table 1)"), std::string::npos);
  EXPECT_NE(wide.out.find("Pan 2010 Table 2 (design spec 15.5)"), std::string::npos);
  EXPECT_GT(wide.out.find('\n'), 160u);  // its header line, padded to every column's width
  // An erratum says so in words: the value the source's own inputs give is the one checked.
  EXPECT_NE(wide.out.find("erratum: the source's own inputs give 65.04 mm (checked), not the printed value"),
            std::string::npos) << wide.out;
}

// One plugin folder reached twice (RADCHAIN_PLUGIN_PATH relative, the build tree's absolute) is one folder: no
// plugin is reported as shadowed by itself.
TEST(Catalogue, APluginFolderNamedTwiceShadowsNothing) {
  Scratch scratch;
  const CliResult r = run_shell(scratch, "cd '" RADCHAIN_BINARY_DIR "' && RADCHAIN_PLUGIN_PATH=plugins '" RADCHAIN_CLI
                                         "' catalogue '" + sbv_file + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
}

TEST(Catalogue, FailedSolveIsAFailedCheck) {
  Scratch scratch;
  write_text(scratch / "no_root.toml", sbv_with("bracket = [5, 25]", "bracket = [5, 6]"));
  const CliResult r = run_cli(scratch, "catalogue '" + (scratch / "no_root.toml").string() + "' --format csv");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.out.find("[[solve]] failed"), std::string::npos) << r.out;
}

TEST(Catalogue, MissingPathIsBadInput) {
  Scratch scratch;
  const CliResult r = run_cli(scratch, "catalogue '" + (scratch / "nothing_here").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("no such file or folder"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

TEST(Catalogue, SetAppliesToEveryFile) {
  Scratch scratch;
  const CliResult r = run_cli(scratch, "catalogue '" + sbv_file + "' --set 'optics.aperture=\"30 cm\"' --format csv");
  // Pan 2010 Table 2: "about 17" at 30 cm; the check against 15.55 fails.
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.out.find("target.magnitude,paper,17.06"), std::string::npos) << r.out;
}

TEST(Catalogue, FilesOfAFolderAreSorted) {
  Scratch scratch;
  write_text(scratch / "b.toml", read_text(sbv_file));
  write_text(scratch / "a.toml", read_text(sbv_file));
  write_text(scratch / "notes.txt", "not a sensor");
  fs::create_directories(scratch / "peer");
  write_text(scratch / "peer" / "c.toml", read_text(sbv_file));
  const auto files = catalogue_files({scratch.path().string()});
  ASSERT_EQ(files.size(), 3u);  // sub-folders too (validation/<peer>/)
  EXPECT_EQ(fs::path(files[0]).filename(), "a.toml");
  EXPECT_EQ(fs::path(files[1]).filename(), "b.toml");
  EXPECT_EQ(fs::path(files[2]), scratch / "peer" / "c.toml");
  fs::create_directories(scratch / "empty");
  EXPECT_THROW(catalogue_files({(scratch / "empty").string()}), InputError);
}

}  // namespace

namespace {
using namespace radchain;
using namespace radchain::test;

// --tables: each [[table]] cell is a row without a check (the summary counts the same checks); without it the
// tables are not computed at all. The cells equal `radchain run`'s table (Rubin r: m5 at 6 exposures × 3 results).
TEST(Catalogue, TablesAreRowsOnlyWhenAskedFor) {
  Scratch scratch;
  const std::string rubin_r = source_dir + "/sensors/rubin-lsst-r-m5.toml";
  const CliResult plain = run_cli(scratch, "catalogue --format csv '" + rubin_r + "'");
  const CliResult tables = run_cli(scratch, "catalogue --tables --format csv '" + rubin_r + "'");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  ASSERT_EQ(tables.exit_code, 0) << tables.err;
  EXPECT_EQ(plain.out.find(" @ "), std::string::npos);
  EXPECT_EQ(count_lines(tables.out), count_lines(plain.out) + 6 * 3);
  const std::string cell = "target.magnitude @ detector.integration_time = 300 s,,";  // a table cell has no kind
  ASSERT_NE(tables.out.find(cell), std::string::npos) << tables.out;

  const CliResult run = run_cli(scratch, "run --format json '" + rubin_r + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto json = nlohmann::json::parse(run.out);
  const auto& table = json["tables"][0];
  ASSERT_EQ(table["values"].back(), "300 s");
  const double m5_300 = table["rows_si"].back()[0].get<double>();
  std::istringstream row(tables.out.substr(tables.out.find(cell) + cell.size()));
  double computed_cell = 0;
  row >> computed_cell;
  EXPECT_NEAR(computed_cell, m5_300, 1e-4);  // the cell prints 6 significant digits
}

}  // namespace

// `radchain report`: the static HTML report (radchain/batch/html_report.hpp, docs/report.md). Its numbers against
// the commands that compute them on their own (`run`, `budget`, `mtf`), its plots' curves, exit codes, and a folder
// written whole. The pages in a real browser: tests/browser/check_report.py.
#include "cli_helpers.hpp"
#include "radchain/batch/svg_plot.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <regex>
#include <set>
#include <sstream>

namespace {
using namespace radchain;
using namespace radchain::test;
using Json = nlohmann::json;

Json load_json(const fs::path& path) { return Json::parse(read_text(path)); }

// The report of `inputs` into scratch/name; the exit code is checked by the caller.
CliResult report(const Scratch& scratch, const std::string& inputs, const std::string& name = "report",
                 const std::string& more = "") {
  return run_cli(scratch, "report " + inputs + " --out '" + (scratch / name).string() + "' " + more);
}

const Json& result_named(const Json& sensor, const std::string& name) {
  for (const auto& r : sensor["results"])
    if (r["name"] == name) return r;
  throw std::runtime_error("no result " + name);
}

double run_value(const Json& run, const std::string& name) {
  for (const auto& r : run["results"])
    if (r["name"] == name) return r["value_si"].get<double>();
  throw std::runtime_error("run has no result " + name);
}

// The numbers of a CSV column (after the '#' comment lines and the header).
std::vector<double> csv_column(const std::string& csv, const std::string& column) {
  std::istringstream lines(csv);
  std::string line;
  std::vector<std::string> header;
  std::vector<double> values;
  std::size_t index = SIZE_MAX;
  while (std::getline(lines, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream cellstream(line);
    for (std::string cell; std::getline(cellstream, cell, ',');) cells.push_back(cell);
    if (index == SIZE_MAX) {
      for (std::size_t i = 0; i < cells.size(); ++i)
        if (cells[i] == column) index = i;
      if (index == SIZE_MAX) throw std::runtime_error("no column " + column + " in: " + line);
      continue;
    }
    values.push_back(std::stod(cells.at(index)));
  }
  return values;
}

TEST(Report, EveryBundledSensorHasAPageAndTheIndexListsIt) {
  Scratch scratch;
  const CliResult r = report(scratch, "'" + source_dir + "/sensors'");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(r.err, "");
  const fs::path out = scratch / "report";
  const Json j = load_json(out / "report.json");
  const std::string index = read_text(out / "index.html");
  std::set<std::string> stems;
  for (const auto& entry : fs::directory_iterator(source_dir + "/sensors"))
    if (entry.path().extension() == ".toml") stems.insert(entry.path().stem().string());
  ASSERT_EQ(j["sensors"].size(), stems.size());
  std::size_t checks = 0;
  for (const auto& s : j["sensors"]) {
    const std::string stem = s["stem"];
    EXPECT_TRUE(stems.count(stem)) << stem;
    EXPECT_EQ(s["page"], "sensors/" + stem + ".html");
    EXPECT_EQ(s["status"], "ok") << stem;
    EXPECT_FALSE(s["name"].get<std::string>().empty()) << stem;
    EXPECT_NE(index.find("href=\"sensors/" + stem + ".html\""), std::string::npos) << stem;
    const std::string page = read_text(out / s["page"].get<std::string>());
    EXPECT_NE(page.find("<h2 id=\"inputs\">"), std::string::npos) << stem;
    EXPECT_NE(page.find("<h2 id=\"results\">"), std::string::npos) << stem;
    // Self-contained: no script, style or image from anywhere else.
    EXPECT_EQ(page.find("<script src"), std::string::npos) << stem;
    EXPECT_EQ(page.find("<link rel=\"stylesheet\""), std::string::npos) << stem;
    EXPECT_EQ(page.find("src=\"http"), std::string::npos) << stem;
    checks += s["checks"].size();
  }
  // The index's summary is the catalogue's.
  const CliResult catalogue = run_cli(scratch, "catalogue '" + source_dir + "/sensors'");
  const std::string summary = j["summary"];
  EXPECT_NE(catalogue.out.find(summary), std::string::npos) << summary << "\n" << catalogue.out;
  EXPECT_NE(index.find(summary), std::string::npos);
  EXPECT_GT(checks, stems.size());
  // Nothing left beside the report.
  for (const auto& entry : fs::directory_iterator(scratch.path()))
    EXPECT_EQ(entry.path().filename().string().find(".report.partial"), std::string::npos) << entry.path();
}

TEST(Report, NumbersAreTheRunsOwn) {
  Scratch scratch;
  const CliResult r = report(scratch, "'" + sbv_file + "'");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const Json j = load_json(scratch / "report" / "report.json");
  const Json& s = j["sensors"][0];
  const CliResult run = run_cli(scratch, "run '" + sbv_file + "' --format json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const Json ran = Json::parse(run.out);
  // Every result to the last bit: the SNR at the limiting magnitude (5: the criterion binds) and the magnitude.
  ASSERT_EQ(s["results"].size(), ran["results"].size());
  for (std::size_t i = 0; i < ran["results"].size(); ++i) {
    EXPECT_EQ(s["results"][i]["name"], ran["results"][i]["name"]);
    EXPECT_EQ(s["results"][i]["value_si"], ran["results"][i]["value_si"]) << ran["results"][i]["name"];
  }
  const double snr = result_named(s, "detector.snr")["value"];
  EXPECT_EQ(snr, run_value(ran, "detector.snr"));
  EXPECT_NEAR(snr, 5.0, 1e-9);
  EXPECT_NEAR(result_named(s, "target.magnitude")["value"].get<double>(), 15.5565, 5e-5);  // Pan 2010 Table 2: 15.55
  // The page shows them to 6 digits, each naming its place in report.json.
  const std::string page = read_text(scratch / "report" / "sensors" / "msx-sbv.html");
  std::size_t snr_index = 0;
  for (std::size_t i = 0; i < s["results"].size(); ++i)
    if (s["results"][i]["name"] == "detector.snr") snr_index = i;
  EXPECT_NE(page.find(fmt::format("data-json=\"/sensors/0/results/{}/value\" data-sort=\"{}\">5</td>", snr_index, snr)), std::string::npos);
  EXPECT_NE(page.find(">15.5565</td>"), std::string::npos);
  // The check as the catalogue states it: paper, 15.55 ± 0.05, ok, with its source.
  ASSERT_EQ(s["checks"].size(), 1u);
  EXPECT_EQ(s["checks"][0]["kind"], "paper");
  EXPECT_EQ(s["checks"][0]["reference"], 15.55);
  EXPECT_EQ(s["checks"][0]["tolerance"], 0.05);
  EXPECT_EQ(s["checks"][0]["status"], "ok");
  EXPECT_EQ(s["checks"][0]["source"], "Pan 2010 Table 2 (design spec 15.5)");
  // The solve and what binds; the inputs as written, defaults marked.
  ASSERT_EQ(s["solves"].size(), 1u);
  EXPECT_EQ(s["solves"][0]["binding"], "detection");
  bool aperture = false, defaulted = false;
  for (const auto& in : s["inputs"]) {
    if (in["section"] == "optics" && in["key"] == "aperture") {
      aperture = true;
      EXPECT_EQ(in["written"], "15 cm");
      EXPECT_EQ(in["unit"], "m");
      EXPECT_EQ(in["value_si"], 0.15);
      EXPECT_EQ(in["provenance"], "line 22");
      EXPECT_FALSE(in["default"].get<bool>());
    }
    if (in["default"].get<bool>()) defaulted = true;
  }
  EXPECT_TRUE(aperture);
  EXPECT_TRUE(defaulted);
  EXPECT_EQ(s["reference"], "Pan et al. 2010, Acta Optica Sinica 30(10):2935, Tables 1-2");
}

TEST(Report, SnrSweepFallsWithMagnitudeAndExposureSweepRises) {
  Scratch scratch;
  const CliResult r = report(scratch, "'" + sbv_file + "'", "report", "--no-budget");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const Json j = load_json(scratch / "report" / "report.json");
  const Json& plots = j["sensors"][0]["plots"];
  // SNR vs magnitude: 41 points about the limiting magnitude, falling (fainter, less signal), 5 at the root.
  const Json& snr = plots["snr"]["series"][0];
  ASSERT_EQ(snr["x"].size(), 41u);
  EXPECT_EQ(plots["snr"]["parameter"], "target.magnitude");
  for (std::size_t i = 1; i < 41; ++i) {
    EXPECT_GT(snr["x"][i].get<double>(), snr["x"][i - 1].get<double>());
    EXPECT_LT(snr["y"][i].get<double>(), snr["y"][i - 1].get<double>()) << i;
  }
  EXPECT_NEAR(snr["x"][20].get<double>(), 15.5565, 5e-5);  // the middle point is the solved magnitude
  EXPECT_NEAR(snr["y"][20].get<double>(), 5.0, 1e-6);
  // The page draws all 41 points in one path.
  const std::string page = read_text(scratch / "report" / "sensors" / "msx-sbv.html");
  EXPECT_NE(page.find("<path class=\"curve\" data-series=\"detector.snr\" data-points=\"41\""), std::string::npos);
  // Limiting magnitude vs exposure (no [[table]] in the file: a sweep of 20 exposures): fainter with longer exposures.
  const Json& exposure = plots["exposure"]["series"][0];
  EXPECT_EQ(plots["exposure"]["source"], "sweep");
  ASSERT_EQ(exposure["x"].size(), 20u);
  for (std::size_t i = 1; i < 20; ++i) EXPECT_GT(exposure["y"][i].get<double>(), exposure["y"][i - 1].get<double>()) << i;
  EXPECT_EQ(plots.count("tornado"), 0u);  // --no-budget
}

TEST(Report, ExposurePlotIsTheFilesTable) {
  Scratch scratch;
  const std::string file = source_dir + "/sensors/rubin-lsst-r-m5.toml";
  const CliResult r = report(scratch, "'" + file + "'", "report", "--no-budget");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const Json j = load_json(scratch / "report" / "report.json");
  const Json& s = j["sensors"][0];
  const Json& exposure = s["plots"]["exposure"];
  EXPECT_EQ(exposure["source"], "table");
  const Json& table = s["tables"][0];
  ASSERT_EQ(exposure["series"][0]["x"].size(), table["rows"].size());
  for (std::size_t i = 0; i < table["rows"].size(); ++i) {
    EXPECT_EQ(exposure["series"][0]["x"][i], table["values_si"][i]);
    EXPECT_EQ(exposure["series"][0]["y"][i], table["rows"][i][0]);  // target.magnitude, the table's first column
  }
}

TEST(Report, TornadoIsTheBudgetCommands) {
  Scratch scratch;
  const CliResult r = report(scratch, "'" + sbv_file + "'");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const Json j = load_json(scratch / "report" / "report.json");
  const Json& tornado = j["sensors"][0]["plots"]["tornado"][0];
  EXPECT_EQ(tornado["result"], "target.magnitude");
  const CliResult budget = run_cli(scratch, "budget '" + sbv_file + "' --results target.magnitude --format csv");
  ASSERT_EQ(budget.exit_code, 0) << budget.err;
  const std::vector<double> elasticities = csv_column(budget.out, "elasticity");
  ASSERT_FALSE(tornado["bars"].empty());
  // The bars are the budget's ranked entries without the zero ones, largest first, the same numbers.
  std::vector<double> nonzero;
  for (double e : elasticities)
    if (e != 0) nonzero.push_back(e);
  ASSERT_GE(nonzero.size(), tornado["bars"].size());
  for (std::size_t i = 0; i < tornado["bars"].size(); ++i)
    EXPECT_NEAR(tornado["bars"][i]["elasticity"].get<double>(), nonzero[i], 1e-9 * std::abs(nonzero[i])) << i;
  const std::string page = read_text(scratch / "report" / "sensors" / "msx-sbv.html");
  EXPECT_NE(page.find("class=\"plot tornado\""), std::string::npos);
}

TEST(Report, MtfIsTheMtfCommands) {
  Scratch scratch;
  for (const auto& [stem, column] : {std::pair{"worldview-2-pan", "system"}, std::pair{"kolobrodov-1996-ccd151-computed", "system_eq10"}}) {
    const std::string file = source_dir + "/sensors/" + stem + ".toml";
    const CliResult r = report(scratch, "'" + file + "'", stem, "--no-budget");
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    const Json j = load_json(scratch / stem / "report.json");
    const Json& mtf = j["sensors"][0]["plots"]["mtf"];
    const Json& system = mtf["series"].back();
    EXPECT_EQ(system["label"].get<std::string>().substr(0, 6), "system") << stem;
    const CliResult cli = run_cli(scratch, "mtf '" + file + "'");
    ASSERT_EQ(cli.exit_code, 0) << cli.err;
    const std::vector<double> expected = csv_column(cli.out, column), frequency = csv_column(cli.out, "frequency_mm-1");
    ASSERT_EQ(system["y"].size(), expected.size()) << stem;
    for (std::size_t i = 0; i < expected.size(); ++i) {
      EXPECT_NEAR(system["y"][i].get<double>(), expected[i], 5e-7) << stem << " " << i;  // the CSV has 6 decimals
      EXPECT_NEAR(system["x"][i].get<double>(), frequency[i], 1e-5 * frequency[i] + 1e-12) << stem << " " << i;
      if (i > 0 && frequency[i] * 2 < frequency.back()) {
        EXPECT_LE(system["y"][i].get<double>(), system["y"][i - 1].get<double>() + 1e-12);
      }
    }
    // The page draws it with every point.
    const std::string page = read_text(scratch / stem / "sensors" / (std::string(stem) + ".html"));
    EXPECT_NE(page.find(fmt::format("data-points=\"{}\"", expected.size())), std::string::npos) << stem;
  }
}

TEST(Report, FailingCheckIsShownWithItsReasonAndExits1) {
  Scratch scratch;
  fs::create_directories(scratch / "in");
  write_text(scratch / "in" / "good.toml", read_text(sbv_file));
  write_text(scratch / "in" / "wrong.toml", sbv_with("value = 15.55, tolerance = 0.05", "value = 14.0, tolerance = 0.05"));
  const CliResult r = report(scratch, "'" + (scratch / "in").string() + "'", "report", "--no-budget");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_NE(r.out.find("2 sensor files, 2 checks (2 paper): 1 FAILED"), std::string::npos) << r.out;
  const Json j = load_json(scratch / "report" / "report.json");
  EXPECT_EQ(j["sensors"][0]["status"], "ok");
  EXPECT_EQ(j["sensors"][1]["status"], "FAIL");
  EXPECT_EQ(j["sensors"][1]["checks"][0]["status"], "FAIL");
  EXPECT_EQ(j["sensors"][1]["checks"][0]["reference"], 14.0);
  const std::string page = read_text(scratch / "report" / "sensors" / "wrong.html");
  EXPECT_NE(page.find("<td class=\"status FAIL\" data-sort=\"FAIL\">FAIL</td>"), std::string::npos);
  EXPECT_NE(read_text(scratch / "report" / "index.html").find("<span class=\"badge FAIL\" id=\"status\">FAIL</span>"), std::string::npos);
}

TEST(Report, BadFileIsOneLocatedLineAndExits2) {
  Scratch scratch;
  fs::create_directories(scratch / "in");
  write_text(scratch / "in" / "good.toml", read_text(sbv_file));
  write_text(scratch / "in" / "bad.toml", sbv_with("aperture = \"15 cm\"", "aperture = \"15 kg\""));
  const CliResult r = report(scratch, "'" + (scratch / "in").string() + "'", "report", "--no-budget");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("bad.toml:22:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("aperture = \"15 kg\""), std::string::npos) << r.err;
  // The report is written, the bad file's page says why.
  const Json j = load_json(scratch / "report" / "report.json");
  EXPECT_EQ(j["sensors"][0]["status"], "ERROR");
  EXPECT_EQ(j["sensors"][0]["error"].get<std::string>() + "\n", r.err);
  EXPECT_NE(read_text(scratch / "report" / "sensors" / "bad.html").find("expected a length"), std::string::npos);

  // No such input: one line, nothing written.
  const CliResult missing = report(scratch, "'" + (scratch / "nope.toml").string() + "'", "missing");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(count_lines(missing.err), 1u) << missing.err;
  EXPECT_NE(missing.err.find("nope.toml: catalogue: no such file or folder"), std::string::npos) << missing.err;
  EXPECT_FALSE(fs::exists(scratch / "missing"));
}

TEST(Report, FolderIsWrittenWholeAndNeverOverAnInput) {
  Scratch scratch;
  fs::create_directories(scratch / "in");
  write_text(scratch / "in" / "sbv.toml", read_text(sbv_file));
  const std::string in = "'" + (scratch / "in").string() + "'";
  // --out onto the input folder, or onto the input file: refused, nothing touched.
  CliResult r = run_cli(scratch, "report " + in + " --out " + in + " --no-budget");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--out"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("inputs"), std::string::npos) << r.err;
  r = run_cli(scratch, "report " + in + " --out '" + (scratch / "in" / "sbv.toml").string() + "' --no-budget");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(read_text(scratch / "in" / "sbv.toml"), read_text(sbv_file));
  // A folder that is not a report: refused, its files kept.
  fs::create_directories(scratch / "mine");
  write_text(scratch / "mine" / "notes.txt", "keep me");
  r = report(scratch, in, "mine", "--no-budget");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("not an earlier radchain report"), std::string::npos) << r.err;
  EXPECT_EQ(read_text(scratch / "mine" / "notes.txt"), "keep me");
  // An earlier report is replaced whole: a file it had that the new one has not is gone.
  r = report(scratch, in, "report", "--no-budget");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  write_text(scratch / "report" / "stale.html", "old");
  r = report(scratch, in, "report", "--no-budget --set 'optics.aperture=20 cm'");
  ASSERT_EQ(r.exit_code, 1) << r.out << r.err;  // a larger aperture sees fainter: the [expected] 15.55 fails
  EXPECT_FALSE(fs::exists(scratch / "report" / "stale.html"));
  EXPECT_EQ(load_json(scratch / "report" / "report.json")["overrides"][0], "optics.aperture=20 cm");
  for (const auto& entry : fs::directory_iterator(scratch.path()))
    EXPECT_EQ(entry.path().filename().string().find(".partial-"), std::string::npos) << entry.path();
}

TEST(SvgPlot, TicksAreRoundAndTextIsEscaped) {
  EXPECT_EQ(svg::linear_ticks(0, 1), (std::vector<double>{0, 0.2, 0.4, 0.6, 0.8, 1.0}));
  EXPECT_EQ(svg::linear_ticks(10.5, 20.5), (std::vector<double>{12, 14, 16, 18, 20}));
  EXPECT_EQ(svg::log_ticks(1e-3, 10), (std::vector<double>{1e-3, 1e-2, 1e-1, 1, 10}));
  EXPECT_EQ(svg::log_ticks(1e-20, 1).size(), 7u);  // every third decade when there are many
  // Curves differ in colour and in dash for the first 24.
  std::set<std::pair<std::string, std::string>> styles;
  for (std::size_t i = 0; i < 24; ++i) styles.emplace(svg::series_colour(i), svg::series_dash(i));
  EXPECT_EQ(styles.size(), 24u);
  svg::LinePlot plot;
  plot.id = "p";
  plot.x = {"x <&> \"quoted\"", true};
  plot.y = {"y", false};
  plot.series.push_back({"a<b", {1, 10, 100, 1000}, {1, NAN, 3, 4}});
  const std::string out = svg::render_line_plot(plot);
  EXPECT_NE(out.find("x &lt;&amp;&gt; &quot;quoted&quot;"), std::string::npos);
  EXPECT_NE(out.find("data-series=\"a&lt;b\" data-points=\"3\""), std::string::npos);
  EXPECT_NE(out.find("class=\"failed\""), std::string::npos);  // the point without a value is marked, not dropped
  EXPECT_NE(out.find("no value at this point"), std::string::npos);
}

}  // namespace

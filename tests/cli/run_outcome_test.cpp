// A run's outcome as a user sees it: every criterion counts (a saturated pixel, a NIIRS below its requirement fail
// the run unless the file marks the criterion informational), physically suspect results are located warnings in
// text and JSON, `compare --tolerance` judges a margin on its own scale, and `budget` runs on every bundled file.
#include "cli_helpers.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>

namespace {
using namespace radchain::test;
using nlohmann::json;

const std::string sentinel_file = source_dir + "/sensors/sentinel-2a-msi-b4.toml";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) return "# replacement target not found: " + from + "\n[[[";
  return text.replace(at, from.size(), to);
}

// The file without its [expected] table (a full well of 10 e- also moves the quantisation term, hence m_lim; a
// look off nadir moves the swath).
std::string without_expected(const std::string& text) { return text.substr(0, text.find("\n[expected]") + 1); }

// "[detector]\nintegration_time = \"0.00147895… s\"": the time to the last digit.
std::string fmt_time(double seconds) {
  char text[64];
  std::snprintf(text, sizeof text, "%.17g", seconds);
  return std::string("[detector]\nintegration_time = \"") + text + " s\"";
}

const json* criterion(const json& report, const std::string& section) {
  for (const auto& c : report["criteria"])
    if (c["section"] == section) return &c;
  return nullptr;
}

double result(const json& report, const std::string& name) {
  for (const auto& r : report["results"])
    if (r["name"] == name) return r["value_si"].get<double>();
  ADD_FAILURE() << "no result " << name;
  return NAN;
}

// A full well of 10 e-: at the limiting magnitude the one pixel Pan's model puts the image in holds far more (the
// closed form: the SNR = 5 signal alone is ≥ 25 e-). The SNR of a clipped pixel is not valid: the run fails.
TEST(RunOutcome, ASaturatedPixelFailsTheRunWithoutACriterion) {
  Scratch scratch;
  const fs::path file = scratch / "full-well.toml";
  write_text(file, without_expected(sbv_with("full_well = \"1e5 e-\"", "full_well = \"10 e-\"")));
  const CliResult text = run_cli(scratch, "run '" + file.string() + "'");
  EXPECT_EQ(text.exit_code, 1) << text.out << text.err;
  EXPECT_NE(text.out.find("FAIL detector"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("saturates"), std::string::npos) << text.out;

  const CliResult as_json = run_cli(scratch, "run '" + file.string() + "' --format json");
  EXPECT_EQ(as_json.exit_code, 1);
  const json report = json::parse(as_json.out);
  EXPECT_FALSE(report["passed"].get<bool>());
  const json* detector = criterion(report, "detector");
  ASSERT_NE(detector, nullptr) << as_json.out;
  EXPECT_FALSE((*detector)["passed"].get<bool>());
  // The fill the check reads: the pixel's charge over the well, > 2.5 (≥ 25 e- of signal alone in 10 e-).
  EXPECT_GT(result(report, "detector.peak_pixel_fill"), 2.5);
  EXPECT_NEAR(result(report, "detector.peak_pixel_fill"), result(report, "detector.peak_pixel_electrons") / 10.0, 1e-12);

  const CliResult catalogue = run_cli(scratch, "catalogue '" + file.string() + "'");
  EXPECT_EQ(catalogue.exit_code, 1) << catalogue.out;
  EXPECT_NE(catalogue.out.find("detector.peak_pixel_fill"), std::string::npos) << catalogue.out;
  // the solve, the pixel
  EXPECT_NE(catalogue.out.find("2 checks (1 solve, 1 criterion): 1 FAILED"), std::string::npos) << catalogue.out;

  // The file's own sensors/msx-sbv.toml: nothing saturates, the run passes.
  EXPECT_EQ(run_cli(scratch, "run '" + sbv_file + "'").exit_code, 0);
}

// The same saturation judged by an `unsaturated` criterion: it fails the run; marked informational, it is reported
// ("info") and the run passes.
TEST(RunOutcome, AnInformationalCriterionIsReportedAndDoesNotFail) {
  Scratch scratch;
  const std::string base = without_expected(sbv_with("full_well = \"1e5 e-\"", "full_well = \"10 e-\""));
  const fs::path judged = scratch / "judged.toml", informational = scratch / "informational.toml";
  write_text(judged, base + "\n[criteria.unsaturated]\nplugin = \"unsaturated\"\n");
  write_text(informational, base + "\n[criteria.unsaturated]\nplugin = \"unsaturated\"\ninformational = true\n");
  const CliResult failed = run_cli(scratch, "run '" + judged.string() + "'");
  EXPECT_EQ(failed.exit_code, 1) << failed.out << failed.err;
  EXPECT_NE(failed.out.find("FAIL criteria.unsaturated"), std::string::npos) << failed.out;
  const CliResult reported = run_cli(scratch, "run '" + informational.string() + "' --format json");
  EXPECT_EQ(reported.exit_code, 0) << reported.out << reported.err;
  const json report = json::parse(reported.out);
  const json* c = criterion(report, "criteria.unsaturated");
  ASSERT_NE(c, nullptr);
  EXPECT_FALSE((*c)["passed"].get<bool>());
  EXPECT_TRUE((*c)["informational"].get<bool>());
  EXPECT_LT((*c)["margin"].get<double>(), 0.0);
  EXPECT_TRUE(report["passed"].get<bool>());
}

// A NIIRS below its requirement fails the run; the bundled Sentinel-2 file marks its nominal threshold
// informational and passes. Its margin is NIIRS/required − 1 of the GIQE's NIIRS.
TEST(RunOutcome, ANiirsBelowItsRequirementFails) {
  Scratch scratch;
  const fs::path file = scratch / "s2-niirs.toml";
  write_text(file, replaced(replaced(read_text(sentinel_file), "informational = true", ""), "niirs = 1 ", "niirs = 6 "));
  const CliResult r = run_cli(scratch, "run '" + file.string() + "' --format json");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const json report = json::parse(r.out);
  const json* c = criterion(report, "criteria.iq");
  ASSERT_NE(c, nullptr);
  EXPECT_FALSE((*c)["passed"].get<bool>());
  EXPECT_NEAR((*c)["margin"].get<double>(), result(report, "criteria.iq.niirs") / 6.0 - 1.0, 1e-12);
  EXPECT_NE((*c)["reason"].get<std::string>().find("NIIRS / NIIRS_required"), std::string::npos);
  EXPECT_EQ(run_cli(scratch, "run '" + sentinel_file + "'").exit_code, 0);
}

// Warnings: located lines in text and in JSON warnings[]. A GIQE NIIRS outside the rating scale 0-9 (Landsat-8
// TIRS's 99 m GSD gives −2.4); an integration time longer than the line time, whose excess is counted as smear; lines
// farther apart than the along-track GSD.
TEST(RunOutcome, PhysicallySuspectResultsAreLocatedWarnings) {
  Scratch scratch;
  const CliResult tirs = run_cli(scratch, "run '" + source_dir + "/sensors/landsat-8-tirs-b10.toml' --format json");
  EXPECT_EQ(tirs.exit_code, 0) << tirs.err;
  const json tirs_report = json::parse(tirs.out);
  ASSERT_EQ(tirs_report["warnings"].size(), 1u) << tirs.out;
  const std::string niirs_warning = tirs_report["warnings"][0];
  EXPECT_NE(niirs_warning.find("landsat-8-tirs-b10.toml:"), std::string::npos) << niirs_warning;
  EXPECT_NE(niirs_warning.find("outside the rating scale 0-9"), std::string::npos) << niirs_warning;
  const CliResult tirs_text = run_cli(scratch, "run '" + source_dir + "/sensors/landsat-8-tirs-b10.toml'");
  EXPECT_NE(tirs_text.out.find("warning: " + niirs_warning), std::string::npos) << tirs_text.out;

  // Sentinel-2's line time is 1.479 ms; integrating 2.4 of them smears 1.4 pixels along track (the scene pixel, 39 %
  // full at one line time, stays below its capacity).
  const fs::path smeared = scratch / "s2-smear.toml";
  write_text(smeared, replaced(read_text(sentinel_file), "[detector]", "[detector]\nintegration_time = \"3.55 ms\""));
  const CliResult smear = run_cli(scratch, "run '" + smeared.string() + "' --format json");
  EXPECT_EQ(smear.exit_code, 0) << smear.err;
  const json smear_report = json::parse(smear.out);
  const json base = json::parse(run_cli(scratch, "run '" + sentinel_file + "' --format json").out);
  EXPECT_TRUE(base["warnings"].empty()) << base["warnings"].dump();
  ASSERT_EQ(smear_report["warnings"].size(), 1u) << smear.out;
  EXPECT_NE(smear_report["warnings"][0].get<std::string>().find("line times"), std::string::npos);
  const double line_time = result(base, "criteria.gsd.line_time");
  const double pixels = 3.55e-3 / line_time - 1;
  EXPECT_NEAR(result(smear_report, "criteria.iq.smear_length"), pixels * 7.5e-6, 1e-12);
  EXPECT_EQ(result(base, "criteria.iq.smear_length"), 0.0);
  EXPECT_LT(result(smear_report, "criteria.iq.rer"), result(base, "criteria.iq.rer"));

  const fs::path sparse = scratch / "s2-sparse.toml";
  write_text(sparse, replaced(read_text(sentinel_file), "direction = \"nadir\"", "direction = \"nadir\"\nalong_track_sampling = \"20 m\""));
  const CliResult gaps = run_cli(scratch, "run '" + sparse.string() + "' --format json");
  EXPECT_EQ(gaps.exit_code, 0) << gaps.err;
  const json gaps_report = json::parse(gaps.out);
  ASSERT_GE(gaps_report["warnings"].size(), 1u) << gaps.out;
  EXPECT_NE(gaps_report["warnings"][0].get<std::string>().find("along_track_sampling"), std::string::npos);
}

// A pushbroom's integration time is stated once: without one, the detector integrates for the line time the GSD
// criterion reports (GSD_along / ground speed), at nadir and at a look off nadir; a file stating it explicitly as
// that value gives the same signal.
TEST(RunOutcome, APushbroomIntegratesForItsLineTimeUnlessSet) {
  Scratch scratch;
  for (const char* roll : {"", "roll = \"25 deg\"\n"}) {
    const fs::path derived = scratch / "s2-line-time.toml";
    std::string text = replaced(without_expected(read_text(sentinel_file)), "altitude = \"786 km\"", std::string("altitude = \"786 km\"\n") + roll);
    write_text(derived, text);
    const CliResult r = run_cli(scratch, "run '" + derived.string() + "' --format json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json report = json::parse(r.out);
    const double line_time = result(report, "criteria.gsd.line_time");
    EXPECT_NEAR(result(report, "detector.integration_time") / line_time, 1.0, 1e-12) << roll;
    EXPECT_TRUE(report["warnings"].empty()) << report["warnings"].dump();
    // The same time written in the file: the same electrons.
    const fs::path stated = scratch / "s2-stated.toml";
    write_text(stated, replaced(text, "[detector]", fmt_time(line_time)));
    const json same = json::parse(run_cli(scratch, "run '" + stated.string() + "' --format json").out);
    EXPECT_NEAR(result(same, "detector.signal_electrons") / result(report, "detector.signal_electrons"), 1.0, 1e-12);
  }
}

// Two files that differ by 1e-10 in one input: every result moves by ~1e-10 relative except the solved criterion's
// margin, which is ~1e-15 at either root. On its own scale (1) it agrees to 1e-6.
TEST(RunOutcome, CompareJudgesAMarginOnItsOwnScale) {
  Scratch scratch;
  const fs::path nudged = scratch / "nudged.toml";
  write_text(nudged, sbv_with("qe = 0.27", "qe = 0.270000000027"));
  const CliResult r = run_cli(scratch, "compare '" + sbv_file + "' '" + nudged.string() + "' --tolerance 1e-6");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(r.out.find("EXCEEDS"), std::string::npos) << r.out;
  // A real change of a margin still exceeds: forward-only at magnitude 15, a threshold of 6 instead of 5.
  const fs::path stricter = scratch / "stricter.toml";
  write_text(stricter, sbv_with("threshold = 5 ", "threshold = 6 "));
  const CliResult moved = run_cli(scratch, "compare '" + sbv_file + "' '" + stricter.string() +
                                               "' --no-solve --set target.magnitude=15 --tolerance 1e-6");
  EXPECT_EQ(moved.exit_code, 1) << moved.out;
  EXPECT_NE(moved.out.find("criteria.detection.margin"), std::string::npos) << moved.out;
}

// `budget` exits 0 on every bundled sensor and example: each file's solved unknowns and checked results, every
// input stepped inside its range (a first step where the chain cannot be evaluated is shrunk).
TEST(RunOutcome, BudgetRunsOnEveryBundledFile) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "30 s of budgets in the release build; the sanitizer builds check memory, not this";
#endif
  Scratch scratch;
  int files = 0;
  for (const char* folder : {"/sensors", "/examples"})
    for (const auto& entry : fs::directory_iterator(source_dir + folder)) {
      if (entry.path().extension() != ".toml") continue;
      const CliResult run = run_cli(scratch, "run '" + entry.path().string() + "' --format json");
      ASSERT_EQ(run.exit_code, 0) << entry.path() << run.err;
      const json report = json::parse(run.out);
      std::string results;
      for (const auto& s : report["solves"]) results += (results.empty() ? "" : ",") + s["unknown"].get<std::string>();
      if (results.empty())
        for (const auto& e : report["expected"]) {
          results = e["result"].get<std::string>();
          break;
        }
      if (results.empty()) continue;
      ++files;
      const CliResult budget = run_cli(scratch, "budget '" + entry.path().string() + "' --results " + results);
      EXPECT_EQ(budget.exit_code, 0) << entry.path() << "\n" << budget.out << budget.err;
    }
  EXPECT_GE(files, 30);
}

}  // namespace

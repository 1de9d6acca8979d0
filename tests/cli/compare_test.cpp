// `radchain compare`: msx-sbv against a copy with a 20 cm pupil and QE 0.30. References: the inputs as written,
// and closed forms of the chain: collecting area ∝ D², so (20/15)² - 1 = +77.8 %; at the limiting magnitude the
// signal is fixed by SNR = T, so the flux ratio D² QE gives Δm = 2.5 log10((20/15)² · 0.30/0.27).
#include "cli_helpers.hpp"
#include "radchain/batch/compare.hpp"
#include "radchain/error.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

namespace {
using namespace radchain;
using namespace radchain::test;

class Compare : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string text = sbv_with("aperture = \"15 cm\"", "aperture = \"20 cm\"");
    text = text.replace(text.find("qe = 0.27"), 9, "qe = 0.30");
    variant_ = scratch_ / "sbv-20cm.toml";
    write_text(variant_, text);
  }
  Scratch scratch_;
  fs::path variant_;
};

const ResultDifference& result_named(const Comparison& c, const std::string& name) {
  for (const auto& r : c.results)
    if (r.name == name) return r;
  throw std::out_of_range(name);
}

TEST_F(Compare, InputsThatDifferAreListedInSi) {
  const Comparison c = compare(load_compare_input(sbv_file), load_compare_input(variant_.string()));
  ASSERT_TRUE(c.inputs_compared);
  ASSERT_EQ(c.inputs.size(), 2u);  // the solved magnitude is compared as written in the file, not as solved
  EXPECT_EQ(c.inputs[0].name, "optics.aperture");
  EXPECT_EQ(c.inputs[0].a, "15 cm");
  EXPECT_EQ(c.inputs[0].b, "20 cm");
  EXPECT_EQ(c.inputs[0].unit, "cm");
  EXPECT_DOUBLE_EQ(c.inputs[0].a_si, 0.15);
  EXPECT_DOUBLE_EQ(c.inputs[0].b_si, 0.20);
  EXPECT_EQ(c.inputs[0].si_unit, "m");
  EXPECT_EQ(c.inputs[1].name, "detector.qe");
  EXPECT_DOUBLE_EQ(c.inputs[1].b_si, 0.30);
}

TEST_F(Compare, EveryResultSideBySide) {
  const Comparison c = compare(load_compare_input(sbv_file), load_compare_input(variant_.string()));
  const auto& area = result_named(c, "optics.collecting_area");
  EXPECT_NEAR(area.relative(), std::pow(20.0 / 15.0, 2) - 1, 1e-12);
  EXPECT_EQ(area.unit, "cm2");
  const auto& magnitude = result_named(c, "target.magnitude");
  EXPECT_NEAR(magnitude.b_si - magnitude.a_si, 2.5 * std::log10(std::pow(20.0 / 15.0, 2) * 0.30 / 0.27), 1e-9);
  const auto& dark = result_named(c, "detector.dark_electrons");
  EXPECT_TRUE(dark.same());
  EXPECT_FALSE(dark.exceeds(0));
  // Each noise term, the signal and the SNR are there.
  for (const char* name : {"detector.signal_electrons", "detector.shot_noise", "detector.read_noise",
                           "detector.quantisation_noise", "detector.noise_electrons", "detector.snr"})
    EXPECT_NO_THROW(result_named(c, name)) << name;
  EXPECT_GT(count_exceeding(c, 1e-6), 0u);
}

TEST_F(Compare, ToleranceTurnsItIntoARegressionTest) {
  const CliResult differs = run_cli(scratch_, "compare '" + sbv_file + "' '" + variant_.string() + "' --tolerance 1e-6");
  EXPECT_EQ(differs.exit_code, 1) << differs.err;
  EXPECT_NE(differs.out.find("optics.aperture  15 cm"), std::string::npos) << differs.out;
  EXPECT_NE(differs.out.find("EXCEEDS"), std::string::npos);
  const CliResult no_tolerance = run_cli(scratch_, "compare '" + sbv_file + "' '" + variant_.string() + "'");
  EXPECT_EQ(no_tolerance.exit_code, 0) << no_tolerance.err;
  const CliResult same = run_cli(scratch_, "compare '" + sbv_file + "' '" + sbv_file + "' --tolerance 0");
  EXPECT_EQ(same.exit_code, 0) << same.err;
  EXPECT_NE(same.out.find("inputs: the same"), std::string::npos) << same.out;
  EXPECT_NE(same.out.find("0 differ"), std::string::npos) << same.out;
}

TEST_F(Compare, SavedJsonResultsCompareWithASensorFile) {
  const fs::path saved = scratch_ / "sbv.json";
  const CliResult run = run_cli(scratch_, "run '" + sbv_file + "' --format json");
  ASSERT_EQ(run.exit_code, 0);
  write_text(saved, run.out);
  // The JSON holds every value to the last bit: no result moves.
  const CliResult r = run_cli(scratch_, "compare '" + saved.string() + "' '" + sbv_file + "' --tolerance 0 --format json");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_GT(j["rows"].size(), 20u);
  for (const auto& row : j["rows"]) {
    EXPECT_EQ(row["kind"], "result");  // no inputs: a results file has none
    EXPECT_EQ(row["status"], "same") << row.dump();
  }
}

TEST_F(Compare, CsvHasInputsThenResults) {
  const CliResult r = run_cli(scratch_, "compare '" + sbv_file + "' '" + variant_.string() + "' --format csv");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out.substr(0, r.out.find('\n')), "kind,name,a,b,unit,delta,delta_pct,status");
  EXPECT_NE(r.out.find("\ninput,optics.aperture,15,20,cm,+5,+33.3,differs\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\nresult,optics.aperture,15,20,cm,+5,+33.3,differs\n"), std::string::npos) << r.out;
}

TEST_F(Compare, SolvedUnknownsComeFirst) {
  const Comparison c = compare(load_compare_input(sbv_file), load_compare_input(variant_.string()));
  ASSERT_FALSE(c.results.empty());
  EXPECT_EQ(c.results.front().name, "target.magnitude");
  const CliResult r = run_cli(scratch_, "compare '" + sbv_file + "' '" + variant_.string() + "' --format csv");
  const auto first_result = r.out.find("\nresult,");
  ASSERT_NE(first_result, std::string::npos) << r.out;
  EXPECT_EQ(r.out.compare(first_result, 25, "\nresult,target.magnitude,"), 0) << r.out;
}

// The same pupil written as "150 mm": the inputs differ as written, the results by rounding at most, and
// nothing is reported as differing.
TEST_F(Compare, RoundingIsNotADifference) {
  const fs::path mm = scratch_ / "sbv-mm.toml";
  write_text(mm, sbv_with("aperture = \"15 cm\"", "aperture = \"150 mm\""));
  const CliResult r = run_cli(scratch_, "compare '" + sbv_file + "' '" + mm.string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("differs"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" 0 differ by more than 1e-09"), std::string::npos) << r.out;
}

TEST(CompareStatus, MovesWithinTheRoundingToleranceAreOk) {
  Comparison c;
  c.results.push_back(ResultDifference{"a.same", "m", 1, 2.0, 2.0, true, true});
  c.results.push_back(ResultDifference{"a.rounding", "m", 1, 2.0, 2.0 * (1 + 1e-12), true, true});
  c.results.push_back(ResultDifference{"a.moved", "m", 1, 2.0, 2.0 * (1 + 1e-6), true, true});
  const std::string text = format_comparison_text(c);
  EXPECT_NE(text.find("3 results, 1 differ by more than 1e-09"), std::string::npos) << text;
  std::ostringstream csv;
  write_comparison(c, TableFormat::csv, csv);
  EXPECT_NE(csv.str().find("result,a.same,2,2,m,+0,+0,same\n"), std::string::npos) << csv.str();
  EXPECT_NE(csv.str().find("result,a.rounding,2,2,m,+2e-12,+1e-10,ok\n"), std::string::npos) << csv.str();
  EXPECT_NE(csv.str().find(",differs\n"), std::string::npos) << csv.str();
  // An explicit tolerance still decides: 0 makes the rounding exceed.
  std::ostringstream strict;
  write_comparison(c, TableFormat::csv, strict, 0.0);
  EXPECT_NE(strict.str().find("result,a.rounding,2,2,m,+2e-12,+1e-10,EXCEEDS\n"), std::string::npos) << strict.str();
  EXPECT_EQ(count_exceeding(c, 0.0), 2u);
}

TEST_F(Compare, NoSolveComparesForward) {
  const CliResult r = run_cli(scratch_, "compare '" + sbv_file + "' '" + variant_.string() + "' --no-solve --format csv");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  // Both at the magnitude written in the file; the signal grows with the pupil and the QE instead.
  EXPECT_NE(r.out.find("\nresult,target.magnitude,15.5,15.5,,+0,+0,same\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\nresult,detector.signal_electrons,"), std::string::npos) << r.out;
}

TEST(CompareInputs, BadTolerance) {
  EXPECT_THROW(parse_tolerance("abc"), InputError);
  EXPECT_THROW(parse_tolerance("-1"), InputError);
  EXPECT_DOUBLE_EQ(parse_tolerance("0.1%"), 1e-3);
  EXPECT_DOUBLE_EQ(parse_tolerance("1e-6"), 1e-6);
}

}  // namespace

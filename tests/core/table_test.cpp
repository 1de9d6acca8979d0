// [[table]]: the limiting magnitude vs exposure of Rubin r, recomputed by hand from the noise
// terms of the 30 s run — the CCD equation solved as a quadratic in S — and against single runs at each exposure.
#include "radchain/chain.hpp"
#include "radchain/report.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace {
using namespace radchain;

const std::string source_dir = RADCHAIN_SOURCE_DIR;
const std::string rubin_r = source_dir + "/sensors/rubin-lsst-r-m5.toml";

const TableOutcome& only_table(const Report& report) {
  EXPECT_EQ(report.tables.size(), 1u);
  return report.tables.front();
}

TEST(SensorTable, RubinDepthVsExposureMatchesTheCcdEquationByHand) {
  Chain chain = load_sensor(rubin_r);
  const Report report = chain.run();
  const TableOutcome& table = only_table(report);
  ASSERT_EQ(table.spec.vary, "detector.integration_time");
  ASSERT_EQ(table.columns.front().name, "target.magnitude");
  ASSERT_EQ(table.rows.size(), table.spec.values_si.size());

  // Noise per exposure of t seconds from the 30 s run: sky and dark electrons grow with t; read and
  // quantisation noise do not (n_eff pixels, gain 1 DN/e-, no PRNU or DSNU in this file).
  const double t0 = *report.value("detector.integration_time");
  ASSERT_DOUBLE_EQ(t0, 30.0);
  const double sky0 = *report.value("detector.background_electrons");
  const double dark0 = *report.value("detector.dark_electrons");
  const double read = *report.value("detector.read_noise");
  const double n_eff = *report.value("detector.noise_equivalent_area");
  const double quantisation = *report.value("detector.quantisation_noise");
  const double zero_point = *report.value("detector.instrumental_zero_point");  // m giving 1 e-/s
  const double k = 5;  // [criteria.detection] threshold
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    const double t = table.spec.values_si[r];
    const double variance = (sky0 + dark0) * t / t0 + read * read + n_eff * quantisation * quantisation;
    // S / √(S + V) = k  ⇔  S² − k² S − k² V = 0
    const double signal = 0.5 * (k * k + std::sqrt(k * k * k * k + 4 * k * k * variance));
    const double m5 = zero_point - 2.5 * std::log10(signal / t);
    EXPECT_NEAR(table.rows[r][0], m5, 1e-6) << "t = " << table.spec.values_written[r];
    EXPECT_TRUE(table.notes[r].empty()) << table.notes[r];
  }
  // Sky-limited: ten times the exposure is 1.25 mag deeper, plus what the read noise costs the 30 s visit.
  const double deeper = table.rows.back()[0] - table.rows[2][0];
  ASSERT_EQ(table.spec.values_written[2], "30 s");
  ASSERT_EQ(table.spec.values_written.back(), "300 s");
  EXPECT_GT(deeper, 1.25);
  EXPECT_LT(deeper, 1.30);
}

TEST(SensorTable, EachRowEqualsARunAtThatValueAndTheChainIsPutBack) {
  Chain chain = load_sensor(rubin_r);
  const Report report = chain.run();
  const TableOutcome& table = only_table(report);
  for (std::size_t r = 0; r < table.rows.size(); ++r) {
    Chain single = load_sensor(rubin_r, {{"detector.integration_time", "\"" + table.spec.values_written[r] + "\""}});
    single.tables.clear();
    const Report alone = single.run();
    for (std::size_t c = 0; c < table.columns.size(); ++c)
      EXPECT_NEAR(table.rows[r][c], *alone.value(table.columns[c].name), 1e-9 * std::abs(table.rows[r][c]))
          << table.columns[c].name << " at " << table.spec.values_written[r];
  }
  // After the table, the chain holds the file's 30 s again: a second run reports what the first did.
  const Report again = chain.run();
  EXPECT_DOUBLE_EQ(*again.value("target.magnitude"), *report.value("target.magnitude"));
  EXPECT_DOUBLE_EQ(*again.value("detector.integration_time"), 30.0);
}

TEST(SensorTable, ARowWhoseSolveFailsHasNoValuesAndSaysWhy) {
  // A 1 µs exposure cannot reach 5σ inside the bracket [20, 28]: that row is NaN with the solver's reason.
  Chain chain = load_sensor(rubin_r);
  chain.tables.clear();
  TableSpec spec;
  spec.vary = "detector.integration_time";
  spec.values_si = {1e-6, 30};
  spec.values_written = {"0.000001 s", "30 s"};
  spec.results = {"target.magnitude", "detector.snr"};
  (void)chain.run();
  const TableOutcome out = chain.tabulate(spec);
  ASSERT_EQ(out.rows.size(), 2u);
  EXPECT_TRUE(std::isnan(out.rows[0][0]) && std::isnan(out.rows[0][1]));
  EXPECT_NE(out.notes[0].find("target.magnitude"), std::string::npos) << out.notes[0];
  EXPECT_FALSE(std::isnan(out.rows[1][0]));
  EXPECT_TRUE(out.notes[1].empty());
  EXPECT_NE(format_table_text(out).find("(target.magnitude: "), std::string::npos);
}

}  // namespace

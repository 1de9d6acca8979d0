// The detection threshold of Pan 2010 §3.3 (T = 5 for P_d ≥ 99 %, P_fa ≤ 1 %, read off its Fig. 5) in
// Gaussian detection theory (physics/detection.hpp): tabulated normal quantiles, what T = 5 means exactly,
// and the snr_threshold plugin with probabilities.
#include "radchain/chain.hpp"
#include "radchain/error.hpp"
#include "radchain/physics/detection.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

namespace {
using namespace radchain;
using namespace radchain::physics;

const std::string sbv = std::string(RADCHAIN_SOURCE_DIR) + "/sensors/msx-sbv.toml";

// Φ from the C library's erfc: independent of Boost.Math.
double phi(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

TEST(Pan2010Detection, NormalQuantilesAgainstTables) {
  // Abramowitz & Stegun Table 26.5 / any statistics table.
  EXPECT_NEAR(standard_normal_quantile(0.99), 2.326348, 5e-7);
  EXPECT_NEAR(standard_normal_quantile(0.995), 2.575829, 5e-7);
  EXPECT_NEAR(standard_normal_quantile(0.975), 1.959964, 5e-7);
  EXPECT_NEAR(standard_normal_quantile(0.5), 0.0, 1e-15);
  EXPECT_NEAR(standard_normal_cdf(2.5), 0.9937903, 5e-8);
  EXPECT_NEAR(standard_normal_tail(2.5), 0.0062097, 5e-8);
  EXPECT_NEAR(standard_normal_tail(8.0), 6.22096e-16, 1e-20);  // no cancellation in the far tail
  EXPECT_THROW(standard_normal_quantile(1.0), std::domain_error);
}

TEST(Pan2010Detection, WhatTheThresholdFiveMeans) {
  // The stated requirement P_d = 0.99, P_fa = 0.01 needs T = 2 z(0.99) = 4.652696, less than the paper's 5.
  EXPECT_NEAR(snr_threshold_for(0.99, 0.01), 4.652696, 5e-7);
  // T = 5 exceeds it. With P_fa = 1 % it gives P_d = Φ(5 − 2.326348) = Φ(2.673652) = 0.996248;
  const double pd = detection_probability_at(5.0, 0.01);
  EXPECT_NEAR(pd, phi(5.0 - 2.3263478740), 1e-12);
  EXPECT_NEAR(pd, 0.996248, 5e-7);
  // with P_d = 99 % it allows P_fa = 1 − Φ(2.673652) = 0.003752;
  const double pfa = false_alarm_probability_at(5.0, 0.99);
  EXPECT_NEAR(pfa, 1.0 - phi(2.6736521260), 1e-12);
  EXPECT_NEAR(pfa, 0.003752, 5e-7);
  // split evenly (decision level at T/2 = 2.5σ): P_d = 1 − P_fa = Φ(2.5) = 0.993790, P_fa = 0.006210.
  EXPECT_NEAR(detection_probability_at(5.0, standard_normal_tail(2.5)), phi(2.5), 1e-12);
  EXPECT_NEAR(snr_threshold_for(phi(2.5), 1.0 - phi(2.5)), 5.0, 1e-12);
  EXPECT_NEAR(phi(2.5), 0.993790, 5e-7);
  // Round trips.
  EXPECT_NEAR(detection_probability_at(snr_threshold_for(0.9, 1e-6), 1e-6), 0.9, 1e-12);
  EXPECT_NEAR(false_alarm_probability_at(snr_threshold_for(0.9, 1e-6), 0.9), 1e-6, 1e-17);
}

// msx-sbv.toml with its threshold line replaced, written next to the test's temporary files.
std::string sbv_with_criterion(const std::string& criterion_lines, const std::string& name) {
  std::ifstream in(sbv);
  std::stringstream text;
  std::string line;
  while (std::getline(in, line)) text << (line.rfind("threshold = 5", 0) == 0 ? criterion_lines : line) << '\n';
  // Unique per process: other builds on the machine may run this test at the same time.
  const auto path = std::filesystem::temp_directory_path() /
                    ("radchain_pan2010_detection_" + std::to_string(::getpid()) + "_" + name + ".toml");
  std::ofstream(path) << text.str();
  return path.string();
}

TEST(Pan2010Detection, PluginWithProbabilities) {
  const std::string file = sbv_with_criterion("detection_probability = 0.99\nfalse_alarm_probability = 0.01", "pd_pfa");
  Chain chain = load_sensor(file);
  const Report r = chain.run();
  std::filesystem::remove(file);
  ASSERT_TRUE(r.solves.at(0).converged);
  EXPECT_NEAR(r.value("criteria.detection.threshold").value(), 4.652696, 5e-7);
  EXPECT_NEAR(r.value("detector.snr").value(), 4.652696, 5e-7);
  EXPECT_NEAR(r.value("criteria.detection.detection_probability").value(), 0.99, 1e-9);
  // A lower threshold, a fainter limit: 15.6590 instead of 15.5565 at T = 5.
  EXPECT_NEAR(r.solves.at(0).value_si, 15.6590, 1e-4);
}

TEST(Pan2010Detection, PluginReportsTheDetectionProbabilityOfAGivenThreshold) {
  const std::string file = sbv_with_criterion("threshold = 5\nfalse_alarm_probability = 0.01", "t_pfa");
  Chain chain = load_sensor(file);
  const Report r = chain.run();
  ASSERT_TRUE(r.solves.at(0).converged);
  EXPECT_NEAR(r.solves.at(0).value_si, 15.5565, 1e-4);  // the threshold decides, P_fa only reports
  EXPECT_NEAR(r.value("criteria.detection.detection_probability").value(), 0.996248, 5e-7);
  EXPECT_EQ(r.value("criteria.detection.false_alarm_probability").value(), 0.01);
  // P_d alone is not enough.
  const std::string bad = sbv_with_criterion("threshold = 5\ndetection_probability = 0.99", "t_pd");
  EXPECT_THROW(load_sensor(bad), InputError);
  std::filesystem::remove(file);
  std::filesystem::remove(bad);
}

}  // namespace

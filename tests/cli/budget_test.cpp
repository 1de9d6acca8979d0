// `radchain budget`: derivatives checked against closed forms, one-sided differences at a bound, a solve that fails
// at a perturbed point, and bad input.
//
// The closed forms for the MSX SBV limiting magnitude (Pan 2010 noise equation, no sky, a 1-pixel window): at the
// root, F(m, x) = S − T √(C + S) = 0 with S ∝ D² τ η t 10^(−0.4 (m − m_sun)) / d² the signal electrons and
// C = N_d + σ² + q² the signal-independent variance (N_d = dark rate × t, q² = n_well / (2^N √12) as printed).
// With n = S/T at the root, ∂F/∂S = 1 − T²/(2S) =: A, ∂F/∂C = −T²/(2S), ∂S/∂m = −c S (c = 0.4 ln 10), and the
// implicit function theorem gives dm/dln x = (∂F/∂ln x) / (A c S):
//   aperture D:       ∂F/∂ln D = 2 A S                  → dm/dln D = 2/c = 5/ln 10 (exact: m − 5 log D is constant)
//   transmittance τ:  ∂F/∂ln τ = A S                    → 2.5/ln 10
//   Sun's magnitude:  S depends on m − m_sun only       → dm/dm_sun = 1
//   read noise σ:     ∂F/∂ln σ = −T² σ² / S             → −T² σ² / (A c S²)
//   dark rate r:      ∂F/∂ln r = −T² N_d / (2S)         → −T² N_d / (2 A c S²)
//   full well n_well: ∂F/∂ln n_well = −T² q² / (2S)     → −T² q² / (2 A c S²)
//   integration t:    ∂F/∂ln t = A S − T² N_d / (2S)    → (A S − T² N_d/(2S)) / (A c S)
//   threshold T:      ∂F/∂ln T = −T n = −S              → −1 / (A c)
// S, N_d, σ, q are the chain's own results at the nominal point (`radchain run`); nothing here differentiates.
#include "cli_helpers.hpp"
#include "radchain/batch/budget.hpp"
#include "radchain/error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>

namespace {
using namespace radchain;
using namespace radchain::test;

const BudgetEntry& entry(const Budget& budget, const std::string& result, const std::string& parameter) {
  for (const auto& e : budget.entries)
    if (e.result == result && e.parameter == parameter) return e;
  throw std::out_of_range("no entry " + result + " / " + parameter);
}

bool has_entry(const Budget& budget, const std::string& parameter) {
  for (const auto& e : budget.entries)
    if (e.parameter == parameter) return true;
  return false;
}

Budget budget_of(const std::string& file, const std::vector<std::string>& results, const std::vector<Override>& sets = {},
                 bool no_solve = false) {
  Chain chain = load_sensor(file, sets);
  if (no_solve) chain.solves.clear();
  BudgetOptions options;
  options.results = results;
  return compute_budget(chain, options);
}

constexpr double tolerance = 1e-6;  // relative, the accuracy the budget promises
const double c = 0.4 * std::numbers::ln10;

TEST(Budget, SbvLimitingMagnitudeAgainstClosedForms) {
  Chain nominal = load_sensor(sbv_file);
  const Report report = nominal.run();
  const double S = report.value("detector.signal_electrons").value();
  const double Nd = report.value("detector.dark_electrons").value();
  const double sigma = report.value("detector.read_noise").value();
  const double q = report.value("detector.quantisation_noise").value();
  const double T = report.value("criteria.detection.threshold").value();
  const double A = 1 - T * T / (2 * S);
  ASSERT_NEAR(report.value("detector.snr").value(), T, 1e-9);

  const Budget b = budget_of(sbv_file, {"target.magnitude", "detector.snr"});
  EXPECT_EQ(b.solved, std::vector<std::string>{"target.magnitude"});
  EXPECT_FALSE(has_entry(b, "target.magnitude"));  // the solved unknown is not an input
  EXPECT_FALSE(has_entry(b, "detector.adc_bits"));  // an integer

  struct Reference {
    std::string parameter;
    double dm_dln;  // ∂m/∂ln x
  };
  const double m_sun = -26.73;
  const std::vector<Reference> references = {
      {"optics.aperture", 5 / std::numbers::ln10},
      {"optics.transmittance", 2.5 / std::numbers::ln10},
      {"detector.read_noise", -T * T * sigma * sigma / (A * c * S * S)},
      {"detector.dark_current", -T * T * Nd / (2 * A * c * S * S)},
      {"detector.full_well", -T * T * q * q / (2 * A * c * S * S)},
      {"detector.integration_time", (A * S - T * T * Nd / (2 * S)) / (A * c * S)},
      {"criteria.detection.threshold", -1 / (A * c)},
  };
  for (const auto& r : references) {
    const BudgetEntry& e = entry(b, "target.magnitude", r.parameter);
    ASSERT_TRUE(e.ok) << r.parameter << ": " << e.failure;
    EXPECT_EQ(e.kind, DifferenceKind::central) << r.parameter;
    EXPECT_NEAR(e.elasticity, r.dm_dln, tolerance * std::abs(r.dm_dln)) << r.parameter;
    EXPECT_NEAR(e.derivative, r.dm_dln / e.value_si, tolerance * std::abs(r.dm_dln / e.value_si)) << r.parameter;
    EXPECT_NEAR(e.log_elasticity, r.dm_dln / e.result_si, tolerance * std::abs(r.dm_dln / e.result_si)) << r.parameter;
    EXPECT_TRUE(e.accurate) << r.parameter << " error " << e.error;
  }
  // The SNR is held at T by the solve: it moves with T only (∂SNR/∂ln T = T), with nothing else (to rounding).
  const BudgetEntry& snr_t = entry(b, "detector.snr", "criteria.detection.threshold");
  EXPECT_NEAR(snr_t.elasticity, T, tolerance * T);
  for (const char* p : {"optics.aperture", "detector.read_noise", "detector.integration_time"})
    EXPECT_NEAR(entry(b, "detector.snr", p).elasticity, 0.0, 1e-9) << p;

  // The Sun's magnitude: dm/dm_sun = 1 exactly (the target's irradiance is E_sun 10^(0.4 (m_sun − m))); a magnitude's
  // elasticity is by the flux it stands for, ∂m/∂ln F_sun = −2.5/ln 10, the same size as the QE's (a flux factor).
  const BudgetEntry& sun = entry(b, "target.magnitude", "source.visual_magnitude");
  EXPECT_TRUE(sun.per_flux);
  EXPECT_NEAR(sun.value_si, m_sun, 1e-12);
  EXPECT_NEAR(sun.derivative, 1.0, tolerance);
  EXPECT_NEAR(sun.elasticity, -2.5 / std::numbers::ln10, tolerance * 1.0857);
  EXPECT_NEAR(std::abs(sun.elasticity), entry(b, "target.magnitude", "detector.qe").elasticity, tolerance * 1.0857);
  EXPECT_FALSE(entry(b, "target.magnitude", "detector.qe").per_flux);

  // Ranked by |elasticity|: the aperture (2.17) first, then the threshold (1.43).
  EXPECT_EQ(entry(b, "target.magnitude", "optics.aperture").rank, 1u);
  EXPECT_EQ(entry(b, "target.magnitude", "criteria.detection.threshold").rank, 2u);
  std::size_t previous_rank = 0;
  double previous = INFINITY;
  for (const auto& e : b.entries)
    if (e.result == "target.magnitude") {
      EXPECT_EQ(e.rank, previous_rank + 1);
      EXPECT_LE(std::abs(e.elasticity), previous);
      previous = std::abs(e.elasticity), previous_rank = e.rank;
    }
}

// The root-finder (TOMS 748 to 2^-47 of the bracket) instead of the closed form: still within 1e-6.
// A sky brightness in mag/arcsec² is a magnitude too: its elasticity is per ln of the sky's flux. Rubin r's m5:
// with the sky's flux B, n² ≈ B n_eff + read + dark at SNR 5, so ∂m5/∂m_sky lies in (0, ½] — ½ when the sky
// dominates the noise (m5 ∝ −1.25 lg B), less with read noise and the source's own shot noise.
TEST(Budget, SkyBrightnessIsAMagnitude) {
  const Budget b = budget_of(source_dir + "/sensors/rubin-lsst-r-m5.toml", {"target.magnitude"});
  const BudgetEntry& sky = entry(b, "target.magnitude", "atmosphere.sky_brightness");
  ASSERT_TRUE(sky.ok) << sky.failure;
  EXPECT_TRUE(sky.per_flux);
  EXPECT_GT(sky.derivative, 0.3);  // Rubin r is sky-dominated (987 e- of sky per pixel against 77 e-² of read noise)
  EXPECT_LT(sky.derivative, 0.5);
  EXPECT_NEAR(sky.elasticity, -2.5 / std::numbers::ln10 * sky.derivative, 1e-12);
  const std::string text = format_budget_text(b);
  const auto row = text.find("atmosphere.sky_brightness");
  ASSERT_NE(row, std::string::npos);
  EXPECT_NE(text.substr(row, text.find('\n', row) - row).find("magnitude: elasticity per ln flux"), std::string::npos) << text;
}

TEST(Budget, SbvWithBracketingSolver) {
  Chain chain = load_sensor(sbv_file);
  chain.solver = SolverChoice::root;
  BudgetOptions options;
  options.results = {"target.magnitude"};
  const Budget b = compute_budget(chain, options);
  const BudgetEntry& e = entry(b, "target.magnitude", "optics.aperture");
  ASSERT_TRUE(e.ok) << e.failure;
  EXPECT_NEAR(e.elasticity, 5 / std::numbers::ln10, tolerance * 5 / std::numbers::ln10);
}

// Forward only (--no-solve): S ∝ t and S ∝ D², so ∂S/∂ln t = S and ∂S/∂ln D = 2S exactly; the magnitude is an
// input then, with ∂ln S/∂m = −0.4 ln 10.
TEST(Budget, NoSolveSignalIsProportionalToIntegrationTime) {
  const Budget b = budget_of(sbv_file, {"detector.signal_electrons"}, {}, true);
  EXPECT_TRUE(b.solved.empty());
  const BudgetEntry& t = entry(b, "detector.signal_electrons", "detector.integration_time");
  ASSERT_TRUE(t.ok) << t.failure;
  EXPECT_NEAR(t.elasticity, t.result_si, tolerance * t.result_si);
  EXPECT_NEAR(t.log_elasticity, 1.0, tolerance);
  EXPECT_EQ(t.derivative_unit, "electron/s");
  const BudgetEntry& d = entry(b, "detector.signal_electrons", "optics.aperture");
  EXPECT_NEAR(d.log_elasticity, 2.0, tolerance * 2);
  const BudgetEntry& m = entry(b, "detector.signal_electrons", "target.magnitude");
  ASSERT_TRUE(m.ok) << m.failure;
  EXPECT_NEAR(m.derivative / m.result_si, -c, tolerance * c);
}

// A value at its bound gets a one-sided difference: τ = 1 (accepted (0, 1]) backward, ε = 0 ([0, 1)) forward.
TEST(Budget, OneSidedAtTheBounds) {
  const Budget b = budget_of(sbv_file, {"target.magnitude"}, {{"optics.transmittance", "1"}});
  const BudgetEntry& tau = entry(b, "target.magnitude", "optics.transmittance");
  ASSERT_TRUE(tau.ok) << tau.failure;
  EXPECT_EQ(tau.kind, DifferenceKind::backward);
  EXPECT_NEAR(tau.elasticity, 2.5 / std::numbers::ln10, tolerance * 2.5 / std::numbers::ln10);
  const BudgetEntry& eps = entry(b, "target.magnitude", "optics.obscuration");
  ASSERT_TRUE(eps.ok) << eps.failure;
  EXPECT_EQ(eps.kind, DifferenceKind::forward);
  // S ∝ 1 − ε²: dm/dε = −(5/ln 10) ε/(1 − ε²) = 0 at ε = 0 (absolute: the scale of dm/dε is ~m).
  EXPECT_NEAR(eps.derivative, 0.0, tolerance);
  EXPECT_EQ(eps.elasticity, 0.0);
  // ε = 0.3 (interior, central) against the same closed form.
  const Budget b3 = budget_of(sbv_file, {"target.magnitude"}, {{"optics.obscuration", "0.3"}});
  const BudgetEntry& e3 = entry(b3, "target.magnitude", "optics.obscuration");
  EXPECT_EQ(e3.kind, DifferenceKind::central);
  const double reference = -(5 / std::numbers::ln10) * 0.3 / (1 - 0.09);
  EXPECT_NEAR(e3.derivative, reference, tolerance * std::abs(reference));
}

// An EO camera: Kolobrodov 1996 (computed). f' = V_s h / δV (eq. 16) and, with the matching criterion binding,
// D = k f' λ / (η_max V_D) (eq. 12): ∂ln f'/∂ln h = 1, ∂ln f'/∂ln δV = −1, ∂ln D/∂ln h = 1, ∂ln D/∂ln η_max = −1,
// ∂ln D/∂ln λ = 1 — whatever the spectra give.
TEST(Budget, KolobrodovFocalLengthAndAperture) {
  const std::string file = source_dir + "/sensors/kolobrodov-1996-ccd151-computed.toml";
  const Budget b = budget_of(file, {"optics.focal_length", "optics.aperture"});
  EXPECT_FALSE(has_entry(b, "optics.focal_length"));
  EXPECT_FALSE(has_entry(b, "optics.aperture"));
  struct Reference {
    std::string result, parameter;
    double log_elasticity;
  };
  for (const Reference& r : std::vector<Reference>{{"optics.focal_length", "platform.altitude", 1},
                                                    {"optics.focal_length", "criteria.resolution.ground_element", -1},
                                                    {"optics.aperture", "platform.altitude", 1},
                                                    {"optics.aperture", "criteria.matching.max_quality", -1},
                                                    {"optics.aperture", "criteria.matching.wavelength", 1},
                                                    {"optics.focal_length", "atmosphere.transmittance", 0}}) {
    const BudgetEntry& e = entry(b, r.result, r.parameter);
    ASSERT_TRUE(e.ok) << r.parameter << ": " << e.failure;
    EXPECT_NEAR(e.log_elasticity, r.log_elasticity, tolerance) << r.result << " / " << r.parameter;
  }
}

// A solve that fails at a perturbed point is reported with the reason, never a zero: a bracket that ends 1e-6 mag
// above the root (15.5565045) fails as soon as the aperture grows, even by the smallest first step budget tries
// (1e-3 of 2 %: 4e-5 mag).
TEST(Budget, FailedSolveIsReported) {
  Scratch scratch;
  write_text(scratch / "tight.toml", sbv_with("bracket = [5, 25]", "bracket = [5, 15.556505]"));
  Chain chain = load_sensor((scratch / "tight.toml").string());
  chain.solver = SolverChoice::root;
  BudgetOptions options;
  options.results = {"target.magnitude"};
  const Budget b = compute_budget(chain, options);
  const BudgetEntry& d = entry(b, "target.magnitude", "optics.aperture");
  EXPECT_FALSE(d.ok);
  EXPECT_TRUE(std::isnan(d.derivative));
  EXPECT_NE(d.failure.find("optics.aperture = "), std::string::npos) << d.failure;
  EXPECT_NE(d.failure.find("target.magnitude"), std::string::npos) << d.failure;
  // Failed entries rank last; the obscuration (at 0, where m does not move) still has its derivative.
  EXPECT_TRUE(entry(b, "target.magnitude", "optics.obscuration").ok);
  EXPECT_FALSE(entry(b, "target.magnitude", "detector.read_noise").ok);  // fails at σ − h (m rises)
  EXPECT_EQ(b.entries.back().ok, false);

  const CliResult cli = run_cli(scratch, "budget --solver root '" + (scratch / "tight.toml").string() + "' --results target.magnitude");
  EXPECT_EQ(cli.exit_code, 1) << cli.err;
  EXPECT_NE(cli.out.find("FAILED"), std::string::npos) << cli.out;
}

TEST(BudgetCli, TextCsvJsonAndPlot) {
  Scratch scratch;
  const CliResult text = run_cli(scratch, "budget '" + sbv_file + "' --results target.magnitude,detector.snr");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("target.magnitude = 15.556"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("optics.aperture"), std::string::npos);
  EXPECT_NE(text.out.find("re-solved at every point: target.magnitude"), std::string::npos);

  const CliResult csv = run_cli(scratch, "budget '" + sbv_file + "' --results target.magnitude --format csv");
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  std::istringstream lines(csv.out);
  std::string header, line;
  std::getline(lines, header);
  EXPECT_EQ(header, "result,rank,parameter,value,unit,derivative,derivative_unit,elasticity,result_unit,log_elasticity,error,method,note");
  bool found = false;
  while (std::getline(lines, line))
    if (line.find(",optics.aperture,") != std::string::npos) {
      found = true;
      // elasticity column: 5/ln 10 to 10 significant digits
      std::vector<std::string> cells;
      std::stringstream row(line);
      for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
      ASSERT_GE(cells.size(), 8u);
      EXPECT_NEAR(std::stod(cells[7]), 5 / std::numbers::ln10, 1e-6);
    }
  EXPECT_TRUE(found) << csv.out;

  const CliResult json = run_cli(scratch, "budget '" + sbv_file + "' --results target.magnitude --out '" +
                                              (scratch / "b.json").string() + "' --plot '" + (scratch / "t.png").string() + "'");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_NE(read_text(scratch / "b.json").find("\"kind\": \"budget\""), std::string::npos);
  const std::string png = read_text(scratch / "t.png");
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

// Bad input: one located line, exit 2.
TEST(BudgetCli, BadInputIsOneLineAndExit2) {
  Scratch scratch;
  const std::string sbv = "'" + sbv_file + "'";
  struct Case {
    std::string arguments, expected;
  };
  for (const Case& k : std::vector<Case>{
           {sbv + " --results target.magnitud", "did you mean \"target.magnitude\""},
           {sbv + " --results detector.qe", "not a result"},
           {sbv + " --results target.magnitude,target.magnitude", "listed twice"},
           {sbv + " --results target.magnitude --set optics.aperture='\"15 kg\"'", "aperture"},
           {sbv + " --results target.magnitude --set optics.aperture", "expected <section>.<key>=<value>"},
           {sbv + " --results target.magnitude --set optics.aperturex=1", "aperturex"},
           {sbv + " --results target.magnitude --format yaml", "yaml"},
           {sbv, "--results"},
       }) {
    const CliResult r = run_cli(scratch, "budget " + k.arguments);
    EXPECT_EQ(r.exit_code, 2) << k.arguments << "\n" << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << k.arguments << "\n" << r.err;
    EXPECT_NE(r.err.find(k.expected), std::string::npos) << k.arguments << "\n" << r.err;
  }
  EXPECT_THROW(budget_of(sbv_file, {}), InputError);
}

}  // namespace

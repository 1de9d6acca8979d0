// `radchain uncertainty`: the distributions' moments, Monte Carlo against exact propagation through laws the chain
// obeys exactly (S ∝ t; m − 5 log₁₀ D constant along SNR = T), reproducibility (seed, thread count), bad input.
#include "cli_helpers.hpp"
#include "radchain/batch/uncertainty.hpp"
#include "radchain/error.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace {
using namespace radchain;
using namespace radchain::test;

// Each distribution's mean and sd (closed forms) against the midpoint rule over its quantile function
// (E[x] = ∫₀¹ Q(u) du), 2·10⁵ points: agreement to 1e-4 relative (the rule's error at the tails of the normal).
TEST(Uncertainty, DistributionMomentsFromQuantiles) {
  using K = Distribution::Kind;
  for (const Distribution& d : {Distribution{K::normal, 0.56, 0.02, 0}, Distribution{K::uniform, 2, 5, 0},
                                Distribution{K::lognormal, 6, 1.5, 0}, Distribution{K::triangular, 1, 2, 4},
                                Distribution{K::triangular, 1, 1, 3}}) {
    const int n = 200000;
    double s = 0, s2 = 0;
    for (int i = 0; i < n; ++i) {
      const double x = d.quantile((i + 0.5) / n);
      s += x, s2 += x * x;
    }
    const double mean = s / n, sd = std::sqrt(s2 / n - mean * mean);
    EXPECT_NEAR(mean, d.mean(), 1e-4 * std::abs(d.mean())) << static_cast<int>(d.kind);
    EXPECT_NEAR(sd, d.sd(), 1e-3 * d.sd()) << static_cast<int>(d.kind);
  }
  // The uniform variates: in (0, 1), reproducible, different per sample and per input.
  EXPECT_EQ(sample_uniform(7, 3, 1), sample_uniform(7, 3, 1));
  EXPECT_NE(sample_uniform(7, 3, 1), sample_uniform(7, 4, 1));
  EXPECT_NE(sample_uniform(7, 3, 1), sample_uniform(7, 3, 2));
  EXPECT_NE(sample_uniform(7, 3, 1), sample_uniform(8, 3, 1));
}

// A truncated normal's moments against its closed form (Johnson, Kotz & Balakrishnan 1994, §10.1):
// with α = (lo − μ)/σ, β = (hi − μ)/σ, Z = Φ(β) − Φ(α),
//   mean = μ + σ (φ(α) − φ(β))/Z,   var = σ² [1 + (αφ(α) − βφ(β))/Z − ((φ(α) − φ(β))/Z)²];
// and a truncated uniform is the uniform on the overlap. Each quantile Q(u) leaves the share u of the interval below it.
TEST(Uncertainty, TruncatedDistributionsMomentsAndRange) {
  using K = Distribution::Kind;
  const double pi = std::numbers::pi;
  auto phi = [&](double z) { return std::exp(-z * z / 2) / std::sqrt(2 * pi); };
  auto Phi = [](double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); };
  struct Case {
    double mu, sigma, lo, hi;
  };
  auto Q = [](double z) { return 0.5 * std::erfc(z / std::numbers::sqrt2); };  // 1 − Φ(z), no cancellation
  // Upper-tail intervals reaching "infinity" (1e9: φ(β) = 0) are where F(x) rounds to 1: the sd was 22.37 instead of
  // 0.4091 for (6, 1, 7.3, 1e9) until the quantile worked from the upper tail there.
  for (const Case& k : {Case{0.99, 0.02, 0.0, 1.0}, Case{0.56, 0.02, 0.55, 0.60}, Case{10, 3, -1, 12}, Case{0, 1, 2, 3},
                        Case{0, 1, 1.3, 1e9}, Case{6, 1, 7.3, 1e9}, Case{6, 1, -1e9, 4.2}}) {
    Distribution d{K::normal, k.mu, k.sigma, 0};
    const double a = (k.lo - k.mu) / k.sigma, b = (k.hi - k.mu) / k.sigma;
    const bool upper = a > 0;  // the interval lies in the upper tail: work with 1 − Φ
    const double z = upper ? Q(a) - Q(b) : Phi(b) - Phi(a);
    EXPECT_NEAR(d.truncate(k.lo, k.hi), z, 1e-14);
    const double mean = k.mu + k.sigma * (phi(a) - phi(b)) / z;
    const double var = k.sigma * k.sigma * (1 + (a * phi(a) - (std::isfinite(phi(b)) && phi(b) > 0 ? b * phi(b) : 0)) / z -
                                            std::pow((phi(a) - phi(b)) / z, 2));
    EXPECT_NEAR(d.mean(), mean, 1e-12 * std::max(1.0, std::abs(mean))) << k.mu << " " << k.lo;
    EXPECT_NEAR(d.sd(), std::sqrt(var), 1e-10 * std::sqrt(var)) << k.mu << " " << k.lo;
    // The defining property: the share of the interval's probability below Q(u) is u.
    for (double u : {1e-9, 0.01, 0.5, 0.99, 1 - 1e-9}) {
      const double x = (d.quantile(u) - k.mu) / k.sigma;
      const double share = upper ? (Q(a) - Q(x)) / z : (Phi(x) - Phi(a)) / z;
      EXPECT_NEAR(share, u, 1e-9) << k.mu << " " << k.lo << " u = " << u;
    }
  }
  Distribution u{K::uniform, 2, 5, 0};
  EXPECT_NEAR(u.truncate(3, 9), 2.0 / 3, 1e-15);
  EXPECT_NEAR(u.mean(), 4, 1e-13);
  EXPECT_NEAR(u.sd(), 2 / std::sqrt(12.0), 1e-13);
  Distribution outside{K::uniform, 2, 5, 0};
  EXPECT_EQ(outside.truncate(6, 7), 0);  // no probability in the interval: not truncated, the parser refuses it
  EXPECT_FALSE(outside.truncated);
  Distribution far{K::normal, 0.56, 0.02, 0};
  EXPECT_LT(far.truncate(0.7, 0.8), Distribution::least_truncated_probability);  // 7σ out: 1.3e-12
  EXPECT_FALSE(far.truncated);
}

// Parameters near the largest doubles (distribution_fuzz): a distribution is either refused in one line or has a
// finite mean, sd and samples at both ends of sample_uniform's range, and the moments of its closed form.
// truncated(uniform(0, 1e300), 0, 1e300) made the moments' quadrature square 1e300 and boost throw an
// evaluation_error (exit 3); lognormal(6, 1e200) squared sd/mean to infinity and sampled NaN.
TEST(Uncertainty, ExtremeParametersAreRefusedOrFinite) {
  Chain chain = load_sensor(sbv_file);
  const double pi = std::numbers::pi;
  struct Accepted {
    std::string vary;
    double mean, sd;  // closed forms
  };
  const double half_normal = (1 / std::sqrt(2 * pi)) * (1 - std::exp(-0.5)) / (0.5 * std::erf(1 / std::numbers::sqrt2));
  for (const Accepted& k : std::vector<Accepted>{
           {"detector.full_well=truncated(uniform(0 e-, 1e300 e-), 0 e-, 1e300 e-)", 5e299, 1e300 / std::sqrt(12.0)},
           {"detector.full_well=truncated(uniform(-8e307 e-, 8e307 e-), -8e307 e-, 8e307 e-)", 0, 1.6e308 / std::sqrt(12.0)},
           {"detector.full_well=triangular(0 e-, 1e200 e-, 1e200 e-)", 2e200 / 3, 1e200 / std::sqrt(18.0)},
           // a narrow law far from 0: the sd from a² + b² + c² − ab − ac − bc was 0.333 (cancellation), not 1/√6
           {"detector.full_well=triangular(100000000 e-, 100000001 e-, 100000002 e-)", 100000001, 1 / std::sqrt(6.0)},
           {"detector.full_well=truncated(normal(0 e-, 1e200 e-), 0 e-, 1e200 e-)", half_normal * 1e200, NAN},
           {"detector.full_well=truncated(normal(1e5 e-, 1 e-), -1e300 e-, 1e300 e-)", 1e5, 1},
           {"detector.read_noise=lognormal(6 e-, 1e200 e-)", 6, 1e200},
       }) {
    const VariedInput v = parse_vary(chain, k.vary);
    const Distribution& d = v.distribution;
    EXPECT_NEAR(d.mean(), k.mean, 1e-9 * std::abs(k.mean) + (k.mean == 0 ? 1e-9 * d.sd() : 0)) << k.vary;
    if (!std::isnan(k.sd)) {
      EXPECT_NEAR(d.sd(), k.sd, 1e-9 * k.sd) << k.vary;
    }
    for (const double u : {Distribution::least_u, 0.5, Distribution::greatest_u}) EXPECT_TRUE(std::isfinite(d.quantile(u))) << k.vary << " u = " << u;
  }
  for (const std::string vary : {"detector.full_well=normal(1e5 e-, 1e308 e-)", "detector.full_well=uniform(-1e308 e-, 1.7e308 e-)",
                                 "detector.full_well=truncated(uniform(-1.7e308 e-, 1.7e308 e-), 0 e-, 1 e-)",
                                 "optics.aperture=normal(1e306 km, 1 m)"}) {
    EXPECT_THROW(
        try { (void)parse_vary(chain, vary); } catch (const InputError& e) {
          EXPECT_TRUE(std::string(e.what()).find("beyond the range of a double") != std::string::npos ||
                      std::string(e.what()).find("not finite in SI units") != std::string::npos)
              << e.what();
          throw;
        },
        InputError)
        << vary;
  }
}

UncertaintyOptions sbv_options(std::vector<std::string> vary, std::vector<std::string> results, std::size_t samples) {
  UncertaintyOptions o;
  o.sensor_file = sbv_file;
  o.vary = std::move(vary);
  o.results = std::move(results);
  o.samples = samples;
  o.seed = 42;
  return o;
}

// truncated(normal(0.99, 0.02), 0, 1) keeps every sample of a transmittance in range (none is left out), and the
// Monte Carlo mean of the input equals the truncated law's (4 standard errors).
TEST(Uncertainty, TruncationKeepsSamplesInRange) {
  UncertaintyOptions o = sbv_options({"optics.transmittance=truncated(normal(0.99, 0.02), 0, 1)"}, {"optics.transmittance"}, 4000);
  const Uncertainty u = run_uncertainty(o);
  EXPECT_EQ(u.out_of_range, 0u);
  EXPECT_EQ(u.used, 4000u);
  Distribution d{Distribution::Kind::normal, 0.99, 0.02, 0};
  d.truncate(0, 1);
  const ResultStatistics& s = u.results.at(0);
  EXPECT_NEAR(s.mean, d.mean(), 4 * d.sd() / std::sqrt(4000.0));
  EXPECT_LE(s.p95, 1.0);
  EXPECT_NEAR(s.sd, d.sd(), 4 * d.sd() / std::sqrt(2 * 4000.0));
}

// S ∝ t (forward only): S = S₀ t/t₀ is linear, so the linear propagation is exact (S₀ σ_t/t₀), the correlation is 1,
// and the Monte Carlo mean and sd agree with it within sampling error (4 standard errors).
TEST(Uncertainty, LinearChainMatchesLinearPropagation) {
  UncertaintyOptions o = sbv_options({"detector.integration_time=normal(0.625 s, 10 ms)"}, {"detector.signal_electrons"}, 4000);
  o.no_solve = true;
  const Uncertainty u = run_uncertainty(o);
  ASSERT_EQ(u.used, 4000u);
  const ResultStatistics& s = u.results.at(0);
  const double S0 = s.nominal, sd = S0 * 0.01 / 0.625;
  EXPECT_NEAR(s.linear_sd, sd, 1e-6 * sd);
  EXPECT_NEAR(s.correlation.at(0), 1.0, 1e-12);
  EXPECT_NEAR(s.mean, S0, 4 * sd / std::sqrt(4000.0));
  EXPECT_NEAR(s.sd, sd, 4 * sd / std::sqrt(2 * 4000.0));
  EXPECT_NEAR(s.p50, S0, 4 * 1.2533 * sd / std::sqrt(4000.0));
  EXPECT_NEAR(s.p95 - s.p5, 2 * 1.6449 * sd, 0.05 * 2 * 1.6449 * sd);
}

// A product of independent log-normal factors is log-normal (Aitchison & Brown 1957, §2.6): S ∝ τ η t (forward,
// the point target), so with τ, η, t log-normal of means equal to the file's values and coefficients of variation
// v_i, S has mean S₀, sd S₀ √(Π(1 + v_i²) − 1), median S₀ / √Π(1 + v_i²), and ln S is normal with variance
// s² = Σ ln(1 + v_i²), so its 5/95 % points are the median × exp(∓1.6449 s). Monte Carlo within 4 standard errors.
TEST(Uncertainty, ProductOfLognormalFactorsIsLognormal) {
  UncertaintyOptions o = sbv_options({"optics.transmittance=lognormal(0.56, 0.028)", "detector.qe=lognormal(0.27, 0.027)",
                                      "detector.integration_time=lognormal(0.625 s, 50 ms)"},
                                     {"detector.signal_electrons"}, 20000);
  o.no_solve = true;
  const Uncertainty u = run_uncertainty(o);
  ASSERT_EQ(u.used, 20000u);
  const ResultStatistics& r = u.results.at(0);
  const double S0 = r.nominal;
  double growth = 1, s2 = 0;
  for (double v : {0.05, 0.1, 0.08}) growth *= 1 + v * v, s2 += std::log1p(v * v);
  const double sd = S0 * std::sqrt(growth - 1), median = S0 / std::sqrt(growth), n = 20000;
  EXPECT_NEAR(r.mean, S0, 4 * sd / std::sqrt(n));
  EXPECT_NEAR(r.sd, sd, 0.03 * sd);  // the sample sd's standard error is ~0.6 % here (log-normal kurtosis at s ≈ 0.14)
  const double se_median = 1.2533 * median * std::sqrt(s2) / std::sqrt(n);
  EXPECT_NEAR(r.p50, median, 4 * se_median);
  EXPECT_NEAR(r.p5, median * std::exp(-1.6449 * std::sqrt(s2)), 6 * se_median);
  EXPECT_NEAR(r.p95, median * std::exp(1.6449 * std::sqrt(s2)), 6 * se_median);
}

// The limiting magnitude along SNR = T: m = m₀ + 5 log₁₀(D/D₀) exactly, so for D ~ normal(15 cm, 0.3 cm) the
// magnitude's median is m₀ (the median of D is D₀), its 5/95 % points are m₀ + 5 log₁₀(1 ∓ 1.6449 × 0.02), and
// the linear sd is (5/ln 10) × 0.02.
TEST(Uncertainty, LimitingMagnitudeOverAperture) {
  const Uncertainty u = run_uncertainty(sbv_options({"optics.aperture=normal(15 cm, 3 mm)"}, {"target.magnitude"}, 4000));
  const ResultStatistics& s = u.results.at(0);
  const double linear = 5 / std::numbers::ln10 * 0.02;
  EXPECT_NEAR(s.linear_sd, linear, 1e-6 * linear);
  const double m0 = s.nominal;
  EXPECT_NEAR(m0, 15.5565045, 1e-6);
  const double se = linear / std::sqrt(4000.0);
  EXPECT_NEAR(s.p50, m0, 4 * 1.2533 * se);
  EXPECT_NEAR(s.p5, m0 + 5 * std::log10(1 - 1.6449 * 0.02), 6 * se);
  EXPECT_NEAR(s.p95, m0 + 5 * std::log10(1 + 1.6449 * 0.02), 6 * se);
  EXPECT_NEAR(s.sd, linear, 0.05 * linear);
  EXPECT_GT(s.correlation.at(0), 0.999);
}

// The same seed gives the same output byte for byte, whatever the thread count; another seed another one.
TEST(UncertaintyCli, ReproducibleAcrossSeedsAndThreads) {
  Scratch scratch;
  const std::string base = "uncertainty '" + sbv_file +
                           "' --vary 'optics.transmittance=normal(0.56, 0.02)' --vary 'detector.read_noise=triangular(5 e-, 6 e-, 8 e-)' "
                           "--results target.magnitude,detector.noise_electrons --samples 500 --format csv";
  const CliResult one = run_cli(scratch, base + " --seed 3 --threads 1");
  const CliResult two = run_cli(scratch, base + " --seed 3 --threads 2");
  const CliResult other = run_cli(scratch, base + " --seed 4 --threads 2");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  ASSERT_EQ(two.exit_code, 0) << two.err;
  EXPECT_EQ(one.out, two.out);
  EXPECT_NE(one.out, other.out);
  EXPECT_NE(one.out.find("target.magnitude,detector.read_noise,correlation,"), std::string::npos) << one.out;
  const CliResult text = run_cli(scratch, "uncertainty '" + sbv_file +
                                              "' --vary 'optics.transmittance=uniform(0.5, 0.6)' --results target.magnitude --samples 100");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("linear propagation"), std::string::npos) << text.out;
}

// Samples outside an input's accepted range (τ > 1) are counted and left out, not clamped.
TEST(Uncertainty, OutOfRangeSamplesAreCounted) {
  const Uncertainty u = run_uncertainty(sbv_options({"optics.transmittance=normal(0.99, 0.02)"}, {"target.magnitude"}, 1000));
  EXPECT_GT(u.out_of_range, 200u);  // P(τ > 1) = 1 − Φ(0.5) = 0.31
  EXPECT_LT(u.out_of_range, 420u);
  EXPECT_EQ(u.used + u.out_of_range + u.failed, 1000u);
}

// A distribution far wider than its input's range (τ ~ N(1, 1000) on (0, 1]: P(inside) = 4e-4) leaves no usable
// sample: bad input, one line, exit 2, no table of NaN statistics (it exited 0 with every statistic NaN).
TEST(Uncertainty, NoUsableSampleIsBadInput) {
  Scratch scratch;
  const CliResult r = run_cli(scratch, "uncertainty '" + sbv_file +
                                           "' --vary 'optics.transmittance=normal(1, 1000)' --results target.magnitude --samples 200");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_EQ(count_lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("200 of 200 samples fell outside an input's accepted range, 0 remain"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST(UncertaintyCli, BadInputIsOneLineAndExit2) {
  Scratch scratch;
  const std::string sbv = "uncertainty '" + sbv_file + "' --results target.magnitude ";
  struct Case {
    std::string arguments, expected;
  };
  for (const Case& k : std::vector<Case>{
           {"--vary 'optics.transmittance=gauss(0.56, 0.02)'", "unknown distribution"},
           {"--vary 'optics.aperture=normal(15, 0.3)'", "has no unit"},
           {"--vary 'optics.aperture=normal(15 kg, 0.3 kg)'", "wrong unit"},
           {"--vary 'optics.transmittance=normal(0.56)'", "takes 2 values"},
           {"--vary 'optics.transmittance=normal(0.56, -1)'", "must be > 0"},
           {"--vary 'target.magnitude=normal(15, 1)'", "[[solve]]"},
           {"--vary 'optics.apperture=normal(15 cm, 1 cm)'", "did you mean"},
           {"--vary 'optics.transmittance=normal(0.56, 0.02)' --samples 1", "at least 2"},
           {"--vary 'optics.transmittance=truncated(normal(0.56, 0.02), 0.7, 0.8)'", "holds a probability of"},
           {"--vary 'optics.transmittance=truncated(normal(0.56, 0.02), 0.6, 0.5)'", "needs lo < hi"},
           {"--vary 'optics.transmittance=truncated(normal(0.56, 0.02), 0.5)'", "truncated takes a distribution and two values"},
           {"--vary 'optics.transmittance=truncated(truncated(normal(0.56, 0.02), 0, 1), 0, 1)'", "give one interval"},
           {"--vary 'optics.aperture=truncated(normal(15 cm, 3 mm), 14, 16 cm)'", "has no unit"},
           {"--vary 'optics.transmittance=truncated(normal(0.56, 0.02), 0.5, 0.6'", "expected normal(mean, sd)"},
       }) {
    const CliResult r = run_cli(scratch, sbv + k.arguments);
    EXPECT_EQ(r.exit_code, 2) << k.arguments << "\n" << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << k.arguments << "\n" << r.err;
    EXPECT_NE(r.err.find(k.expected), std::string::npos) << k.arguments << "\n" << r.err;
  }
  // A normal law of 1/K is not a normal law of K: a gain's law is stated in DN/e-.
  const CliResult gain = run_cli(scratch, "uncertainty '" + source_dir + "/sensors/rubin-lsst-r-m5.toml' --results "
                                          "target.magnitude --vary 'detector.gain=normal(1.6 e-/DN, 0.1 e-/DN)'");
  EXPECT_EQ(gain.exit_code, 2) << gain.err;
  EXPECT_EQ(count_lines(gain.err), 1u) << gain.err;
  EXPECT_NE(gain.err.find("stated in DN/e-"), std::string::npos) << gain.err;
}

}  // namespace

namespace {
using namespace radchain;
using namespace radchain::test;

const std::string tolerances_file = source_dir + "/examples/sbv-tolerances.toml";
const char* file_distributions =
    " --vary 'optics.transmittance=normal(0.56, 0.02)' --vary 'detector.qe=normal(0.27, 0.0135)'"
    " --vary 'detector.read_noise=uniform(4 e-, 6 e-)'";

// The file's [uncertainty] is what --vary of the same distributions does, byte for byte; a --vary of a key the
// file varies replaces the file's distribution; without either there is nothing to vary (one line, exit 2).
TEST(UncertaintySection, TheFileTolerancesAreTheSameAsVary) {
  Scratch scratch;
  const std::string tail = " --results target.magnitude --samples 400 --format csv";
  const CliResult from_file = run_cli(scratch, "uncertainty '" + tolerances_file + "'" + tail);
  const CliResult from_vary = run_cli(scratch, "uncertainty '" + sbv_file + "'" + file_distributions + tail);
  ASSERT_EQ(from_file.exit_code, 0) << from_file.err;
  ASSERT_EQ(from_vary.exit_code, 0) << from_vary.err;
  EXPECT_EQ(from_file.out, from_vary.out);

  const CliResult replaced = run_cli(scratch, "uncertainty '" + tolerances_file + "' --vary 'detector.qe=normal(0.27, 0.001)'" + tail);
  const CliResult by_hand = run_cli(scratch, "uncertainty '" + sbv_file +
                                                 "' --vary 'optics.transmittance=normal(0.56, 0.02)' --vary 'detector.qe=normal(0.27, 0.001)'"
                                                 " --vary 'detector.read_noise=uniform(4 e-, 6 e-)'" + tail);
  ASSERT_EQ(replaced.exit_code, 0) << replaced.err;
  EXPECT_EQ(replaced.out, by_hand.out);

  const CliResult nothing = run_cli(scratch, "uncertainty '" + sbv_file + "' --results target.magnitude");
  EXPECT_EQ(nothing.exit_code, 2);
  EXPECT_EQ(count_lines(nothing.err), 1u) << nothing.err;
  EXPECT_NE(nothing.err.find("nothing to vary"), std::string::npos) << nothing.err;
}

// catalogue --uncertainty N: the 5 % and 95 % rows equal `radchain uncertainty`'s percentiles of the same samples
// (seed 1) and bracket the nominal limiting magnitude; files without [uncertainty] get no such rows.
TEST(UncertaintySection, CatalogueShowsTheFivetoNinetyFivePercentBand) {
  Scratch scratch;
  const CliResult cat = run_cli(scratch, "catalogue --format json --uncertainty 400 '" + tolerances_file + "' '" + sbv_file + "'");
  ASSERT_EQ(cat.exit_code, 0) << cat.err;
  const auto rows = nlohmann::json::parse(cat.out)["rows"];
  double p5 = NAN, p95 = NAN, nominal = NAN;
  std::size_t band_rows = 0;
  for (const auto& row : rows) {
    const std::string name = row["result"];
    if (name.find(" @ ") != std::string::npos) {
      ++band_rows;
      EXPECT_EQ(row["sensor"], "sbv-tolerances");
    }
    if (row["sensor"] != "sbv-tolerances") continue;
    if (name == "target.magnitude @ 5 %") p5 = row["computed"].get<double>();
    if (name == "target.magnitude @ 95 %") p95 = row["computed"].get<double>();
    if (name == "target.magnitude") nominal = row["computed"].get<double>();
  }
  EXPECT_EQ(band_rows, 2u);
  EXPECT_LT(p5, nominal);
  EXPECT_GT(p95, nominal);
  const CliResult mc = run_cli(scratch, "uncertainty '" + tolerances_file + "' --results target.magnitude --samples 400 --format json");
  ASSERT_EQ(mc.exit_code, 0) << mc.err;
  double mc_p5 = NAN, mc_p95 = NAN;
  const auto mc_json = nlohmann::json::parse(mc.out);  // kept: a range-for over parse(...)["rows"] would dangle
  for (const auto& row : mc_json["rows"]) {
    if (!row["input"].get<std::string>().empty()) continue;
    const std::string statistic = row["statistic"];
    if (statistic == "p5") mc_p5 = row["value"].get<double>();
    if (statistic == "p95") mc_p95 = row["value"].get<double>();
  }
  EXPECT_NEAR(p5, mc_p5, 1e-4);  // the catalogue prints 6 significant digits
  EXPECT_NEAR(p95, mc_p95, 1e-4);
}

}  // namespace

namespace {
using namespace radchain;
using namespace radchain::test;

// The square-root choice: ⌈√n⌉ bins (5..60) over [min, max], every value counted once, the maximum in the last
// bin; a uniform distribution's bins hold n/bins each within 5 standard deviations of the binomial count.
TEST(UncertaintyHistogram, BinsCountEverySampleOnce) {
  std::vector<double> values;
  const Distribution uniform{Distribution::Kind::uniform, 2, 5, 0};
  for (std::uint64_t k = 0; k < 3600; ++k) values.push_back(uniform.quantile(sample_uniform(7, k, 0)));
  const Histogram h = histogram_of(values);
  ASSERT_EQ(h.counts.size(), 60u);
  ASSERT_EQ(h.edges.size(), 61u);
  EXPECT_DOUBLE_EQ(h.edges.front(), *std::min_element(values.begin(), values.end()));
  EXPECT_NEAR(h.edges.back(), *std::max_element(values.begin(), values.end()), 1e-12);
  std::size_t total = 0;
  for (const std::size_t c : h.counts) {
    total += c;
    EXPECT_NEAR(static_cast<double>(c), 60.0, 5 * std::sqrt(60.0 * (1 - 1.0 / 60)));
  }
  EXPECT_EQ(total, values.size());
  const Histogram one_value = histogram_of({1.0, 1.0, 1.0});  // a 1e-9 wide range, everything in the first bin
  EXPECT_EQ(one_value.counts.size(), 5u);
  EXPECT_EQ(one_value.counts.front(), 3u);
}

// --plot draws a PNG (gnuplot) and writes the same table as without it; a PNG that cannot be written is one
// located line, exit 2, and no table on stdout.
TEST(UncertaintyCli, PlotDrawsTheHistograms) {
  Scratch scratch;
  const std::string base = "uncertainty '" + source_dir + "/examples/sbv-tolerances.toml' --results target.magnitude,detector.snr --samples 300";
  const CliResult plain = run_cli(scratch, base);
  const CliResult plotted = run_cli(scratch, base + " --plot '" + (scratch / "hist.png").string() + "'");
  ASSERT_EQ(plotted.exit_code, 0) << plotted.err;
  EXPECT_EQ(plotted.out, plain.out);
  const std::string png = read_text(scratch / "hist.png");
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  const CliResult bad = run_cli(scratch, base + " --plot '" + (scratch / "no-such-dir" / "h.png").string() + "'");
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_EQ(count_lines(bad.err), 1u) << bad.err;
  EXPECT_TRUE(bad.out.empty()) << bad.out;
}

}  // namespace

// Limiting magnitudes over a grid factored by axis (radchain/batch/factored_grid.hpp): every point against the
// per-point solve and against Pan 2010 eq. (11) by hand, which axes the noise floor is found to depend on, the
// points solved alone (roots outside the bracket, with the per-point failure text), when a grid is not factored and
// why, shards, and random grids around the bundled sensors (the two paths agree to 1e-10).
#include "cli_helpers.hpp"
#include "radchain/batch/factored_grid.hpp"
#include "radchain/batch/sweep.hpp"
#include "radchain/batch/table.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <random>
#include <sstream>

namespace {
using namespace radchain;
using namespace radchain::test;

SweepOptions grid_of(const std::string& file, std::vector<std::pair<std::string, std::string>> axes,
                     std::vector<Override> overrides = {}) {
  SweepOptions options;
  options.sensor_file = file;
  options.axes = std::move(axes);
  options.overrides = std::move(overrides);
  options.results = {"target.magnitude"};
  return options;
}

// Every point of the plan against SweepWorker::evaluate (the per-point solve: closed form checked at the root, or
// bracketing). Returns the number of points the plan left to the per-point path.
std::size_t expect_every_point_matches(const Sweep& sweep, const FactoredGrid& grid, SweepWorker& worker,
                                       double tolerance = 1e-10) {
  const std::size_t n = sweep.columns(), magnitude = n - 1;
  std::vector<double> rows(sweep.points() * n), reference(n);
  std::vector<char> ok(sweep.points());
  grid.evaluate(0, sweep.points(), 1, rows.data(), ok.data());
  std::size_t alone = 0;
  for (std::size_t p = 0; p < sweep.points(); ++p) {
    const bool converged = worker.evaluate(p, reference.data());
    for (std::size_t a = 0; a + 1 < n; ++a) EXPECT_EQ(rows[p * n + a], reference[a]) << "point " << p << " axis " << a;
    if (!ok[p]) {
      ++alone;
      continue;
    }
    EXPECT_TRUE(converged) << sweep.options().sensor_file << " point " << p << ": " << worker.failure();
    EXPECT_NEAR(rows[p * n + magnitude], reference[magnitude], tolerance * std::abs(reference[magnitude]))
        << sweep.options().sensor_file << " point " << p;
  }
  return alone;
}

TEST(FactoredGrid, TheSbvGridAtEveryPointAgainstThePerPointSolveAndPanByHand) {
  const Sweep sweep(grid_of(sbv_file, {{"optics.aperture", "15 cm:30 cm:12"},
                                       {"detector.qe", "0.2:0.8:11"},
                                       {"detector.integration_time", "0.1 s:2 s:10"}}));
  SweepWorker worker(sweep);
  std::string why_not;
  const auto grid = FactoredGrid::plan(sweep, worker, why_not);
  ASSERT_TRUE(grid) << why_not;
  // Dark electrons grow with the exposure; the read and quantisation variances are constants; the SBV has no sky.
  EXPECT_NE(grid->description().find("the noise floor varies with detector.integration_time;"), std::string::npos)
      << grid->description();
  EXPECT_EQ(expect_every_point_matches(sweep, *grid, worker), 0u);

  // Pan 2010 eq. (11) by hand from the file's Table 1 values and one run of the chain for the electrons per unit flux
  // ratio (its spectral integral): m = m₀ − 2.5 lg(S*/S₀·(D₀/D)²(QE₀/QE)(t₀/t)), S* = (T² + √(T⁴ + 4T²c))/2 with
  // c = 18 e⁻/s · t + 6² + 1e5/(2¹² √12) (Pan 2010 §3.2 adds the quantisation term as printed, unsquared).
  Chain chain = load_sensor(sbv_file);
  (void)chain.run();
  const double m0 = chain.result("target.magnitude"), s0 = chain.result("detector.signal_electrons");
  const double per_unit_flux = s0 / std::pow(10.0, -0.4 * m0) / (0.15 * 0.15 * 0.27 * 0.625);
  std::vector<double> row(sweep.columns());
  char ok = 0;
  for (std::size_t p : {0u, 517u, 1319u, 777u}) {
    grid->evaluate(p, 1, 1, row.data(), &ok);
    ASSERT_TRUE(ok);
    const double d = row[0] / 100, qe = row[1], t = row[2];
    const double floor = 18.0 * t + 36.0 + 1e5 / (4096 * std::sqrt(12.0));  // (the quantisation term as Pan prints it)
    const double required = 0.5 * (25.0 + std::sqrt(625.0 + 100.0 * floor));
    const double by_hand = -2.5 * std::log10(required / (per_unit_flux * d * d * qe * t));
    EXPECT_NEAR(row[3], by_hand, 1e-10 * by_hand) << "point " << p;
  }
}

// One long axis of a parameter that declares a power law (the aperture: S ∝ D²): its signal comes from the law, fitted
// at the ends and checked at the quarters, and a point costs a logarithm, not a chain evaluation.
TEST(FactoredGrid, ALongPowerLawAxisTakesItsSignalFromTheLaw) {
  const Sweep sweep(grid_of(sbv_file, {{"optics.aperture", "5 cm:2 m:20000"}}));
  SweepWorker worker(sweep);
  std::string why_not;
  const auto grid = FactoredGrid::plan(sweep, worker, why_not);
  ASSERT_TRUE(grid) << why_not;
  EXPECT_NE(grid->description().find("the noise floor varies with no axis; "), std::string::npos) << grid->description();
  EXPECT_LT(std::stoul(grid->description().substr(grid->description().find("axis; ") + 6)), 20u);  // chain evaluations
  EXPECT_EQ(expect_every_point_matches(sweep, *grid, worker), 0u);
  // m(2 m) − m(5 cm) = 5 lg 40 exactly: S ∝ D², the SBV's floor does not depend on D.
  std::vector<double> first(2), last(2);
  char ok[2];
  grid->evaluate(0, 1, 1, first.data(), &ok[0]);
  grid->evaluate(19999, 1, 1, last.data(), &ok[1]);
  EXPECT_NEAR(last[1] - first[1], 5 * std::log10(40.0), 1e-12);
}

// The floor depends on the dark rate and the read noise but not on the aperture: J = {dark, read}, a 7 × 6 sub-grid.
TEST(FactoredGrid, TheNoiseFloorsAxesAreFoundFromTheChain) {
  const Sweep sweep(grid_of(sbv_file, {{"detector.dark_current", "1 e-/s:100 e-/s:7"},
                                       {"optics.aperture", "10 cm:40 cm:40"},
                                       {"detector.read_noise", "2 e-:20 e-:6"}}));
  SweepWorker worker(sweep);
  std::string why_not;
  const auto grid = FactoredGrid::plan(sweep, worker, why_not);
  ASSERT_TRUE(grid) << why_not;
  EXPECT_NE(grid->description().find("the noise floor varies with detector.dark_current, detector.read_noise;"), std::string::npos)
      << grid->description();
  EXPECT_EQ(expect_every_point_matches(sweep, *grid, worker), 0u);
}

// A sky in the pixel puts every axis of the signal into the floor: nothing to factor, and the method says why.
TEST(FactoredGrid, ASkyInThePixelLeavesEveryPointToItself) {
  const Sweep sweep(grid_of(sbv_file, {{"optics.aperture", "15 cm:30 cm:40"}, {"detector.qe", "0.2:0.8:40"}},
                            {{"detector.sky_brightness", "21"}, {"detector.pixel_pitch", "10 um"}, {"optics.focal_length", "1 m"}}));
  SweepWorker worker(sweep);
  std::string why_not;
  EXPECT_FALSE(FactoredGrid::plan(sweep, worker, why_not));
  EXPECT_NE(why_not.find("the noise floor varies with axes of 1600 points: too many for factoring to pay"), std::string::npos)
      << why_not;
}

// A sky-limited telescope (Rubin r: site sky and seeing, emva1288's pixel-sampled n_eff) puts every axis into the
// floor, and the airmass is spectral: no power law holds. The detector's floor terms (sky, dark, read) each separate
// into per-axis factors, so the grid still factors, and every point agrees with the per-point solve.
TEST(FactoredGrid, ASkyLimitedTelescopeFactorsByItsNoiseSources) {
  const std::string rubin = source_dir + "/sensors/rubin-lsst-r-m5.toml";
  for (const auto& outer : std::vector<std::pair<std::string, std::string>>{
           {"atmosphere.airmass", "1:2:12"}, {"atmosphere.seeing", "0.5 arcsec:1.5 arcsec:12"}}) {
    const Sweep sweep(grid_of(rubin, {outer, {"detector.integration_time", "5 s:60 s:15"},
                                      {"atmosphere.sky_brightness", "19:22:20"}}));
    SweepWorker worker(sweep);
    std::string why_not;
    const auto grid = FactoredGrid::plan(sweep, worker, why_not);
    ASSERT_TRUE(grid) << outer.first << ": " << why_not;
    EXPECT_NE(grid->description().find("the noise floor as a sum of per-axis products (detector.floor_variance_sky, "
                                       "detector.floor_variance_dark, detector.floor_variance_read)"),
              std::string::npos)
        << grid->description();
    EXPECT_EQ(expect_every_point_matches(sweep, *grid, worker), 0u) << outer.first;
  }
  // PRNU grows with the signal (s_g² S²/n_eff): no floor, and the plan says so.
  const Sweep prnu(grid_of(rubin, {{"atmosphere.airmass", "1:2:12"}, {"detector.integration_time", "5 s:60 s:15"},
                                   {"atmosphere.sky_brightness", "19:22:20"}},
                           {{"detector.prnu", "0.01"}}));
  SweepWorker worker(prnu);
  std::string why_not;
  EXPECT_FALSE(FactoredGrid::plan(prnu, worker, why_not));
  EXPECT_NE(why_not.find("atmosphere.airmass is spectral; the detector's floor terms add up to"), std::string::npos) << why_not;
  EXPECT_NE(why_not.find("such as PRNU, is not a floor"), std::string::npos) << why_not;
}

// Every result column of a forward plan against SweepWorker::evaluate (the per-point evaluation), relative.
void expect_every_forward_point_matches(const Sweep& sweep, const FactoredGrid& grid, SweepWorker& worker,
                                        double tolerance = 1e-10) {
  const std::size_t n = sweep.columns(), n_axes = sweep.axes().size();
  std::vector<double> rows(sweep.points() * n), reference(n);
  std::vector<char> ok(sweep.points());
  grid.evaluate(0, sweep.points(), 1, rows.data(), ok.data());
  for (std::size_t p = 0; p < sweep.points(); ++p) {
    ASSERT_TRUE(worker.evaluate(p, reference.data())) << worker.failure();
    EXPECT_TRUE(ok[p]) << "point " << p;
    for (std::size_t c = 0; c < n; ++c)
      EXPECT_NEAR(rows[p * n + c], reference[c], c < n_axes ? 0.0 : tolerance * std::abs(reference[c]))
          << sweep.options().sensor_file << " point " << p << " column " << c;
  }
}

// An EO camera's forward SNR (no [[solve]]): the signal (the surface's electrons ρ E cos θ_s τ k t(roll)) and the
// floor (dark ∝ t, read) are products of per-axis factors, so SNR = S/√(S + c) costs a square root a point; every
// point and every column against the per-point evaluation. PRNU is no floor: refused with the reason.
TEST(FactoredGrid, AnEoCamerasForwardSnrFactorsBySignalAndNoiseSources) {
  const std::string s2 = source_dir + "/sensors/sentinel-2a-msi-b4.toml";
  SweepOptions options = grid_of(s2, {{"platform.roll", "0 deg:20 deg:10"}, {"target.solar_zenith", "20 deg:70 deg:12"},
                                      {"target.reflectance", "0.02:0.6:15"}});
  options.results = {"detector.snr", "detector.signal_electrons", "detector.noise_electrons"};
  const Sweep sweep(options);
  SweepWorker worker(sweep);
  std::string why_not;
  const auto grid = FactoredGrid::plan(sweep, worker, why_not);
  ASSERT_TRUE(grid) << why_not;
  EXPECT_NE(grid->description().find("forward results factored over the grid"), std::string::npos) << grid->description();
  expect_every_forward_point_matches(sweep, *grid, worker);

  options.overrides = {{"detector.prnu", "0.01"}};
  const Sweep prnu(options);
  SweepWorker prnu_worker(prnu);
  EXPECT_FALSE(FactoredGrid::plan(prnu, prnu_worker, why_not));
  EXPECT_NE(why_not.find("such as PRNU, is not a floor"), std::string::npos) << why_not;
}

// The property test for forward plans: random grids around every bundled EO sensor without a [[solve]]; where the
// plan factors, every point and column agree with the per-point evaluation to 1e-10.
TEST(FactoredGrid, RandomForwardGridsAroundTheBundledEoSensorsAgreeWithThePerPointEvaluation) {
  std::mt19937_64 random(20261128);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::size_t factored = 0, tried = 0;
  for (const auto& entry : fs::directory_iterator(std::string(RADCHAIN_SOURCE_DIR) + "/sensors")) {
    const std::string file = entry.path().string();
    Chain chain = load_sensor(file);
    if (!chain.solves.empty() || !chain.results().find("detector.snr")) continue;
    std::vector<std::pair<std::string, std::string>> candidates;
    auto add = [&](const char* key, double lo, double hi, const char* unit) {
      try {
        chain.parameter(key);
        candidates.emplace_back(key, fmt::format("{:.9g}{}:{:.9g}{}", lo, unit, hi, unit));
      } catch (const std::exception&) {
      }
    };
    add("target.reflectance", 0.02 + 0.1 * uniform(random), 0.3 + 0.6 * uniform(random), "");
    add("target.solar_zenith", 10 + 20 * uniform(random), 40 + 40 * uniform(random), " deg");
    add("platform.roll", 0, 5 + 30 * uniform(random), " deg");
    add("optics.transmittance", 0.3 + 0.2 * uniform(random), 0.6 + 0.3 * uniform(random), "");
    add("detector.qe", 0.2 + 0.2 * uniform(random), 0.5 + 0.4 * uniform(random), "");
    if (candidates.size() < 2) continue;
    for (int draw = 0; draw < 2; ++draw) {
      std::shuffle(candidates.begin(), candidates.end(), random);
      const std::size_t n_axes = std::min<std::size_t>(candidates.size(), 2 + draw % 2);
      std::vector<std::pair<std::string, std::string>> axes;
      for (std::size_t a = 0; a < n_axes; ++a)
        axes.emplace_back(candidates[a].first,
                          candidates[a].second + ":" + std::to_string(n_axes == 2 ? 40 + (draw * 7 + a * 5) % 31 : 12 + (draw * 7 + a * 5) % 17));
      SweepOptions options = grid_of(file, axes);
      options.results = {"detector.snr", "detector.noise_electrons"};
      const Sweep sweep(options);
      SweepWorker worker(sweep);
      std::string why_not;
      ++tried;
      const auto grid = FactoredGrid::plan(sweep, worker, why_not);
      if (!grid) {
        std::cout << "not factored: " << entry.path().filename().string() << ": " << why_not << "\n";
        continue;
      }
      ++factored;
      expect_every_forward_point_matches(sweep, *grid, worker);
    }
  }
  std::cout << "factored " << factored << " of " << tried << " random forward grids around the bundled EO sensors\n";
  EXPECT_GT(factored, 0u);
}

TEST(FactoredGrid, GridsThatDoNotFactorSayWhy) {
  auto why = [](SweepOptions options) {
    const Sweep sweep(options);
    SweepWorker worker(sweep);
    std::string why_not;
    EXPECT_FALSE(FactoredGrid::plan(sweep, worker, why_not));
    return why_not;
  };
  const auto axes = std::vector<std::pair<std::string, std::string>>{{"optics.aperture", "15 cm:30 cm:30"},
                                                                     {"detector.integration_time", "0.1 s:2 s:30"}};
  EXPECT_EQ(why(grid_of(sbv_file, {{"optics.aperture", "15 cm:30 cm:100"}})),
            "the grid's 100 points are too few for factoring to pay");
  SweepOptions more = grid_of(sbv_file, axes);
  more.results = {"target.magnitude", "detector.snr"};
  EXPECT_EQ(why(more), "a result other than the solved target.magnitude is read (detector.snr)");
  SweepOptions root = grid_of(sbv_file, axes);
  root.solver = SolverChoice::root;
  EXPECT_EQ(why(root), "--solver root");
  // An Airy PSF's ensquared energy depends on the f-number: ccd_frame then declares no power law of the aperture.
  EXPECT_EQ(why(grid_of(sbv_file, axes, {{"optics.psf", "airy"},
                                         {"optics.psf_wavelength", "0.6 um"},
                                         {"optics.focal_length", "1 m"},
                                         {"detector.pixel_pitch", "10 um"}})),
            "detector (plugin \"ccd_frame\") does not declare power-law results (swept: optics.aperture)");
  SweepOptions diameter = grid_of(std::string(RADCHAIN_SOURCE_DIR) + "/sensors/sbv-smallest-sphere.toml", axes);
  diameter.results = {"target.diameter"};
  EXPECT_EQ(why(diameter), "the solve is not a target's magnitude inverted in closed form through the noise equation");
}

// A bracket that the largest apertures' roots leave: those points are solved alone and fail with the per-point
// solver's text; the sweep's first failure is the first such point.
TEST(FactoredGrid, RootsOutsideTheBracketAreSolvedAloneWithThePerPointText) {
  Scratch scratch;
  const fs::path file = scratch / "narrow.toml";
  write_text(file, sbv_with("bracket = [5, 25]", "bracket = [12, 16.5]"));
  Sweep sweep(grid_of(file.string(), {{"optics.aperture", "5 cm:50 cm:40"}, {"detector.integration_time", "0.1 s:2 s:40"}}));
  SweepWorker worker(sweep);
  std::string why_not;
  const auto grid = FactoredGrid::plan(sweep, worker, why_not);
  ASSERT_TRUE(grid) << why_not;
  const std::size_t alone = expect_every_point_matches(sweep, *grid, worker);
  EXPECT_GT(alone, 100u);
  EXPECT_LT(alone, 1500u);

  std::ostringstream csv;
  TableWriter writer(csv, TableFormat::csv, sweep.layout(), sweep.points());
  std::string failure;
  EXPECT_EQ(sweep.run(writer, &failure), 1);
  writer.finish(1);
  EXPECT_EQ(sweep.method().rfind("closed form factored over the grid", 0), 0u) << sweep.method();
  EXPECT_NE(failure.find(": the solve for target.magnitude failed: criterion \"detection\" has the same sign at both ends "
                         "of the bracket"),
            std::string::npos)
      << failure;
  EXPECT_NE(csv.str().find(",nan\n"), std::string::npos);
}

// A shard's rows are the whole sweep's rows (the plan is the whole grid's, whichever points a shard runs).
TEST(FactoredGrid, AShardsRowsAreTheWholeSweepsRows) {
  auto rows = [](SweepOptions options) {
    Sweep sweep(std::move(options));
    std::ostringstream out;
    TableWriter writer(out, TableFormat::csv, sweep.layout(), sweep.points(), sweep.options().shard, sweep.job());
    std::map<std::size_t, std::vector<double>> seen;
    const std::size_t n = sweep.columns();
    writer.finish(sweep.run(writer, nullptr, [&](std::size_t point, const double* values) {
      seen[point].assign(values, values + n);
    }));
    EXPECT_EQ(sweep.method().rfind("closed form factored over the grid", 0), 0u) << sweep.method();
    return seen;
  };
  const auto axes = std::vector<std::pair<std::string, std::string>>{{"optics.aperture", "15 cm:30 cm:40"},
                                                                     {"detector.integration_time", "0.1 s:2 s:45"}};
  const auto whole = rows(grid_of(sbv_file, axes));
  ASSERT_EQ(whole.size(), 1800u);
  SweepOptions second = grid_of(sbv_file, axes);
  second.shard = ShardSpec{2, 3, ShardSpec::Order::round_robin};
  const auto shard = rows(second);
  ASSERT_EQ(shard.size(), 600u);  // points 1, 4, 7, …
  for (const auto& [point, values] : shard) {
    EXPECT_EQ(point % 3, 1u);
    EXPECT_EQ(values, whole.at(point)) << "point " << point;
  }
}

// The property test for the factored path: random grids (2-3 axes, random ranges) around every bundled
// sensor whose solve is a limiting magnitude; where the plan factors, every point agrees with the per-point solve
// to 1e-10 relative. The SBV always factors; how many others do is printed.
TEST(FactoredGrid, RandomGridsAroundTheBundledSensorsAgreeWithThePerPointSolve) {
  std::mt19937_64 random(20261127);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::size_t factored = 0, tried = 0;
  bool sbv_factored = false;
  for (const auto& entry : fs::directory_iterator(std::string(RADCHAIN_SOURCE_DIR) + "/sensors")) {
    const std::string file = entry.path().string();
    Chain chain = load_sensor(file);
    if (chain.solves.size() != 1 || chain.solves[0].unknown != "target.magnitude") continue;
    // Candidate axes: the numeric parameters of the optics and the detector that a grid would sweep.
    std::vector<std::pair<std::string, double>> candidates;
    for (const char* key : {"optics.aperture", "optics.transmittance", "detector.qe", "detector.integration_time",
                            "detector.dark_current", "detector.read_noise", "atmosphere.airmass", "atmosphere.seeing",
                            "atmosphere.sky_brightness"}) {
      try {
        const ParameterRef p = chain.parameter(key);
        if (p.value() > 0) candidates.emplace_back(key, p.value());
      } catch (const std::exception&) {
      }
    }
    if (candidates.size() < 2) continue;
    for (int draw = 0; draw < 4; ++draw) {
      std::shuffle(candidates.begin(), candidates.end(), random);
      const std::size_t n_axes = std::min<std::size_t>(candidates.size(), 2 + draw % 2);
      // A spectral axis (the airmass) outermost, as a user orders it: the per-point reference then re-runs the
      // spectral phase once per step, not at every point.
      std::stable_partition(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(n_axes),
                            [](const auto& c) { return c.first == "atmosphere.airmass"; });
      std::vector<std::pair<std::string, std::string>> axes;
      for (std::size_t a = 0; a < n_axes; ++a) {
        const auto& [key, value] = candidates[a];
        // A range around the file's value, within the parameter's own range (transmittance and QE at most 1).
        const bool fraction = key == "optics.transmittance" || key == "detector.qe";
        double lo = value * (0.5 + 0.4 * uniform(random));
        double hi = fraction ? std::min(1.0, value * (1.1 + 0.5 * uniform(random))) : value * (1.1 + 2.0 * uniform(random));
        if (key == "atmosphere.airmass") lo = value, hi = value + 0.2 + 1.5 * uniform(random);  // X ≥ 1
        if (key == "atmosphere.sky_brightness") lo = value - 0.5 - 2 * uniform(random), hi = value + 0.2 + uniform(random);
        const Params::Entry& spec = chain.slot(key.substr(0, key.find('.'))).params->entry(key.substr(key.find('.') + 1));
        const std::string unit = spec.spec->type == ParamType::quantity && spec.spec->si_unit != "1" ? " " + spec.spec->si_unit : "";
        // Large enough to pay for a plan: 40-70 steps on two axes, 12-28 on three.
        const std::size_t steps = n_axes == 2 ? 40 + (draw * 7 + a * 5) % 31 : 12 + (draw * 7 + a * 5) % 17;
        axes.emplace_back(key, fmt::format("{:.9g}{}:{:.9g}{}:{}", lo, unit, hi, unit, steps));
      }
      const Sweep sweep(grid_of(file, axes));
      SweepWorker worker(sweep);
      std::string why_not;
      ++tried;
      const auto grid = FactoredGrid::plan(sweep, worker, why_not);
      if (!grid) continue;
      ++factored;
      std::cout << "factored: " << entry.path().filename().string() << " over " << sweep.points() << " points; "
                << grid->description() << "\n";
      sbv_factored = sbv_factored || file == sbv_file;
      expect_every_point_matches(sweep, *grid, worker);
    }
  }
  EXPECT_TRUE(sbv_factored);
  std::cout << "factored " << factored << " of " << tried << " random grids around the bundled sensors\n";
}

TEST(SweepCli, ExplainSaysHowThePointsWereSolved) {
  Scratch scratch;
  const std::string grid = "--set 'optics.aperture=15 cm:30 cm:40' --set 'detector.integration_time=0.1 s:2 s:40' "
                           "--results target.magnitude --out '" + (scratch / "grid.csv").string() + "' --explain";
  const CliResult factored = run_cli(scratch, "sweep '" + sbv_file + "' " + grid);
  EXPECT_EQ(factored.exit_code, 0) << factored.err;
  EXPECT_EQ(factored.err.rfind("radchain sweep: closed form factored over the grid: the noise floor varies with "
                               "detector.integration_time; ",
                               0),
            0u)
      << factored.err;
  EXPECT_EQ(count_lines(factored.err), 1u) << factored.err;
  const std::string root_grid = "--set 'optics.aperture=15 cm:30 cm:40' --set 'detector.integration_time=0.1 s:2 s:40' "
                                "--results target.magnitude --out '" + (scratch / "root.csv").string() + "' --explain";
  const CliResult root = run_cli(scratch, "sweep '" + sbv_file + "' " + root_grid + " --solver root");
  EXPECT_EQ(root.exit_code, 0) << root.err;
  EXPECT_EQ(root.err, "radchain sweep: per point: --solver root\n");
  // Both files hold the same grid; the magnitudes agree to 1e-10 (the bracketing root is within 2^-47 of it).
  std::istringstream a(read_text(scratch / "grid.csv")), b(read_text(scratch / "root.csv"));
  std::string line_a, line_b;
  std::size_t rows = 0;
  std::getline(a, line_a), std::getline(b, line_b);
  EXPECT_EQ(line_a, line_b);  // the header
  while (std::getline(a, line_a) && std::getline(b, line_b)) {
    ++rows;
    const double m_a = std::stod(line_a.substr(line_a.rfind(',') + 1)), m_b = std::stod(line_b.substr(line_b.rfind(',') + 1));
    EXPECT_EQ(line_a.substr(0, line_a.rfind(',')), line_b.substr(0, line_b.rfind(',')));
    EXPECT_NEAR(m_a, m_b, 1e-10 * m_b) << line_a;
  }
  EXPECT_EQ(rows, 1600u);
}

}  // namespace

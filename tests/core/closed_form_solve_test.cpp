// Closed-form solves (solver.cpp) against the bracketing root-finder: both paths must give the same root
// to 1e-10 relative on every bundled sensor and example, on random parameter draws, near the bracket ends, in
// lanes, and the same failure text where no root lies in the bracket. The bracketing solver (TOMS 748 to 2^-47
// relative) is the independent reference: it knows nothing of the declared power laws.
#include "radchain/chain.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

namespace {
using namespace radchain;
namespace fs = std::filesystem;

const std::string source_dir = RADCHAIN_SOURCE_DIR;

std::vector<std::string> files_with_solves() {
  std::vector<std::string> files;
  for (const char* folder : {"/sensors", "/examples"})
    for (const auto& entry : fs::directory_iterator(source_dir + folder))
      if (entry.path().extension() == ".toml" && !load_sensor(entry.path().string()).solves.empty())
        files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

// The same root, or the same failure.
void expect_same(const SolveOutcome& closed, const SolveOutcome& root, const std::string& where) {
  ASSERT_EQ(closed.converged, root.converged) << where << ": " << closed.message << " | " << root.message;
  if (!root.converged) {
    EXPECT_EQ(closed.message, root.message) << where;
    return;
  }
  EXPECT_NEAR(closed.value_si, root.value_si, 1e-10 * std::abs(root.value_si)) << where << " (" << closed.method << ")";
  EXPECT_EQ(closed.binding, root.binding) << where;
}

std::vector<SolveOutcome> solve_with(Chain& chain, SolverChoice choice) {
  chain.solver = choice;
  std::vector<SolveOutcome> outcomes;
  chain.solve_all(outcomes);
  return outcomes;
}

TEST(ClosedFormSolve, EveryBundledSolveAgreesWithTheBracketingSolver) {
  int closed = 0, solves = 0;
  for (const std::string& file : files_with_solves()) {
    Chain a = load_sensor(file), b = load_sensor(file);
    b.solver = SolverChoice::root;
    const Report auto_report = a.run(), root_report = b.run();
    ASSERT_EQ(auto_report.solves.size(), root_report.solves.size());
    for (std::size_t i = 0; i < auto_report.solves.size(); ++i) {
      ++solves;
      expect_same(auto_report.solves[i], root_report.solves[i], file + " " + auto_report.solves[i].spec.unknown);
      EXPECT_EQ(root_report.solves[i].method.rfind("root", 0) == 0 || root_report.solves[i].method == "bracket end", true);
      EXPECT_EQ(root_report.solves[i].fallback, "");  // --solver root is a choice, not a fallback
      if (auto_report.solves[i].method.rfind("closed form", 0) == 0) ++closed;
    }
  }
  // The magnitude solves of the paper sensors and the ground telescope, the sphere's diameter, Kolobrodov's f' and D
  // (energy) are power laws end to end.
  EXPECT_GE(closed, 6) << "of " << solves;
}

TEST(ClosedFormSolve, TheReportSaysWhichPathRanAndWhyNot) {
  const Report sbv = load_sensor(source_dir + "/sensors/msx-sbv.toml").run();
  EXPECT_EQ(sbv.solves[0].method, "closed form (noise equation)");
  EXPECT_EQ(sbv.solves[0].fallback, "");
  EXPECT_EQ(sbv.solves[0].iterations, 1);  // the check at the root (after the faint end, which is not counted)
  // The datasheet camera: its n_eff is a PSF integral over the f-number (not power_law()), but the flux enters
  // linearly (power_law_in_signal()), so a magnitude goes closed form; with PRNU (variance ∝ S²) the noise equation
  // no longer holds, the check at the root says so and the bracketing solver gives the root.
  const std::string rubin = source_dir + "/sensors/rubin-lsst-r-m5.toml";
  const Report m5 = load_sensor(rubin).run();
  EXPECT_EQ(m5.solves[0].method, "closed form (noise equation)");
  EXPECT_EQ(m5.solves[0].iterations, 1);
  Chain with_prnu = load_sensor(rubin, {{"detector.prnu", "0.05"}}), with_prnu_root = load_sensor(rubin, {{"detector.prnu", "0.05"}});
  with_prnu_root.solver = SolverChoice::root;
  const Report prnu = with_prnu.run(), prnu_root = with_prnu_root.run();
  EXPECT_EQ(prnu.solves[0].method, "root (TOMS 748)");
  EXPECT_EQ(prnu.solves[0].fallback.rfind("the closed form's root ", 0), 0u) << prnu.solves[0].fallback;
  EXPECT_NEAR(prnu.solves[0].value_si, prnu_root.solves[0].value_si, 1e-10 * prnu_root.solves[0].value_si);
  EXPECT_GT(prnu.solves[0].value_si, m5.solves[0].value_si - 0.2);  // PRNU costs a bright-limited m5 little
  const Report eo = load_sensor(source_dir + "/examples/eo-design-niirs5.toml").run();
  EXPECT_EQ(eo.solves[1].method, "root (TOMS 748)");  // NIIRS is not a power law of D
  EXPECT_EQ(eo.solves[1].fallback, "criteria.quality (plugin \"giqe\") declares no closed-form inverse");
}

// Random designs around five sensors: every numeric optics/detector/target parameter scaled by a log-normal factor
// (σ = 0.3), kept inside its schema range. Each draw is solved both ways, also with the bracket shrunk to 1e-7 around
// the root on either side and moved entirely past it (no solution: the same failure text).
TEST(ClosedFormSolve, RandomDrawsAgreeIncludingBracketEdgesAndNoSolution) {
  std::mt19937_64 random(20261123);
  std::lognormal_distribution<double> factor(0.0, 0.3);
  int draws = 0, closed = 0;
  for (const char* name : {"/sensors/msx-sbv.toml", "/sensors/sbv-smallest-sphere.toml", "/examples/ground-telescope-geo.toml",
                           "/sensors/kolobrodov-1996-ccd151.toml", "/sensors/rubin-lsst-r-m5.toml"}) {
    const std::string file = source_dir + name;
    for (int draw = 0; draw < 60; ++draw) {
      Chain chain = load_sensor(file);
      for (StageSlot& slot : chain.stages) {
        if (slot.section != "optics" && slot.section != "detector" && slot.section != "target") continue;
        for (const Params::Entry& entry : slot.params->entries()) {
          const ParamType type = entry.spec->type;
          if (!entry.present || entry.spec->spectral || type != ParamType::quantity) continue;
          const std::string key = slot.section + "." + entry.spec->key;
          const double value = chain.parameter(key).value() * factor(random);
          if (entry.spec->in_range(value)) chain.set(key, value);
        }
      }
      const std::string where = std::string(name) + " draw " + std::to_string(draw);
      const std::vector<SolveOutcome> root = solve_with(chain, SolverChoice::root);
      const std::vector<SolveOutcome> closed_form = solve_with(chain, SolverChoice::automatic);
      for (std::size_t i = 0; i < root.size(); ++i) {
        expect_same(closed_form[i], root[i], where);
        closed += closed_form[i].method.rfind("closed form", 0) == 0;
      }
      ++draws;
      // The first solve's bracket around its root: just above, just below, and past it.
      if (!root[0].converged || chain.solves.size() != 1) continue;
      const double x = root[0].value_si, lo = chain.solves[0].lo, hi = chain.solves[0].hi;
      for (const auto& [new_lo, new_hi] : {std::pair{x * (1 - 1e-7), hi}, std::pair{lo, x * (1 + 1e-7)},
                                           std::pair{lo + 0.5 * (x - lo), x - 0.25 * (x - lo)}}) {
        chain.solves[0].lo = std::min(new_lo, new_hi), chain.solves[0].hi = std::max(new_lo, new_hi);
        expect_same(solve_with(chain, SolverChoice::automatic)[0], solve_with(chain, SolverChoice::root)[0],
                    where + " bracket [" + std::to_string(chain.solves[0].lo) + ", " + std::to_string(chain.solves[0].hi) + "]");
      }
    }
  }
  EXPECT_EQ(draws, 300);
  EXPECT_GE(closed, 250);  // most draws take the closed form (Kolobrodov's f' solve too)
}

TEST(ClosedFormSolve, LanesAgreeWithTheBracketingLanes) {
  Chain chain = load_sensor(source_dir + "/sensors/msx-sbv.toml");
  (void)chain.run();
  const ParameterRef aperture = chain.parameter("optics.aperture");
  Lanes d;
  for (int i = 0; i < lane_count; ++i) d(i) = 0.05 + 0.05 * i;
  chain.set_lanes(aperture, d);
  LaneSolveOutcome closed, root;
  chain.solver = SolverChoice::automatic;
  chain.solve_lanes(closed);
  chain.solver = SolverChoice::root;
  chain.solve_lanes(root);
  EXPECT_EQ(closed.closed_form, lane_count);
  EXPECT_EQ(root.closed_form, 0);
  // A magnitude through the noise equation: the faint end and the check at the roots (the two-end form took three
  // passes, the bracketing eleven).
  EXPECT_EQ(closed.passes, 2);
  EXPECT_LT(closed.passes, root.passes);
  for (int i = 0; i < lane_count; ++i) {
    ASSERT_TRUE(closed.converged[i] && root.converged[i]) << i;
    EXPECT_NEAR(closed.value(i), root.value(i), 1e-10 * std::abs(root.value(i))) << "lane " << i;
  }
}

}  // namespace

// A lane group whose roots leave the bracket on both sides (apertures from 1 mm to 40 m: the limiting magnitude runs
// from below 6 to above 30): the lanes with a root take the one-end closed form, the others fall back to both ends
// and fail with the bracketing lanes' text, lane by lane, and the two paths agree where a root exists.
TEST(ClosedFormSolve, LanesWithAndWithoutARootInTheBracket) {
  Chain chain = load_sensor(source_dir + "/sensors/msx-sbv.toml");
  (void)chain.run();
  const double lo = chain.solves[0].lo, hi = chain.solves[0].hi;
  Lanes d;
  const double apertures[lane_count] = {0.001, 0.15, 40.0, 0.3, 0.0005, 1.0, 80.0, 0.05};
  for (int i = 0; i < lane_count; ++i) d(i) = apertures[i];
  chain.set_lanes(chain.parameter("optics.aperture"), d);
  LaneSolveOutcome closed, root;
  chain.solver = SolverChoice::automatic;
  chain.solve_lanes(closed);
  chain.solver = SolverChoice::root;
  chain.solve_lanes(root);
  int with_root = 0;
  for (int i = 0; i < lane_count; ++i) {
    ASSERT_EQ(closed.converged[i], root.converged[i]) << "lane " << i << ": " << closed.message[i] << " | " << root.message[i];
    if (!root.converged[i]) {
      EXPECT_EQ(closed.message[i], root.message[i]) << "lane " << i;
      EXPECT_NE(root.message[i].find("no solution in"), std::string::npos) << root.message[i];
      continue;
    }
    ++with_root;
    EXPECT_GE(root.value(i), lo);
    EXPECT_LE(root.value(i), hi);
    EXPECT_NEAR(closed.value(i), root.value(i), 1e-10 * std::abs(root.value(i))) << "lane " << i;
  }
  EXPECT_EQ(closed.closed_form, with_root);
  EXPECT_GE(with_root, 3);
  EXPECT_LE(with_root, lane_count - 3);  // the group mixes both kinds (else the test tests less than it says)
}

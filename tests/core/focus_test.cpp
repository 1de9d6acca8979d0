// Chain::focus: a chain asked for some results only leaves out the stages none of them needs (later stages, and
// criteria nobody asked for and no [[solve]] drives), and gives those results exactly as the whole chain does —
// over every bundled sensor, after a change of parameter and through its solves; focus({}) gives everything back.
#include "radchain/chain.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace {
using namespace radchain;

// The same double, NaN included (a result not evaluated is NaN in both).
bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

std::vector<ResultId> declared_by(const Chain& chain, const std::string& section) {
  std::vector<ResultId> ids;
  for (const StageSlot& s : chain.stages)
    if (s.section == section)
      for (const StageMemo::Declared& d : s.memo.declarations) ids.push_back(d.id);
  return ids;
}

// The detector's first real-valued, non-spectral parameter that the file states (an exposure, a QE, a read noise): what
// a sweep of the detector would change.
std::string detector_parameter(Chain& chain) {
  for (auto& e : chain.slot("detector").params->entries())
    if (e.present && !e.spec->spectral && (e.spec->type == ParamType::quantity || e.spec->type == ParamType::number) &&
        e.number > 0)
      return "detector." + e.spec->key;
  return {};
}

void solve_or_evaluate(Chain& chain) {
  std::vector<SolveOutcome> outcomes;
  if (chain.solves.empty()) chain.evaluate();
  else chain.solve_all(outcomes);
}

TEST(Focus, TheAskedResultsAreTheWholeChainsOnEveryBundledSensor) {
  int sensors = 0, with_skips = 0;
  for (const auto& entry : std::filesystem::directory_iterator(RADCHAIN_SOURCE_DIR "/sensors")) {
    if (entry.path().extension() != ".toml") continue;
    const std::string file = entry.path().string();
    SCOPED_TRACE(file);
    Chain whole = load_sensor(file), focused = load_sensor(file);
    whole.run();
    focused.run();
    const std::string key = detector_parameter(whole);
    if (key.empty()) continue;
    ++sensors;
    std::vector<ResultId> asked = declared_by(focused, "detector");
    focused.focus(asked);
    bool skipped = false;
    for (std::size_t k = 0; k < focused.stages.size(); ++k) {
      skipped = skipped || focused.skips(k);
      // A criterion a [[solve]] drives is never left out.
      if (!focused.skips(k)) continue;
      for (const SolveSpec& s : focused.solves)
        for (const std::string& c : s.criteria) EXPECT_NE(focused.stages[k].section, "criteria." + c);
    }
    with_skips += skipped ? 1 : 0;
    for (const double factor : {0.9, 0.95}) {
      const double value = whole.parameter(key).value() * factor;
      whole.set(key, value);
      focused.set(key, value);
      solve_or_evaluate(whole);
      solve_or_evaluate(focused);
      for (ResultId id : asked)
        EXPECT_TRUE(same_bits(focused.results().value(id), whole.results().value(id)))
            << focused.results().info(id).name << " at " << key << " = " << value;
      for (const SolveSpec& s : whole.solves)
        EXPECT_TRUE(same_bits(focused.parameter(s.unknown).value(), whole.parameter(s.unknown).value())) << s.unknown;
    }
    // Unfocused again: every result is the whole chain's.
    focused.focus({});
    solve_or_evaluate(focused);
    for (ResultId id = 0; id < whole.results().size(); ++id)
      EXPECT_TRUE(same_bits(focused.results().value(id), whole.results().value(id))) << whole.results().info(id).name;
  }
  EXPECT_GE(sensors, 30);
  EXPECT_GE(with_skips, 15);  // 18 of the 33 have a criterion that a detector result does not need
}

// The Earth-observation camera's GIQE criterion is left out of a sweep of the detector's SNR, and nothing else is.
TEST(Focus, AnSnrSweepLeavesTheImageQualityCriterionOut) {
  Chain chain = load_sensor(RADCHAIN_SOURCE_DIR "/sensors/sentinel-2a-msi-b4.toml");
  chain.focus({*chain.results().find("detector.snr")});
  for (std::size_t k = 0; k < chain.stages.size(); ++k)
    EXPECT_EQ(chain.skips(k), chain.stages[k].section.starts_with("criteria.")) << chain.stages[k].section;
  // Asked for the NIIRS, the GIQE criterion runs and the GSD criterion does not.
  chain.focus({*chain.results().find("criteria.iq.niirs")});
  for (std::size_t k = 0; k < chain.stages.size(); ++k)
    EXPECT_EQ(chain.skips(k), chain.stages[k].section == "criteria.gsd") << chain.stages[k].section;
}

}  // namespace

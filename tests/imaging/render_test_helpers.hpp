#pragma once
// Shared by tests/render: the bundled sensors, run once per test.
#include "radchain/chain.hpp"

#include <string>
#include <vector>

namespace radchain::render_tests {

inline std::string sensor_path(const std::string& name) { return std::string(RADCHAIN_SOURCE_DIR) + "/sensors/" + name; }

struct Loaded {
  Chain chain;
  Report report;
};

inline Loaded load(const std::string& name, const std::vector<Override>& overrides = {}) {
  Loaded l{load_sensor(sensor_path(name), overrides), {}};
  l.report = l.chain.run();
  return l;
}

// The SBV with a fine ADC and the EMVA quantisation noise (the renderer's ADC is a uniform quantiser, so the
// chain's budget describes the frame; with the paper's printed form and 24 e-/DN it does not: docs/rendering.md).
inline Loaded sbv_fine_adc() {
  return load("msx-sbv.toml", {{"detector.quantisation", "emva"}, {"detector.adc_bits", "16"}});
}

}  // namespace radchain::render_tests

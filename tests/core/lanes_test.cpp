// Lanes (radchain/lanes.hpp) against the scalar phase: for every bundled sensor and example, every numeric
// non-spectral parameter is given eight different values at once; each lane's every result must equal what the
// scalar evaluate() gives at that lane's value. Stages with a lane form (point_magnitude, telescope, ccd_frame,
// snr_threshold) and those without (evaluated lane by lane) are both covered. Tolerance: 1e-13 relative (the lane
// exponential is Eigen's, the scalar one glibc's; everything else is the same arithmetic).
#include "radchain/chain.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace {
using namespace radchain;
namespace fs = std::filesystem;

std::vector<std::string> sensor_files() {
  std::vector<std::string> files;
  for (const char* folder : {"/sensors", "/examples"})
    for (const auto& entry : fs::directory_iterator(std::string(RADCHAIN_SOURCE_DIR) + folder))
      if (entry.path().extension() == ".toml") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

bool same(double lane, double scalar) {
  if (std::isnan(scalar)) return std::isnan(lane);
  return std::abs(lane - scalar) <= 1e-13 * std::abs(scalar) + 1e-300;
}

TEST(Lanes, EveryResultOfEveryLaneEqualsTheScalarPhase) {
  int parameters = 0, comparisons = 0;
  for (const std::string& file : sensor_files()) {
    Chain chain = load_sensor(file);
    (void)chain.run();  // the solved unknowns: a realistic operating point
    for (StageSlot& slot : chain.stages) {
      for (const Params::Entry& entry : slot.params->entries()) {
        const ParamType type = entry.spec->type;
        if (!entry.present || entry.spec->spectral || (type != ParamType::quantity && type != ParamType::number)) continue;
        const std::string key = slot.section + "." + entry.spec->key;
        const ParameterRef parameter = chain.parameter(key);
        if (parameter.spectral()) continue;  // spectral in this chain: a later spectral phase reads a result of it
        const double base = parameter.value();
        Lanes values;
        for (int i = 0; i < lane_count; ++i) values(i) = base * (1.0 - 0.004 * i);  // inside any range that holds base
        chain.clear_lanes();
        chain.set_lanes(parameter, values);
        chain.evaluate_lanes(Detail::full);
        std::vector<Lanes> lanes(chain.results().size());
        for (ResultId id = 0; id < lanes.size(); ++id) lanes[id] = chain.lane_result(id);
        for (int i = 0; i < lane_count; ++i) {
          chain.set(parameter, values(i));
          chain.evaluate();
          for (ResultId id = 0; id < lanes.size(); ++id) {
            ++comparisons;
            EXPECT_PRED2(same, lanes[id](i), chain.results().value(id))
                << file << ": " << key << " lane " << i << " = " << values(i) << ", result " << chain.results().info(id).name;
          }
        }
        chain.set(parameter, base);
        ++parameters;
      }
    }
    chain.clear_lanes();
  }
  EXPECT_GT(parameters, 60);
  RecordProperty("comparisons", comparisons);
}

TEST(Lanes, TwoParametersVaryTogether) {
  Chain chain = load_sensor(std::string(RADCHAIN_SOURCE_DIR) + "/sensors/msx-sbv.toml");
  const ParameterRef aperture = chain.parameter("optics.aperture"), magnitude = chain.parameter("target.magnitude");
  Lanes d, m;
  for (int i = 0; i < lane_count; ++i) d(i) = 0.15 + 0.02 * i, m(i) = 14.0 + 0.5 * i;
  chain.set_lanes(aperture, d);
  chain.set_lanes(magnitude, m);
  chain.evaluate_lanes();
  const ResultId snr = *chain.results().find("detector.snr");
  const ResultId margin = *chain.results().find("criteria.detection.margin");
  for (int i = 0; i < lane_count; ++i) {
    chain.set(aperture, d(i));
    chain.set(magnitude, m(i));
    chain.evaluate();
    EXPECT_PRED2(same, chain.lane_result(snr)(i), chain.results().value(snr)) << "lane " << i;
    EXPECT_PRED2(same, chain.lane_result(margin)(i), chain.results().value(margin)) << "lane " << i;
  }
  // The SNR grows with the aperture and falls with the magnitude: lane 0 (15 cm, m 14) against lane 7 differ.
  EXPECT_NE(chain.lane_result(snr)(0), chain.lane_result(snr)(7));
}

TEST(Lanes, ASpectralParameterCannotDifferBetweenLanes) {
  Chain chain = load_sensor(std::string(RADCHAIN_SOURCE_DIR) + "/sensors/msx-sbv.toml");
  EXPECT_THROW(chain.set_lanes(chain.parameter("detector.band_max"), Lanes::Constant(0.9e-6)), std::logic_error);
}

}  // namespace

// Swift UVOT's count-rate zero points in the AB system, through the same files the catalogue checks in the Vega
// system (sensors/swift-uvot-*-zero-point.toml): the file's target switched to a flat-f_ν source of the AB system.
// The reference is the published table (Swift UVOT digest "Zero Points", 2011; Breeveld et al. 2011), with the
// table's own errors as tolerances. The AB-minus-Vega difference also checks the Vega spectrum through each curve.
#include "radchain/chain.hpp"
#include "radchain/sensor_file.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>
#include <utility>

namespace {

struct Band {
  const char* file;
  double vega, ab, error;  // published zero points and their error (mag)
};

TEST(CountRateZeroPoints, SwiftUvotInTheAbSystem) {
  for (const Band& b : {Band{"swift-uvot-v-zero-point.toml", 17.89, 17.88, 0.01}, Band{"swift-uvot-b-zero-point.toml", 19.11, 18.98, 0.02},
                        Band{"swift-uvot-u-zero-point.toml", 18.34, 19.36, 0.02},
                        Band{"swift-uvot-uvw1-zero-point.toml", 17.44, 18.95, 0.03}}) {
    const std::string path = std::string(RADCHAIN_SOURCE_DIR) + "/sensors/" + b.file;
    radchain::Chain vega = radchain::load_sensor(path);
    const double zp_vega = vega.run().value("detector.instrumental_zero_point").value();
    // The same file with a flat-f_ν source in the AB system instead of a Vega-like one in the Vega system.
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const auto& [from, to] : {std::pair<std::string, std::string>{"system = \"vega\"", "system = \"ab\""},
                                   {"sed = \"vega_alpha_lyr_stis_002.csv\"", "sed_shape = \"flat_f_nu\""}}) {
      const auto at = text.find(from);
      ASSERT_NE(at, std::string::npos) << b.file << ": " << from;
      text.replace(at, from.size(), to);
    }
    radchain::Chain ab = radchain::load_sensor_text(text, path);
    const double zp_ab = ab.run().value("detector.instrumental_zero_point").value();
    EXPECT_NEAR(zp_vega, b.vega, b.error) << b.file;
    EXPECT_NEAR(zp_ab, b.ab, b.error) << b.file;
    // The published AB − Vega column (V −0.01, B −0.13, U +1.02, UVW1 +1.51) to its rounding.
    EXPECT_NEAR(zp_ab - zp_vega, b.ab - b.vega, 0.011) << b.file;
  }
}

}  // namespace

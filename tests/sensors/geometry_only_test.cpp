// Geometry-only sensor files: without [source], [atmosphere] and [target] a chain evaluates
// everything that needs no light (GSD, swath, MTF, NIIRS at a given SNR); a stage that needs light refuses with
// one located line naming the missing [source]. A file with some light sections must have all three.
#include "radchain/chain.hpp"
#include "radchain/error.hpp"
#include "radchain/sensor_file.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

namespace {

const std::string sensors = std::string(RADCHAIN_SOURCE_DIR) + "/sensors/";

std::string text_of(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The text with the section [name] (up to the next section header) removed.
std::string without_section(std::string text, const std::string& name) {
  const auto at = text.find("\n[" + name + "]\n");
  if (at == std::string::npos) return text;
  const auto next = text.find("\n[", at + 1);
  return text.erase(at, next == std::string::npos ? std::string::npos : next - at);
}

std::string error_of(const std::string& text, const std::string& path) {
  try {
    radchain::load_sensor_text(text, path);
  } catch (const radchain::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(GeometryOnlySensor, RunsWithoutLightSections) {
  // WorldView-2 pan at nadir: the bundled file has no [source], [atmosphere] or [target].
  const std::string path = sensors + "worldview-2-pan.toml";
  const std::string text = text_of(path);
  ASSERT_EQ(text.find("[source]"), std::string::npos);
  ASSERT_EQ(text.find("[target]"), std::string::npos);
  radchain::Chain chain = radchain::load_sensor(path);
  for (const auto& slot : chain.stages) {
    EXPECT_NE(slot.section, "source");
    EXPECT_NE(slot.section, "target");
    EXPECT_NE(slot.section, "atmosphere");
  }
  const radchain::Report report = chain.run();
  EXPECT_TRUE(report.all_passed());
  // Pixel-pitch GSD at nadir h p / f' (Schowengerdt 2007 §3.3) from the file's 770 km, 8 µm, 13.3 m.
  EXPECT_NEAR(report.value("criteria.gsd.gsd_nadir").value(), 770e3 * 8e-6 / 13.3, 1e-9);
  EXPECT_TRUE(report.value("criteria.iq.niirs").has_value());
}

TEST(GeometryOnlySensor, ARadiometricStageWithoutLightGetsALocatedError) {
  // The Kolobrodov camera without its light: ccd_line needs a focal-plane irradiance.
  std::string text = text_of(sensors + "kolobrodov-1996-ccd151.toml");
  for (const char* section : {"source", "atmosphere", "target"}) text = without_section(text, section);
  text = text.substr(0, text.find("[[solve]]"));  // the energy solve would need the light as well
  int detector_line = 1;
  for (std::size_t i = 0; i < text.find("[detector]"); ++i) detector_line += text[i] == '\n';
  const std::string message = error_of(text, "no-light.toml");
  EXPECT_EQ(message.rfind("no-light.toml:" + std::to_string(detector_line) + ":", 0), 0u) << message;
  EXPECT_NE(message.find("detector (plugin \"ccd_line\")"), std::string::npos) << message;
  EXPECT_NE(message.find("no [source] section"), std::string::npos) << message;
}

TEST(GeometryOnlySensor, SomeLightSectionsNeedTheOthers) {
  const std::string text = without_section(text_of(sensors + "kolobrodov-1996-ccd151.toml"), "target");
  const std::string message = error_of(text, "no-target.toml");
  EXPECT_NE(message.find("[target]: missing section"), std::string::npos) << message;
  EXPECT_NE(message.find("a file with light has atmosphere, target (and source when the target reflects it"), std::string::npos) << message;
}

}  // namespace

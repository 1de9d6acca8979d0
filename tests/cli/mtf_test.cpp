// `radchain mtf`: the Kolobrodov design's MTF curves as CSV (and the exit code of a sensor without them).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

int run_cli(const std::string& arguments) {
  const int status = std::system((std::string(RADCHAIN_CLI) + " " + arguments + " 2>/dev/null").c_str());
  return WEXITSTATUS(status);
}

TEST(MtfCli, WritesTheFourCurves) {
  const auto csv = std::filesystem::temp_directory_path() / "radchain_mtf_test.csv";
  ASSERT_EQ(run_cli("mtf " RADCHAIN_SOURCE_DIR "/sensors/kolobrodov-1996-ccd151-computed.toml --out " + csv.string()), 0);
  std::ifstream in(csv);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("frequency_mm-1,diffraction,objective_eq7,detector_eq8,system_eq10\n0,1.000000,1.000000,"
                            "1.000000,1.000000\n"),
            std::string::npos);
  std::filesystem::remove(csv);
}

TEST(MtfCli, ASensorWithoutADesignIsBadInput) {
  EXPECT_EQ(run_cli("mtf " RADCHAIN_SOURCE_DIR "/sensors/msx-sbv.toml"), 2);
}

}  // namespace

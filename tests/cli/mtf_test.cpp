// `radchain mtf`: the Kolobrodov design's MTF curves as CSV (and the exit code of a sensor without them).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

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

TEST(MtfCli, WritesTheBudgetOfAnEarthObservationCamera) {
  // WorldView-2 pan (geometry only, giqe criterion): every component and the system; the comment names Nyquist
  // 1/(2 × 8 µm) = 62.5 mm⁻¹, and its row is diffraction (Goodman, x = λNν) × pixel 2/π.
  const auto csv = std::filesystem::temp_directory_path() / "radchain_mtf_budget_test.csv";
  ASSERT_EQ(run_cli("mtf " RADCHAIN_SOURCE_DIR "/sensors/worldview-2-pan.toml --out " + csv.string()), 0);
  std::ifstream in(csv);
  std::stringstream text;
  text << in.rdbuf();
  std::filesystem::remove(csv);
  EXPECT_NE(text.str().find("frequency_mm-1,diffraction,pixel,jitter,smear,diffusion,wavefront,tdi,atmosphere,system\n0,1.000000,"),
            std::string::npos);
  EXPECT_NE(text.str().find("# Nyquist 1/(2p) = 62.5 mm-1: system MTF"), std::string::npos);
  const auto row = text.str().find("\n62.5,");
  ASSERT_NE(row, std::string::npos);
  const double x = 625e-9 * (13.3 / 1.1) * 62.5e3, pi = 3.14159265358979323846;
  const double diffraction = 2 / pi * (std::acos(x) - x * std::sqrt(1 - x * x));
  std::stringstream fields(text.str().substr(row + 1, text.str().find('\n', row + 1) - row - 1));
  std::vector<double> v;
  for (std::string field; std::getline(fields, field, ',');) v.push_back(std::stod(field));
  ASSERT_EQ(v.size(), 10u);
  EXPECT_NEAR(v[1], diffraction, 1e-6);
  EXPECT_NEAR(v[2], 2 / pi, 1e-6);
  EXPECT_NEAR(v[8], 1.0, 1e-12);  // no turbulence term in the file
  EXPECT_NEAR(v[9], diffraction * 2 / pi, 2e-6);
}

// The budget's plot: every curve in one panel (PNG 1000 × 620: one panel, where a panel per curve was 2620 tall),
// Nyquist marked; --log draws the MTF axis logarithmic. gnuplot draws either; both are PNGs of the same size.
TEST(MtfCli, BudgetPlotIsOnePanelLinearOrLog) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot is not installed";
  const auto dir = std::filesystem::temp_directory_path();
  for (const char* log : {"", " --log"}) {
    const auto png = dir / (std::string("radchain_mtf_plot") + (*log ? "_log" : "") + ".png");
    ASSERT_EQ(run_cli("mtf " RADCHAIN_SOURCE_DIR "/sensors/worldview-2-pan.toml --out /dev/null --plot " + png.string() + log), 0);
    std::ifstream in(png, std::ios::binary);
    std::string head(24, '\0');
    in.read(head.data(), 24);
    std::filesystem::remove(png);
    ASSERT_EQ(head.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << log;
    auto be32 = [&](std::size_t at) {
      return (static_cast<unsigned>(static_cast<unsigned char>(head[at])) << 24) | (static_cast<unsigned char>(head[at + 1]) << 16) |
             (static_cast<unsigned char>(head[at + 2]) << 8) | static_cast<unsigned char>(head[at + 3]);
    };
    EXPECT_EQ(be32(16), 1000u) << log;  // IHDR width
    EXPECT_EQ(be32(20), 620u) << log;   // IHDR height: one panel
  }
  EXPECT_NE(run_cli("mtf " RADCHAIN_SOURCE_DIR "/sensors/worldview-2-pan.toml --out /dev/null --log --plot /nonexistent/dir/x.png"), 0);
}

TEST(MtfCli, ASensorWithoutADesignIsBadInput) {
  EXPECT_EQ(run_cli("mtf " RADCHAIN_SOURCE_DIR "/sensors/msx-sbv.toml"), 2);
}

}  // namespace

// `radchain render` / `validate` through the CLI: files written, exit codes (the rendering itself is tested in tests/render).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

int run_cli(const std::string& arguments) {
  const int status = std::system((std::string(RADCHAIN_CLI) + " " + arguments + " >/dev/null 2>&1").c_str());
  return WEXITSTATUS(status);
}

TEST(RenderCli, SpaceFrameWritesFitsAndPreview) {
  const auto dir = std::filesystem::temp_directory_path() / "radchain_render_cli";
  std::filesystem::create_directories(dir);
  const std::string fits = (dir / "sbv.fits").string(), png = (dir / "sbv.png").string();
  EXPECT_EQ(run_cli("render " RADCHAIN_SOURCE_DIR "/sensors/msx-sbv.toml --focal-length \"45 cm\" --pixel-pitch \"27 um\""
                    " --width 64 --height 64 --stars 5 --seed 3 --out " + fits + " --png " + png),
            0);
  EXPECT_GT(std::filesystem::file_size(fits), 2880u);  // at least one FITS block
  EXPECT_TRUE(std::filesystem::exists(png));
  std::filesystem::remove_all(dir);
}

TEST(RenderCli, EarthSceneAsFloatTiffAndBadExtension) {
  const auto tif = std::filesystem::temp_directory_path() / "radchain_render_cli_scene.tif";
  EXPECT_EQ(run_cli("render " RADCHAIN_SOURCE_DIR "/sensors/kolobrodov-1996-ccd151-computed.toml --out " + tif.string()), 0);
  EXPECT_GT(std::filesystem::file_size(tif), 10000u);  // a 256×256 float32 scene at the designed 5 m GSD (compressed)
  std::filesystem::remove(tif);
  EXPECT_EQ(run_cli("render " RADCHAIN_SOURCE_DIR "/sensors/kolobrodov-1996-ccd151-computed.toml --out /tmp/x.jpg"), 2);
}

TEST(RenderCli, BadQuantityIsBadInput) {
  EXPECT_EQ(run_cli("render " RADCHAIN_SOURCE_DIR "/sensors/msx-sbv.toml --focal-length 45 --pixel-pitch \"27 um\""), 2);
}

}  // namespace

// radchain/input_file.hpp: inputs are remembered so that an output naming one is refused, and a file that later
// takes a deleted input's place (its name, perhaps its inode) is not mistaken for it; oversized and non-regular
// files are refused before they are read.
#include "radchain/input_file.hpp"

#include "radchain/error.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

namespace {
using namespace radchain;
namespace fs = std::filesystem;

TEST(InputFile, AnInputIsKnownUntilAnotherFileTakesItsPlace) {
  const fs::path folder = fs::temp_directory_path() / ("radchain_input_file_test_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  const fs::path input = folder / "sensor.toml", other = folder / "other.csv";
  std::ofstream(input) << "[sensor]\n";
  std::ofstream(other) << "x\n";
  EXPECT_EQ(read_input_file(input.string(), "sensor file", max_sensor_file_bytes), "[sensor]\n");
  EXPECT_EQ(input_file_kind(input.string()), "sensor file");
  EXPECT_EQ(input_file_kind(other.string()), "");  // never read
  // Deleted and written again (often on the same inode): a new file, not the input. (The status-change time moves
  // by the kernel's clock tick, a few ms.)
  fs::remove(input);
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::ofstream(input) << "[sensor]\nname = \"new\"\n";
  EXPECT_EQ(input_file_kind(input.string()), "");
  EXPECT_THROW(read_input_file(input.string(), "sensor file", 4), InputError);  // larger than 4 bytes
  EXPECT_THROW(read_input_file(folder.string(), "sensor file", max_sensor_file_bytes), InputError);  // a folder
  fs::remove_all(folder);
}

}  // namespace

#pragma once
// What the libFuzzer harnesses share (docs/fuzzing.md): the plugin search path and data path of the build tree,
// and a private folder for the input files a harness writes (the parsers under test read files, as the CLI does).
#include "radchain/plugin_host.hpp"

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

namespace radchain::fuzz {

// The plugins next to the harness (<build>/plugins/<kind>/, found by the host as for the CLI) and the source
// tree's spectra/ (built in), unless the environment names others.
inline void configure_host() { PluginHost::instance().configure({}); }

// A folder of this process (removed by the OS's tmp cleaning only: a crash must leave the input to reproduce).
inline const std::filesystem::path& scratch_dir() {
  static const std::filesystem::path dir = [] {
    std::string pattern = (std::filesystem::temp_directory_path() / "radchain-fuzz-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) std::abort();
    return std::filesystem::path(pattern);
  }();
  return dir;
}

// Writes `bytes` to <scratch>/<name> and returns the path.
inline std::string write_scratch(const std::string& name, std::string_view bytes) {
  const std::filesystem::path path = scratch_dir() / name;
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return path.string();
}

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// The input cut into shard files at each line that starts "# radchain shard" (at most 32: the last takes the
// rest), written to the scratch folder as name_of(k) for k = 0, 1, …; returns their paths.
template <class NameOf>
std::vector<std::string> write_shard_files(std::string_view input, NameOf name_of) {
  const std::string_view header = "# radchain shard";
  constexpr std::size_t max_files = 32;
  std::vector<std::string> files;
  std::size_t begin = 0;
  while (begin < input.size() && files.size() < max_files) {
    std::size_t next = input.find(header, begin + 1);
    while (next != std::string_view::npos && input[next - 1] != '\n') next = input.find(header, next + 1);
    if (next == std::string_view::npos || files.size() + 1 == max_files) next = input.size();
    files.push_back(write_scratch(name_of(files.size()), input.substr(begin, next - begin)));
    begin = next;
  }
  return files;
}

}  // namespace radchain::fuzz

// A library built for another ABI whose static constructor leaves a marker file: the host must refuse it
// without running any of its code (it reads the ABI number from the file before loading it).
#include <boost/config.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>

extern "C" BOOST_SYMBOL_EXPORT const std::uint32_t radchain_plugin_abi_version;
extern "C" BOOST_SYMBOL_EXPORT const std::uint32_t radchain_plugin_abi_version = 999;

namespace {
struct Marker {
  Marker() {
    if (const char* path = std::getenv("RADCHAIN_TEST_MARKER"))
      if (std::FILE* f = std::fopen(path, "w")) std::fclose(f);
  }
} marker;
}  // namespace

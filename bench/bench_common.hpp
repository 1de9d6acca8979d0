#pragma once
// Shared by the benchmark programs.
#include <benchmark/benchmark.h>

#include <string>

namespace radchain::bench {

// benchmark::DoNotOptimize through a const reference: its read-write form ("+m,r") let GCC 12 lose a double
// assigned in the loop (valgrind: uninitialised after the loop).
template <class T>
void keep(const T& value) {
  benchmark::DoNotOptimize(value);
}

inline const std::string sbv_sensor = RADCHAIN_SOURCE_DIR "/sensors/msx-sbv.toml";

}  // namespace radchain::bench

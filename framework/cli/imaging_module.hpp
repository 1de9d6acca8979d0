#pragma once
// The imaging module: `radchain render`, `validate` and `mtf` live in radchain-imaging-commands.so, which links
// radchain::imaging (OpenImageIO, FFTW: some 250 shared libraries). The executable loads it (dlopen) only when
// one of those commands runs, so every other command starts without them (docs/startup.md).
//
// The module exports one extern "C" function per command, taking the option struct of options.hpp, and
// radchain_imaging_module_build(): the executable refuses a module built from other option structs.
#include "options.hpp"

#include "radchain/version.hpp"

#include <string>

namespace radchain::cli {

inline constexpr const char* imaging_module_file = "radchain-imaging-commands.so";

// What both sides must agree on: the framework version and the layout of the structs passed.
inline std::string imaging_module_build() {
  return std::string(framework_version) + "/" + std::to_string(sizeof(RenderCommand)) + "/" +
         std::to_string(sizeof(ValidateCommand)) + "/" + std::to_string(sizeof(MtfCommand));
}

using RenderEntry = int (*)(const RenderCommand&);
using ValidateEntry = int (*)(const ValidateCommand&);
using MtfEntry = int (*)(const MtfCommand&);
using BuildEntry = const char* (*)();

}  // namespace radchain::cli

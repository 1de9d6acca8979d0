# Precompiled headers for the in-tree build (not installed: an out-of-tree plugin compiles its own way).
#
# Why: nearly every file includes the engine's headers, which pull in Eigen and Boost.DLL, and every test file
# also GoogleTest; parsing them costs ~4 s of a ~5 s compile, once per file and once per build tree (release,
# ASan, TSan). A target's header set is parsed once instead. The clang fuzz build keeps them off, so one build
# still compiles every non-test file with only the includes it names.
#
# radchain_precompile(<target> [TESTS])       the target's own precompiled header: the engine's headers (+ GoogleTest)
# radchain_precompile_plugin(<target>)        plugins share one (a plugin is one file: its own would cost more than it saves)
set(RADCHAIN_PCH_THIRD_PARTY_HEADERS
  <algorithm> <cmath> <filesystem> <functional> <map> <memory> <optional> <string> <string_view> <vector>
  <Eigen/Core> <boost/dll/alias.hpp> <fmt/format.h>)
# The plugins' set stops there: plugin.hpp tests RADCHAIN_PLUGIN_NAME/KIND, which each plugin defines its own way,
# and a header that tests a macro the command line defines is not reused (-Winvalid-pch).
set(RADCHAIN_PCH_HEADERS ${RADCHAIN_PCH_THIRD_PARTY_HEADERS} <radchain/chain.hpp>)

function(radchain_precompile target)
  cmake_parse_arguments(ARG "TESTS" "" "" ${ARGN})
  if(NOT RADCHAIN_PCH)
    return()
  endif()
  set(headers ${RADCHAIN_PCH_HEADERS})
  if(ARG_TESTS)
    list(APPEND headers <gtest/gtest.h>)
    # GCC 12 reports its known false positives on std::string's operator+ (a literal joined to a temporary:
    # -Warray-bounds, -Wstringop-overflow, -Wrestrict; GCC PRs 105329, 105651) in a dozen test files once the
    # standard headers come from a precompiled header. The libraries keep the warnings (their one such line is
    # written with fmt); ASan checks the tests' bounds at run time.
    target_compile_options(${target} PRIVATE
                           "$<$<CXX_COMPILER_ID:GNU>:-Wno-array-bounds;-Wno-stringop-overflow;-Wno-restrict>")
  endif()
  target_precompile_headers(${target} PRIVATE ${headers})
endfunction()

function(radchain_precompile_plugin target)
  if(NOT RADCHAIN_PCH)
    return()
  endif()
  if(NOT TARGET radchain_plugin_pch)
    # A plugin's flags without a plugin: the shared header is compiled once, as every plugin would compile it.
    file(WRITE "${CMAKE_BINARY_DIR}/radchain_plugin_pch.cpp" "// the plugins' shared precompiled header\n")
    add_library(radchain_plugin_pch OBJECT "${CMAKE_BINARY_DIR}/radchain_plugin_pch.cpp")
    target_link_libraries(radchain_plugin_pch PRIVATE radchain_core radchain_warnings)
    set_target_properties(radchain_plugin_pch PROPERTIES POSITION_INDEPENDENT_CODE ON
                          CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
    target_precompile_headers(radchain_plugin_pch PRIVATE ${RADCHAIN_PCH_THIRD_PARTY_HEADERS})
  endif()
  target_precompile_headers(${target} REUSE_FROM radchain_plugin_pch)
endfunction()

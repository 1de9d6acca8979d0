# radchain_add_plugin(SOURCES <dir>/<kind>/<name>.cpp [more files...] [NAME <name>] [KIND <kind>])
#
# Builds one plugin as a MODULE library named exactly <name> (no "lib" prefix), so that the file stem, the
# CMake target, the .so and the TOML `plugin = "<name>"` value are one string. The name and kind come from the
# first source's path (plugins/criterion/snr_threshold.cpp) unless given, and reach the code as
# RADCHAIN_PLUGIN_NAME / RADCHAIN_PLUGIN_KIND for RADCHAIN_PLUGIN(): a plugin never restates them. The kinds are
# radchain::kinds (plugin.hpp); a KIND that is none of them does not compile. Hidden visibility: only the entry
# declared by RADCHAIN_PLUGIN() is exported. Output goes to <build>/plugins/<kind>/, where the host looks next
# to its executable.
function(radchain_add_plugin)
  cmake_parse_arguments(ARG "" "NAME;KIND" "SOURCES" ${ARGN})
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "radchain_add_plugin needs SOURCES (the first one is plugins/<kind>/<name>.cpp)")
  endif()
  list(GET ARG_SOURCES 0 first_source)
  if(NOT ARG_NAME)
    get_filename_component(ARG_NAME "${first_source}" NAME_WE)
  endif()
  if(NOT ARG_KIND)
    get_filename_component(kind_dir "${first_source}" ABSOLUTE)
    get_filename_component(kind_dir "${kind_dir}" DIRECTORY)
    get_filename_component(ARG_KIND "${kind_dir}" NAME)
  endif()
  if(NOT ARG_KIND MATCHES "^[a-z_]+$")
    message(FATAL_ERROR "radchain_add_plugin(${ARG_NAME}): kind \"${ARG_KIND}\" is no kind's name (give KIND, e.g. optics)")
  endif()
  add_library(${ARG_NAME} MODULE ${ARG_SOURCES})
  if(TARGET radchain_core)
    target_link_libraries(${ARG_NAME} PRIVATE radchain_core radchain_warnings)
  else()
    target_link_libraries(${ARG_NAME} PRIVATE radchain::core)
  endif()
  target_compile_definitions(${ARG_NAME} PRIVATE RADCHAIN_PLUGIN_NAME="${ARG_NAME}" RADCHAIN_PLUGIN_KIND=${ARG_KIND})
  set_target_properties(${ARG_NAME} PROPERTIES
    PREFIX ""
    OUTPUT_NAME ${ARG_NAME}
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON
    LIBRARY_OUTPUT_DIRECTORY "${CMAKE_BINARY_DIR}/plugins/${ARG_KIND}"
    INSTALL_RPATH "$ORIGIN/../../..")  # <prefix>/lib/radchain/plugins/<kind>/ -> <prefix>/lib
  if(DEFINED RADCHAIN_INSTALL_PLUGINDIR)
    install(TARGETS ${ARG_NAME} LIBRARY DESTINATION "${RADCHAIN_INSTALL_PLUGINDIR}/${ARG_KIND}")
  endif()
endfunction()

# radchain_add_plugin(NAME <name> KIND <kind> SOURCES <files...>)
#
# Builds one plugin as a MODULE library named exactly <name> (no "lib" prefix), so that the file stem, the
# CMake target, the .so and the TOML `plugin = "<name>"` value are one string. Hidden visibility: only the
# entry declared by RADCHAIN_PLUGIN() is exported. Output goes to <build>/plugins/<kind>/, where the
# host looks next to its executable.
function(radchain_add_plugin)
  cmake_parse_arguments(ARG "" "NAME;KIND" "SOURCES" ${ARGN})
  if(NOT ARG_NAME OR NOT ARG_KIND OR NOT ARG_SOURCES)
    message(FATAL_ERROR "radchain_add_plugin needs NAME, KIND and SOURCES")
  endif()
  set(kinds sources targets atmospheres optics detectors criteria platforms)
  if(NOT ARG_KIND IN_LIST kinds)
    message(FATAL_ERROR "radchain_add_plugin(${ARG_NAME}): KIND must be one of ${kinds}")
  endif()
  add_library(${ARG_NAME} MODULE ${ARG_SOURCES})
  if(TARGET radchain_core)
    target_link_libraries(${ARG_NAME} PRIVATE radchain_core radchain_warnings)
  else()
    target_link_libraries(${ARG_NAME} PRIVATE radchain::core)
  endif()
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

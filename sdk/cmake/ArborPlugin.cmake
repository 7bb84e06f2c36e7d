# arbor_add_plugin(<target> SOURCES <files...> [OUTPUT_DIRECTORY <dir>])
#
# Builds an Arbor plugin: a shared module that links the SDK headers, exports
# nothing but the `arbor_entry` symbol, and refuses undefined symbols at link
# time (so a missing library is a build error, not a load error).  The file is
# named <target>.so.  Install it into a folder on ARBOR_PLUGIN_PATH or into
# ~/.local/share/arbor/plugins.
function(arbor_add_plugin target)
  # The version script sits next to this file, wherever the function is called from.
  set(_ARBOR_PLUGIN_MAP "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/arbor-plugin.map")
  cmake_parse_arguments(ARG "" "OUTPUT_DIRECTORY" "SOURCES" ${ARGN})
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "arbor_add_plugin(${target}): SOURCES is required")
  endif()
  add_library(${target} MODULE ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE ArborSDK::sdk)
  set_target_properties(${target} PROPERTIES
    PREFIX ""
    C_VISIBILITY_PRESET hidden
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
  if(ARG_OUTPUT_DIRECTORY)
    set_target_properties(${target} PROPERTIES LIBRARY_OUTPUT_DIRECTORY "${ARG_OUTPUT_DIRECTORY}")
  endif()
  if(CMAKE_SYSTEM_NAME STREQUAL "Linux")
    target_link_options(${target} PRIVATE
      "LINKER:--version-script=${_ARBOR_PLUGIN_MAP}" "LINKER:--no-undefined")
    set_property(TARGET ${target} APPEND PROPERTY LINK_DEPENDS "${_ARBOR_PLUGIN_MAP}")
  endif()
endfunction()

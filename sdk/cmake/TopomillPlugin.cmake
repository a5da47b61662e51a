# topomill_add_plugin(<name> SOURCES <files...> [OUTPUT_DIRECTORY <dir>] [NO_INSTALL])
#
# Builds a plugin library libtopomill_<name>.so: a MODULE (loaded, never linked), hidden
# visibility so that only the TOPOMILL_PLUGIN entry point is exported, linked to the core.
# Name the library after the model it registers: the loader finds model NAME in
# libtopomill_NAME.so without opening any other library.
function(topomill_add_plugin name)
  cmake_parse_arguments(ARG "NO_INSTALL" "OUTPUT_DIRECTORY" "SOURCES" ${ARGN})
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "topomill_add_plugin(${name}): SOURCES is required")
  endif()
  set(target topomill_${name})
  add_library(${target} MODULE ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE topomill::core)
  if(NOT ARG_OUTPUT_DIRECTORY AND DEFINED TOPOMILL_PLUGIN_OUTPUT_DIRECTORY)
    set(ARG_OUTPUT_DIRECTORY ${TOPOMILL_PLUGIN_OUTPUT_DIRECTORY})
  endif()
  set_target_properties(${target} PROPERTIES
    PREFIX "lib"
    OUTPUT_NAME topomill_${name}
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
  if(ARG_OUTPUT_DIRECTORY)
    set_target_properties(${target} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${ARG_OUTPUT_DIRECTORY})
  endif()
  if(NOT ARG_NO_INSTALL AND DEFINED TOPOMILL_PLUGIN_INSTALL_DIR)
    install(TARGETS ${target} LIBRARY DESTINATION ${TOPOMILL_PLUGIN_INSTALL_DIR})
  endif()
endfunction()

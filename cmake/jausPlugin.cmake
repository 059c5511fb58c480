# Component plugins (docs/plugins.md): shared libraries that bring component
# kinds to jausd, which loads those its configuration lists under `plugins:`.
# Included by the installed CMake package (jausConfig.cmake) and in-tree by
# apps/jausd; the same functions build a user's plugin and the project's.
#
# One copy of the framework per process: jausd is linked with every jaus
# library whole and exports their symbols; a plugin links no jaus library
# (only jaus::plugin_api: the headers, C++20, Boost and nlohmann_json headers)
# and its references resolve to jausd's copy when it is loaded.

# jaus_add_component_plugin(<target> SOURCES <file>...): a MODULE library
# lib<target>.so whose sources write JAUS_COMPONENT_PLUGIN
# (jaus/runtime/component_plugin.hpp). Everything but that entry point is
# hidden, so the plugin's own symbols never clash with jausd's or another
# plugin's.
function(jaus_add_component_plugin target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "SOURCES")
  if(NOT arg_SOURCES)
    message(FATAL_ERROR "jaus_add_component_plugin(${target}): give its SOURCES")
  endif()
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "jaus_add_component_plugin(${target}): unknown arguments ${arg_UNPARSED_ARGUMENTS}")
  endif()
  add_library(${target} MODULE ${arg_SOURCES})
  set_target_properties(${target} PROPERTIES
    PREFIX "lib"
    POSITION_INDEPENDENT_CODE ON
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
  target_link_libraries(${target} PRIVATE jaus::plugin_api)
endfunction()

# jaus_enable_component_plugins(<executable> <library>...): the program loads
# component plugins (jaus/host/component_plugins.hpp). The libraries are
# linked whole and their symbols exported, so whatever of them a plugin uses
# is there when it is loaded, once.
#
# The archives are named once, whole, ahead of everything else (link options
# come first): their later, plain occurrences through the libraries' own
# links then add nothing. $<LINK_LIBRARY:WHOLE_ARCHIVE,...> would put each in
# whole at every occurrence, and define its symbols several times.
function(jaus_enable_component_plugins target)
  set_target_properties(${target} PROPERTIES ENABLE_EXPORTS ON)
  set(archives "")
  foreach(library IN LISTS ARGN)
    string(APPEND archives " $<TARGET_FILE:${library}>")
  endforeach()
  target_link_options(${target} PRIVATE "SHELL:LINKER:--whole-archive${archives} LINKER:--no-whole-archive")
  # Plainly too: the archives' own dependencies, and a relink when one changes.
  target_link_libraries(${target} PRIVATE ${ARGN} ${CMAKE_DL_LIBS})
endfunction()

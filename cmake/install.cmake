# What `cmake --install` puts where (GNUInstallDirs), and the CMake package
# other projects use: find_package(jaus CONFIG REQUIRED), then
# target_link_libraries(my_component PRIVATE jaus::runtime).
#
# Every library is exported as jaus::<name without jaus_> (jaus_runtime ->
# jaus::runtime). Internal targets (jaus_warnings, test helpers, the apps'
# own libraries) are not exported: the libraries link jaus_warnings as
# $<BUILD_INTERFACE:...>, so it never reaches the exported interface.
# Programs, the default configuration, the systemd unit and the man pages are
# installed by apps/ and packaging/; packaging/cpack.cmake makes the .deb.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The component folders components/CMakeLists.txt lists (a new kind is
# installed without naming it here): library jaus_<folder>, headers in
# components/<folder>/include.
get_property(jaus_component_folders GLOBAL PROPERTY JAUS_COMPONENT_FOLDERS)
list(TRANSFORM jaus_component_folders PREPEND jaus_ OUTPUT_VARIABLE jaus_component_libraries)
list(TRANSFORM jaus_component_folders PREPEND components/ OUTPUT_VARIABLE jaus_component_include_dirs)
# The kinds' JSS libraries (jaus_jss_translators(), components/CMakeLists.txt):
# library jaus_<folder>_jss, headers in components/<folder>/jss/include.
get_property(jaus_component_jss_folders GLOBAL PROPERTY JAUS_COMPONENT_JSS_FOLDERS)
get_property(jaus_jss_translator_entries GLOBAL PROPERTY JAUS_JSS_TRANSLATORS)
set(jaus_component_jss_libraries "")
foreach(entry IN LISTS jaus_jss_translator_entries)
  string(REPLACE "|" ";" parts "${entry}")
  list(GET parts 0 library)
  list(APPEND jaus_component_jss_libraries ${library})
endforeach()
list(REMOVE_DUPLICATES jaus_component_jss_libraries)
list(REMOVE_DUPLICATES jaus_component_jss_folders)

# The libraries of docs/architecture.md, in dependency order.
set(JAUS_EXPORTED_LIBRARIES
    jaus_base jaus_core jaus_runtime ${jaus_component_libraries} jaus_jss_face ${jaus_component_jss_libraries}
    jaus_transport jaus_clearpath jaus_clearpath_sim jaus_clearpath_asio jaus_bridge
    jaus_model_platform jaus_clearpath_platform jaus_host jaus_ocu jaus_conform)

# The folders whose include/ holds public headers (all under jaus/, no two alike).
set(JAUS_PUBLIC_INCLUDE_DIRS core runtime jss_face transport host ocu conformance clearpath bridge ${jaus_component_include_dirs}
    ${jaus_component_jss_folders})

# jaus::plugin_api: what a component plugin compiles against (the headers,
# C++20, the header-only libraries they include) and nothing it links: jausd
# carries the one copy of the libraries (cmake/jausPlugin.cmake).
add_library(jaus_plugin_api INTERFACE)
add_library(jaus::plugin_api ALIAS jaus_plugin_api)
foreach(dir IN LISTS JAUS_PUBLIC_INCLUDE_DIRS)
  target_include_directories(jaus_plugin_api INTERFACE $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/${dir}/include>)
endforeach()
target_include_directories(jaus_plugin_api INTERFACE $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/generated/include>)
target_compile_features(jaus_plugin_api INTERFACE cxx_std_20)
target_link_libraries(jaus_plugin_api INTERFACE Boost::boost nlohmann_json::nlohmann_json)
set_target_properties(jaus_plugin_api PROPERTIES EXPORT_NAME plugin_api)

set(JAUS_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/jaus)
set(JAUS_INSTALL_DOCDIR ${CMAKE_INSTALL_DATAROOTDIR}/doc/jaus-node)

function(jaus_install_libraries)
  # Consumers compile the headers as C++20, as the libraries are.
  target_compile_features(jaus_base PUBLIC cxx_std_20)
  foreach(library IN LISTS JAUS_EXPORTED_LIBRARIES)
    string(REGEX REPLACE "^jaus_" "" exported "${library}")
    set_target_properties(${library} PROPERTIES EXPORT_NAME ${exported})
  endforeach()
  install(TARGETS ${JAUS_EXPORTED_LIBRARIES} jaus_plugin_api
          EXPORT jausTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  foreach(dir IN LISTS JAUS_PUBLIC_INCLUDE_DIRS)
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
            FILES_MATCHING PATTERN "*.hpp")
  endforeach()
  install(FILES ${PROJECT_BINARY_DIR}/generated/include/jaus/base/version.hpp
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/jaus/base)

  install(EXPORT jausTargets NAMESPACE jaus:: FILE jausTargets.cmake DESTINATION ${JAUS_INSTALL_CMAKEDIR})
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/jausConfig.cmake.in
                                ${PROJECT_BINARY_DIR}/package/jausConfig.cmake
                                INSTALL_DESTINATION ${JAUS_INSTALL_CMAKEDIR})
  # 0.x: a minor version may break the interface, so only the same minor is compatible.
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/package/jausConfigVersion.cmake
                                   VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/package/jausConfig.cmake ${PROJECT_BINARY_DIR}/package/jausConfigVersion.cmake
                ${PROJECT_SOURCE_DIR}/cmake/jausPlugin.cmake
          DESTINATION ${JAUS_INSTALL_CMAKEDIR})
endfunction()

# The default configuration goes to <sysconfdir>/jaus/jausd.yaml: /etc for the
# /usr prefix (the .deb), <prefix>/etc otherwise, as GNUInstallDirs's
# CMAKE_INSTALL_FULL_SYSCONFDIR would say. Decided at install time, because
# cpack installs with its own prefix (/usr) into a tree configured for another.
function(jaus_install_configuration)
  set(source ${PROJECT_SOURCE_DIR}/config/jausd.yaml)
  install(CODE "
    if(CMAKE_INSTALL_PREFIX STREQUAL \"/usr\")
      set(jaus_sysconfdir \"/etc\")
    else()
      set(jaus_sysconfdir \"\${CMAKE_INSTALL_PREFIX}/${CMAKE_INSTALL_SYSCONFDIR}\")
    endif()
    file(INSTALL DESTINATION \"\${jaus_sysconfdir}/jaus\" TYPE FILE FILES \"${source}\")
  ")
endfunction()

function(jaus_install_docs)
  install(FILES ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/CHANGELOG.md DESTINATION ${JAUS_INSTALL_DOCDIR})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${JAUS_INSTALL_DOCDIR}/docs FILES_MATCHING PATTERN "*.md")
endfunction()

jaus_install_libraries()
jaus_install_configuration()
jaus_install_docs()

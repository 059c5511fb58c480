# jaus_reverse_unity_order(<directory>...): the unity-built targets defined in
# these directories (and below) batch their files in reverse order.
#
# A unity build can hide a file's missing include that an earlier file of its
# batch made. scripts/test.sh builds its two trees with the files in opposite
# orders (JAUS_UNITY_BUILD_REVERSED in the sanitizer tree), so a file that
# compiles only after another in one tree comes before it, or in another
# batch, in the other, and fails there; at no cost in compile time.
function(jaus_reverse_unity_order)
  foreach(directory IN LISTS ARGN)
    get_property(targets DIRECTORY "${directory}" PROPERTY BUILDSYSTEM_TARGETS)
    foreach(target IN LISTS targets)
      get_target_property(type ${target} TYPE)
      if(type STREQUAL "INTERFACE_LIBRARY" OR type STREQUAL "UTILITY")
        continue()
      endif()
      get_target_property(unity ${target} UNITY_BUILD)
      if(unity)
        get_target_property(sources ${target} SOURCES)
        list(REVERSE sources)
        set_property(TARGET ${target} PROPERTY SOURCES ${sources})
      endif()
    endforeach()
    get_property(subdirectories DIRECTORY "${directory}" PROPERTY SUBDIRECTORIES)
    jaus_reverse_unity_order(${subdirectories})
  endforeach()
endfunction()

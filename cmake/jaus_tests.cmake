# How a GoogleTest executable compiles and becomes ctest entries: every test
# folder registers its executables through jaus_add_gtests() (included from
# tests/CMakeLists.txt).
#
# jaus_add_gtests(<target> [REAL_TIME | PER_TEST] [SHARDS <n>] [TIMEOUT <seconds>]
#                 [UNITY [SEPARATE <file>...]] [PROPERTIES <name> <value>...])
#
# TIMEOUT applies to each ctest entry (a shard, or a test with PER_TEST);
# without it ctest's --timeout (scripts/test.sh: 300 s) applies.
#
#   (default)  a deterministic suite (virtual time, or bytes alone): <n> ctest
#              entries (default 2, so that `ctest -j2` has two to run),
#              <target>.shard<i>of<n>, each running its share of the tests
#              (GTEST_TOTAL_SHARDS / GTEST_SHARD_INDEX) in ONE process, below
#              normal CPU priority (nice 10). A process per test costs more
#              than most of these tests (40 ms under ASan, 1411 such tests),
#              and they need no CPU promptly: the real-clock tests running
#              beside them get it first.
#   REAL_TIME  tests on real sockets and clocks that start no other process:
#              shards too, at normal priority, each holding a `realtime` slot.
#   PER_TEST   one process per test (gtest_discover_tests), each holding a
#              `realtime` slot: tests that start programs, flood a node or
#              hold loopback addresses (PROPERTIES RESOURCE_LOCK ...).
#
# The `realtime` slots (RESOURCE_GROUPS realtime:1) matter only when ctest is
# given a resource spec file: scripts/test.sh runs the sanitizer suites with
# one realtime slot more than there are cores and as many jobs again for the
# deterministic shards, which fill the CPU the real-clock tests leave idle
# while they wait. Plain `ctest -jN` ignores the slots.
#
# A failing shard prints the whole gtest output of its process (each test's
# [ RUN ] / [ FAILED ] lines and its log). To run one test:
#   <build>/tests/core/core_tests --gtest_filter='Malformed.*'
# or configure with -DJAUS_TEST_ONE_PROCESS_PER_TEST=ON (one ctest entry per
# test, as gtest_discover_tests makes them, for `ctest -R <test name>`).
#
# UNITY: the executable's files compile as unity builds (batches of
# JAUS_UNITY_TESTS_BATCH_SIZE files share one translation unit; off with
# -DJAUS_UNITY_TESTS=OFF): the headers, GoogleTest and every template they
# instantiate (messages, nodes, sessions) are compiled once a batch instead of
# once a file. Measured under clang ASan: five tests/ocu files 22.9 s as five
# units, 8.2 s as one; three tests/core message-check files 100 s, 74 s.
# The files of a batch must not define the same name at file scope (anonymous
# namespaces included: `redefinition of ...`): list such files after
# SEPARATE (each compiled on its own), or give the name a namespace of its
# file.

include_guard(GLOBAL)
include(GoogleTest)

option(JAUS_UNITY_TESTS "Compile the test executables registered with UNITY as unity builds" ON)
option(JAUS_TEST_ONE_PROCESS_PER_TEST "One ctest entry and process per gtest test (for ctest -R <test>)" OFF)
set(JAUS_UNITY_TESTS_BATCH_SIZE 8 CACHE STRING "Source files per unity translation unit of a test executable")

function(jaus_add_gtests target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "REAL_TIME;PER_TEST;UNITY" "SHARDS;TIMEOUT" "SEPARATE;PROPERTIES")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "jaus_add_gtests(${target}): unknown arguments ${arg_UNPARSED_ARGUMENTS}")
  endif()
  if(arg_REAL_TIME AND arg_PER_TEST)
    message(FATAL_ERROR "jaus_add_gtests(${target}): REAL_TIME or PER_TEST, not both")
  endif()
  if(NOT arg_SHARDS)
    set(arg_SHARDS 2)
  endif()
  set(timeout "")
  if(arg_TIMEOUT)
    set(timeout TIMEOUT ${arg_TIMEOUT})
  endif()

  if(arg_UNITY AND JAUS_UNITY_TESTS)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${JAUS_UNITY_TESTS_BATCH_SIZE})
    if(arg_SEPARATE)
      set_source_files_properties(${arg_SEPARATE} TARGET_DIRECTORY ${target} PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
    endif()
  endif()

  # The caller's LABELS are kept and ours added to them; other properties pass through.
  set(labels "")
  set(properties "")
  set(key "")
  foreach(item IN LISTS arg_PROPERTIES)
    if(key STREQUAL "")
      set(key ${item})
    else()
      if(key STREQUAL "LABELS")
        list(APPEND labels ${item})
      else()
        list(APPEND properties ${key} ${item})
      endif()
      set(key "")
    endif()
  endforeach()

  if(arg_PER_TEST OR JAUS_TEST_ONE_PROCESS_PER_TEST)
    if(arg_PER_TEST OR arg_REAL_TIME)
      set(kind realtime)
      list(APPEND properties RESOURCE_GROUPS realtime:1)
    else()
      set(kind deterministic)
    endif()
    list(APPEND properties ${timeout})
    # gtest_discover_tests passes each property one value: the caller's label, else ours.
    if(labels)
      list(GET labels 0 kind)
    endif()
    gtest_discover_tests(${target} DISCOVERY_TIMEOUT 60 PROPERTIES ${properties} LABELS ${kind})
    return()
  endif()

  if(arg_REAL_TIME)
    set(command $<TARGET_FILE:${target}>)
    list(APPEND labels realtime)
    list(APPEND properties RESOURCE_GROUPS realtime:1)
  else()
    set(command nice -n 10 $<TARGET_FILE:${target}>)
    list(APPEND labels deterministic)
  endif()
  foreach(index RANGE 1 ${arg_SHARDS})
    set(name ${target}.shard${index}of${arg_SHARDS})
    math(EXPR gtest_index "${index} - 1")
    add_test(NAME ${name} COMMAND ${command} --gtest_also_run_disabled_tests
             WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
    set_tests_properties(${name} PROPERTIES
      ENVIRONMENT "GTEST_TOTAL_SHARDS=${arg_SHARDS};GTEST_SHARD_INDEX=${gtest_index}"
      LABELS "${labels}" ${timeout} ${properties})
  endforeach()
endfunction()

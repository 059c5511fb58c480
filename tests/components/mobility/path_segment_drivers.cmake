# The path segment drivers (components 47 and 48), on a whole vehicle node
# under virtual time: paths followed within a stated cross-track error on
# both platforms and drivetrains, Part 3's numbering, control, the route's
# life and the safety rules every driver keeps.
add_executable(path_segment_driver_tests ${CMAKE_CURRENT_SOURCE_DIR}/path_segment_drivers_test.cpp)
target_link_libraries(path_segment_driver_tests PRIVATE jaus_local_path_segment_driver jaus_global_path_segment_driver
                                                        jaus_test_support GTest::gtest_main jaus_warnings)
gtest_discover_tests(path_segment_driver_tests DISCOVERY_TIMEOUT 60)

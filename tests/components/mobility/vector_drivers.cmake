# The vector drivers (components 34 and 44, issue 30) on a whole vehicle node
# under virtual time: both platforms, both drivetrains.
add_executable(vector_drivers_tests vector_drivers_test.cpp)
target_link_libraries(vector_drivers_tests PRIVATE jaus_global_vector_driver jaus_local_vector_driver jaus_test_support
                                                   GTest::gtest_main jaus_warnings)
gtest_discover_tests(vector_drivers_tests DISCOVERY_TIMEOUT 60)

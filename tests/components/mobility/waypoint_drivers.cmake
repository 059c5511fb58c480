# The waypoint drivers (components 45 and 46, issue 30) on a whole vehicle
# node under virtual time, both platforms and both drivetrains; the local
# frame's projection the global driver follows its route in.
add_executable(waypoint_driver_tests waypoint_driver_test.cpp waypoint_route_test.cpp waypoint_local_frame_test.cpp
                                     waypoint_options_test.cpp)
target_link_libraries(waypoint_driver_tests PRIVATE jaus_global_waypoint_driver jaus_local_waypoint_driver
                                                    jaus_test_support GTest::gtest_main jaus_warnings)
gtest_discover_tests(waypoint_driver_tests DISCOVERY_TIMEOUT 60)

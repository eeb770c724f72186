# pcl_ros's Debian tools (pcl-ros-tools) driven with the commands docs/tuning.md shows: a PCD
# published as a map, a topic saved to PCD, a bag exported to PCD for pda_align. rostest for the
# roscore the tools need. Included from test/CMakeLists.txt.
add_rostest_gtest(pcl_ros_tools_test ros/pcl_ros_tools.test ros/pcl_ros_tools_test.cpp
                  ros/background_command.cpp ros/rostest_main.cpp)
target_compile_options(pcl_ros_tools_test PRIVATE ${PDA_WARNINGS})
set_target_properties(pcl_ros_tools_test PROPERTIES ENABLE_EXPORTS ON)
target_link_libraries(pcl_ros_tools_test pda_test_support ${catkin_LIBRARIES})
# It reads docs/tuning.md to check that the page still shows the commands it runs.
target_compile_definitions(pcl_ros_tools_test PRIVATE PDA_REPO_DIR="${PDA_REPO_DIR}")
# The test runs the tools through rosrun, as the page does.
add_dependencies(pcl_ros_tools_test pda_align pda_case_bag)

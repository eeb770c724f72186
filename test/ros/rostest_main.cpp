// main() of the nodelet rostests: gtest, then a ROS node (named after the test program) with a
// two-thread spinner so subscriptions are served while a test body waits.
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <cstdio>
#include <string>

int main(int argc, char** argv) {
  // Line-buffered: rostest logs stdout to a file, where a crash would otherwise lose the failure
  // messages gtest printed before it.
  std::setvbuf(stdout, nullptr, _IOLBF, BUFSIZ);
  ::testing::InitGoogleTest(&argc, argv);
  const std::string program = argv[0];
  ros::init(argc, argv, program.substr(program.find_last_of('/') + 1));
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const int result = RUN_ALL_TESTS();
  ros::shutdown();
  return result;
}

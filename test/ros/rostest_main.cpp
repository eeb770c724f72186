// main() of the nodelet rostests: gtest, then a ROS node (named after the test program) with a
// two-thread spinner so subscriptions are served while a test body waits.
#include <execinfo.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstring>
#include <string>

namespace {

// A test process that dies of a signal (glibc aborts on a double free) leaves no gtest report:
// its stack goes to stderr, which rostest prints to its console (run_tests.log, where scripts/test
// finds and prints it), so that a crash seen once in many runs says where it happened.
void printStackAndDie(int signal_number) {
  constexpr char kHeader[] = "\n[rostest_main] the test process received signal ";
  ssize_t ignored = write(STDERR_FILENO, kHeader, sizeof(kHeader) - 1);
  const char* name = strsignal(signal_number);
  ignored = write(STDERR_FILENO, name, std::strlen(name));
  ignored = write(STDERR_FILENO, "; its stack:\n", 13);
  (void)ignored;
  void* frames[64];
  backtrace_symbols_fd(frames, backtrace(frames, 64), STDERR_FILENO);
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

}  // namespace

int main(int argc, char** argv) {
  // Line-buffered: rostest logs stdout to a file, where a crash would otherwise lose the failure
  // messages gtest printed before it.
  std::setvbuf(stdout, nullptr, _IOLBF, BUFSIZ);
  // backtrace() loads libgcc on its first call, which is not safe inside a signal handler.
  void* warm_up[1];
  backtrace(warm_up, 1);
  for (int signal_number : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL}) {
    std::signal(signal_number, printStackAndDie);
  }
  ::testing::InitGoogleTest(&argc, argv);
  const std::string program = argv[0];
  ros::init(argc, argv, program.substr(program.find_last_of('/') + 1));
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const int result = RUN_ALL_TESTS();
  ros::shutdown();
  return result;
}

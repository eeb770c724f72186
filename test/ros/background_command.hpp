#pragma once
// A command-line tool left running while a test talks to it (a publisher, a recorder), stopped
// when the test is done with it, however the test ends.

#include <sys/types.h>

#include <string>

namespace pda_registration {
namespace testing_support {

class BackgroundCommand {
 public:
  /// Runs `command` through /bin/sh in a process group of its own; stdout and stderr go to
  /// `log_path`. Bound it with `exec timeout N ...` so that it cannot outlive a crashed test.
  BackgroundCommand(const std::string& command, const std::string& log_path);
  /// SIGINT to the group (ROS tools shut down on it), SIGKILL if it is still there after 5 s.
  ~BackgroundCommand();
  BackgroundCommand(const BackgroundCommand&) = delete;
  BackgroundCommand& operator=(const BackgroundCommand&) = delete;

  bool running();
  /// What it printed so far (for failure messages).
  std::string log() const;

 private:
  pid_t pid_ = -1;
  bool exited_ = false;
  std::string log_path_;
};

}  // namespace testing_support
}  // namespace pda_registration

#pragma once
// Runs a command-line tool as a user would (through the shell) and inspects what it printed.

#include <string>

namespace pda_registration {
namespace testing_support {

struct CommandRun {
  int exit_code;
  std::string out, err;
};

/// `binary arguments`, capturing stdout and stderr; exit_code -1 when it did not exit normally.
CommandRun runCommand(const std::string& binary, const std::string& arguments);

std::string readFile(const std::string& path);
/// A file name in gtest's temporary directory, unique to this test program.
std::string temporaryPath(const std::string& name);
/// The number after "key": in a one-line JSON object; NaN when absent.
double jsonNumber(const std::string& json, const std::string& key);
size_t lineCount(const std::string& text);

}  // namespace testing_support
}  // namespace pda_registration

#include "test_support/command_run.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>

namespace pda_registration {
namespace testing_support {

std::string readFile(const std::string& path) {
  std::ifstream file(path);
  return std::string(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
}

namespace {
// One directory per test process, removed when it exits (the bags and clouds add up otherwise).
// Never destroyed, so the exit handler can still read it.
const std::string& processTemporaryDirectory() {
  static const std::string* directory = [] {
    auto* path = new std::string(::testing::TempDir() + "pda_test_" + std::to_string(getpid()));
    std::filesystem::create_directories(*path);
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(processTemporaryDirectory(), ignored);
    });
    return path;
  }();
  return *directory;
}
}  // namespace

std::string temporaryPath(const std::string& name) {
  return processTemporaryDirectory() + "/" + name;
}

CommandRun runCommand(const std::string& binary, const std::string& arguments) {
  const std::string out = temporaryPath("stdout"), err = temporaryPath("stderr");
  const int status = std::system((binary + " " + arguments + " >" + out + " 2>" + err).c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, readFile(out), readFile(err)};
}

double jsonNumber(const std::string& json, const std::string& key) {
  std::smatch match;
  if (!std::regex_search(json, match, std::regex("\"" + key + "\":(-?[0-9.eE+-]+)"))) {
    return std::nan("");
  }
  return std::stod(match[1]);
}

size_t lineCount(const std::string& text) {
  return static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
}

}  // namespace testing_support
}  // namespace pda_registration

// The libFuzzer targets of test/fuzz/, briefly: each one runs for a few seconds over its seed
// corpus and replays every input in its regressions folder, with exit code 0 and no sanitizer or
// invariant report. The long run is scripts/fuzz. Without clang's libFuzzer at build time these
// tests fail (CI installs it), they do not skip.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "test_support/command_run.hpp"

namespace pda_registration {
namespace {

using testing_support::CommandRun;
using testing_support::runCommand;
using testing_support::temporaryPath;
namespace fs = std::filesystem;

// One per test/fuzz/<target>_fuzzer.cpp.
const std::vector<std::string> kTargets = {"point_cloud2", "transform_matrix", "initial_transform",
                                           "command_line", "pcd_header"};
constexpr int kShortRunSeconds = 5;

std::string fuzzerBinary(const std::string& target) {
  return std::string(PDA_FUZZ_BINARY_DIR) + "/" + target + "_fuzzer";
}
std::string seedFolder(const std::string& target) {
  return std::string(PDA_FUZZ_SOURCE_DIR) + "/corpus/" + target;
}
std::string regressionFolder(const std::string& target) {
  return std::string(PDA_FUZZ_SOURCE_DIR) + "/regressions/" + target;
}
/// "-dict=<file>" when the target has a dictionary of its format's tokens, else "".
std::string dictionaryOption(const std::string& target) {
  const std::string dictionary =
      std::string(PDA_FUZZ_SOURCE_DIR) + "/dictionaries/" + target + ".dict";
  return fs::exists(dictionary) ? " -dict=" + dictionary : "";
}

std::vector<std::string> regressionInputs(const std::string& target) {
  std::vector<std::string> inputs;
  if (!fs::is_directory(regressionFolder(target))) return inputs;
  for (const fs::directory_entry& entry : fs::directory_iterator(regressionFolder(target))) {
    if (entry.is_regular_file() && entry.path().filename().string()[0] != '.') {
      inputs.push_back(entry.path().string());
    }
  }
  std::sort(inputs.begin(), inputs.end());
  return inputs;
}

void requireFuzzersBuilt(const std::string& target) {
  ASSERT_TRUE(PDA_FUZZERS_AVAILABLE)
      << "clang++ with libFuzzer was not found when the package was built, so the fuzzers were "
         "not: install clang and libclang-rt-14-dev (scripts/install_deps does) and rebuild";
  ASSERT_TRUE(fs::exists(fuzzerBinary(target))) << fuzzerBinary(target) << " was not built";
}

/// The lines that name what went wrong and where libFuzzer saved the input.
std::string findings(const std::string& output) {
  std::istringstream lines(output);
  std::string found;
  for (std::string line; std::getline(lines, line);) {
    for (const char* key :
         {"ERROR: ", "runtime error", "INVARIANT VIOLATED", "Test unit written"}) {
      if (line.find(key) != std::string::npos) found += line + "\n";
    }
  }
  return found;
}

void expectCleanRun(const CommandRun& run) {
  const std::string output = run.out + run.err;
  const std::string tail =
      findings(output) + "...\n" + output.substr(output.size() > 3000 ? output.size() - 3000 : 0);
  EXPECT_EQ(run.exit_code, 0) << tail;
  for (const char* report :
       {"ERROR: AddressSanitizer", "ERROR: libFuzzer", "runtime error", "INVARIANT VIOLATED"}) {
    EXPECT_EQ(output.find(report), std::string::npos) << report << " in:\n" << tail;
  }
}

class FuzzSmoke : public ::testing::TestWithParam<std::string> {};

TEST_P(FuzzSmoke, ShortRunOverTheSeedCorpus) {
  const std::string target = GetParam();
  ASSERT_NO_FATAL_FAILURE(requireFuzzersBuilt(target));
  ASSERT_TRUE(fs::is_directory(seedFolder(target))) << "no seed corpus " << seedFolder(target);
  // libFuzzer writes new inputs into the first folder: a temporary one, so the seeds stay as
  // they are. Crash artifacts go there too.
  const std::string work = temporaryPath(target + "_corpus");
  fs::create_directories(work);
  std::string folders = work + " " + seedFolder(target);
  if (fs::is_directory(regressionFolder(target))) folders += " " + regressionFolder(target);
  expectCleanRun(
      runCommand(fuzzerBinary(target), "-max_total_time=" + std::to_string(kShortRunSeconds) +
                                           " -timeout=10 -rss_limit_mb=2048 -print_final_stats=1" +
                                           dictionaryOption(target) + " -artifact_prefix=" + work +
                                           "/ " + folders));
}

TEST_P(FuzzSmoke, ReplaysEveryRegressionInput) {
  const std::string target = GetParam();
  ASSERT_NO_FATAL_FAILURE(requireFuzzersBuilt(target));
  // Files (not folders) on libFuzzer's command line are each run once.
  for (const std::string& input : regressionInputs(target)) {
    SCOPED_TRACE(input);
    expectCleanRun(runCommand(fuzzerBinary(target), "-timeout=10 " + input));
  }
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzSmoke, ::testing::ValuesIn(kTargets),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

}  // namespace
}  // namespace pda_registration

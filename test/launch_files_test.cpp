// The launch files as a user starts them (roslaunch --dump-params: the parameters the nodelet
// would get, without starting anything). A params YAML holds only the keys it changes, over
// cfg/default_parameters.yaml; launch args override the YAML only when given.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include "test_support/command_run.hpp"

namespace pda_registration {
namespace {

using testing_support::CommandRun;
using testing_support::runCommand;
using testing_support::temporaryPath;

// "/pda_registration/threads: 1" lines as {"threads": "1"}; the exit code and stderr on failure.
std::map<std::string, std::string> nodeletParameters(const std::string& arguments,
                                                     std::string* problem) {
  const CommandRun run =
      runCommand("roslaunch", "--dump-params pda_registration map_alignment.launch " + arguments);
  std::map<std::string, std::string> parameters;
  if (run.exit_code != 0) {
    *problem = "exit " + std::to_string(run.exit_code) + ": " + run.err;
    return parameters;
  }
  std::istringstream lines(run.out);
  const std::string prefix = "/pda_registration/";
  for (std::string line; std::getline(lines, line);) {
    const size_t colon = line.find(": ");
    if (line.rfind(prefix, 0) == 0 && colon != std::string::npos) {
      parameters[line.substr(prefix.size(), colon - prefix.size())] = line.substr(colon + 2);
    }
  }
  return parameters;
}

TEST(MapAlignmentLaunch, DefaultsComeFromTheDefaultYaml) {
  std::string problem;
  auto p = nodeletParameters("", &problem);
  ASSERT_TRUE(problem.empty()) << problem;
  EXPECT_EQ(p["threads"], "2");
  EXPECT_EQ(p["target_cloud"], "dense");
  EXPECT_EQ(p["publish_tf"], "true");
  EXPECT_EQ(p["k"], "5");
  EXPECT_EQ(p["crop_above_points"], "500000");
}

TEST(MapAlignmentLaunch, APartialYamlChangesOnlyItsKeysAndArgsWinWhenGiven) {
  const std::string yaml = temporaryPath("partial.yaml");
  std::ofstream(yaml) << "threads: 1\ntarget_cloud: sparse\ntf_parent_frame: map\n"
                         "publish_tf: false\nk: 7\n";
  std::string problem;
  auto p = nodeletParameters("params:=" + yaml, &problem);
  ASSERT_TRUE(problem.empty()) << problem;
  // The YAML's static settings are not overwritten by the launch file's args ...
  EXPECT_EQ(p["threads"], "1");
  EXPECT_EQ(p["target_cloud"], "sparse");
  EXPECT_EQ(p["tf_parent_frame"], "map");
  EXPECT_EQ(p["publish_tf"], "false");
  EXPECT_EQ(p["k"], "7");
  // ... and whatever it leaves out keeps its default.
  EXPECT_EQ(p["radius"], "1.0");
  EXPECT_EQ(p["solver"], "gauss_newton");

  p = nodeletParameters("params:=" + yaml + " threads:=3 publish_tf:=true tf_child_frame:=odom",
                        &problem);
  ASSERT_TRUE(problem.empty()) << problem;
  EXPECT_EQ(p["threads"], "3");
  EXPECT_EQ(p["publish_tf"], "true");
  EXPECT_EQ(p["tf_child_frame"], "odom");
  EXPECT_EQ(p["tf_parent_frame"], "map");
}

}  // namespace
}  // namespace pda_registration

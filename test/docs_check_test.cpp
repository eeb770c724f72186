// The docs checker on tiny fixtures: it must fail, naming the entry, on each kind of mismatch.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "docs_check/reference_docs.hpp"

namespace pda_registration {
namespace {

using namespace docs_check;

const char* const kCfg = R"(
gen = ParameterGenerator()
group = gen.add_group("association")
group.add("alpha", int_t, 0, "first", 5, 1, 50)
# group.add("commented_out", int_t, 0, "not an entry", 1, 0, 2)
modes = gen.enum([gen.const("fast", str_t, "fast", "a constant, not an entry")], "modes")
gen.add("beta", str_t, 0, "second", "fast", edit_method=modes)
)";

const char* const kPage = R"(# Page
### Parameters

| parameter | meaning |
|---|---|
| `alpha` | first |
| `gamma` | gone |

### `launch/a.launch`

| arg | default | meaning |
|---|---|---|
| `topic` | `/points` | input |
| `bag` | *(required)* | the bag |
| `flag` | `true` | computed in truth |
| `old` | `1` | removed from the file |
)";

const char* const kLaunch = R"xml(<launch>
  <!-- <arg name="in_a_comment" default="1"/> -->
  <arg name="topic" default="/points"/>
  <arg name="bag"/>
  <arg name="flag" value="$(eval arg('topic') != '')"/>
  <include file="other.launch">
    <arg name="passed_on" value="$(arg topic)"/>
  </include>
</launch>
)xml";

bool mentions(const std::vector<std::string>& problems, const std::string& text) {
  for (const std::string& problem : problems) {
    if (problem.find(text) != std::string::npos) return true;
  }
  return false;
}

TEST(DocsCheck, FindsTheCfgEntriesButNotGroupsConstantsOrComments) {
  EXPECT_EQ(dynamicReconfigureEntries(kCfg), (std::vector<std::string>{"alpha", "beta"}));
}

TEST(DocsCheck, FindsTheParametersASourceReads) {
  const char* source = R"(
    s->a = nh.param("tf_timeout", 0.1);
    const std::string t = nh.param<std::string>("target_cloud", "dense");
    // nh.param("commented_out", 1);
    if (!nh.getParam("initial_transform", values)) {}
  )";
  EXPECT_EQ(parametersReadInSource(source),
            (std::vector<std::string>{"tf_timeout", "target_cloud", "initial_transform"}));
}

TEST(DocsCheck, ReportsUndocumentedAndStaleParameters) {
  const auto problems = compareWithTable(dynamicReconfigureEntries(kCfg), "x.cfg", "parameter",
                                         kPage, "page.md", "### Parameters");
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_TRUE(mentions(problems, "undocumented parameter \"beta\" (declared in x.cfg)"));
  EXPECT_TRUE(mentions(problems, "stale parameter \"gamma\""));
}

TEST(DocsCheck, ReportsAMissingHeadingAndAMalformedRow) {
  EXPECT_TRUE(
      mentions(compareWithTable({"alpha"}, "x.cfg", "parameter", kPage, "page.md", "### Not there"),
               "no heading \"### Not there\""));
  const std::string page = "### P\n\n| name | x |\n|---|---|\n| alpha (live) | 1 |\n";
  EXPECT_TRUE(mentions(compareWithTable({"alpha"}, "x.cfg", "parameter", page, "p.md", "### P"),
                       "malformed row"));
}

TEST(DocsCheck, LaunchArgsAreTheFilesOwnNotThosePassedToAnInclude) {
  const auto args = declaredLaunchArgs(kLaunch);
  ASSERT_EQ(args.size(), 3u);
  EXPECT_EQ(args[0].name, "topic");
  EXPECT_EQ(args[0].default_value, "/points");
  EXPECT_EQ(args[1].kind, LaunchArg::Kind::kRequired);
  EXPECT_EQ(args[2].kind, LaunchArg::Kind::kComputed);
}

TEST(DocsCheck, ReportsStaleArgsWrongDefaultsAndStaleLaunchFiles) {
  const auto problems = checkLaunchFile("a.launch", kLaunch, kPage, "page.md");
  EXPECT_EQ(problems.size(), 2u);
  EXPECT_TRUE(mentions(problems, "stale launch arg \"old\""));
  EXPECT_TRUE(mentions(problems, "launch arg \"flag\" of launch/a.launch"));
  EXPECT_TRUE(mentions(
      checkLaunchFile("a.launch", "<launch><arg name=\"new\"/></launch>", kPage, "page.md"),
      "undocumented launch arg \"new\""));
  EXPECT_TRUE(mentions(staleLaunchFileSections({"b.launch"}, kPage, "page.md"),
                       "launch/a.launch no longer exists"));
  EXPECT_TRUE(staleLaunchFileSections({"a.launch"}, kPage, "page.md").empty());
}

TEST(DocsCheck, AnchorsFollowGitHub) {
  EXPECT_EQ(headingAnchor("pda_bag_eval: tuning on recorded bags"),
            "pda_bag_eval-tuning-on-recorded-bags");
  EXPECT_EQ(headingAnchor("`launch/map_alignment.launch`"), "launchmap_alignmentlaunch");
  EXPECT_EQ(headingAnchor("The issue's criteria: PDA against PCL GICP"),
            "the-issues-criteria-pda-against-pcl-gicp");
  EXPECT_EQ(headingAnchor("pda_simulate \u2014 built-in scenes"), "pda_simulate--built-in-scenes");
}

TEST(DocsCheck, ReportsBrokenFilesAndAnchorsButNotCode) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(::testing::TempDir()) / "docs_check_links";
  fs::create_directories(dir);
  std::ofstream(dir / "other.md") << "# Other\n\n## A section\n\n```sh\n# not a heading\n```\n";
  std::ofstream(dir / "page.md") << "[ok](other.md#a-section) [self](#title)\n"
                                    "# Title\n"
                                    "[gone](missing.md) [bad anchor](other.md#not-a-heading)\n"
                                    "`[in code](missing.md)` [web](https://example.org/x)\n"
                                    "```\n[in a block](missing.md)\n```\n";
  const auto problems = brokenRelativeLinks((dir / "page.md").string());
  EXPECT_EQ(problems.size(), 2u);
  EXPECT_TRUE(mentions(problems, "page.md:3: link to \"missing.md\": no such file"));
  EXPECT_TRUE(mentions(problems, "no heading with the anchor #not-a-heading in other.md"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace pda_registration

// docs/ against the code: every dynamic_reconfigure entry, start-up parameter and launch arg is
// documented, nothing documented is gone, every relative link resolves and the README stays a
// front page. The files are read from the repository (PDA_REPO_DIR), so editing a .cfg, a
// launch file or a page needs no rebuild to re-check.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>

#include "docs_check/reference_docs.hpp"

namespace pda_registration {
namespace {

namespace fs = std::filesystem;
using namespace docs_check;

const fs::path kRepo = PDA_REPO_DIR;
const char* const kNodeletPage = "docs/nodelet.md";
const char* const kLiveHeading = "### Live parameters (dynamic_reconfigure)";
const char* const kStartupHeading = "### Start-up parameters";

std::string read(const fs::path& path) {
  std::ifstream file(path);
  return std::string(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
}

std::vector<fs::path> filesIn(const std::string& folder, const std::string& extension) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(kRepo / folder)) {
    if (entry.path().extension() == extension) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string joined(const std::vector<std::string>& problems) {
  std::string text;
  for (const std::string& problem : problems) text += "\n  " + problem;
  return text;
}

std::vector<std::string> liveParameters() {
  std::vector<std::string> names;
  for (const fs::path& cfg : filesIn("cfg", ".cfg")) {
    for (const std::string& name : dynamicReconfigureEntries(read(cfg))) names.push_back(name);
  }
  return names;
}

// What the nodelet reads at start-up besides the live entries (a live entry may be read too).
std::vector<std::string> startupParameters() {
  const std::vector<std::string> live = liveParameters();
  std::vector<std::string> names;
  for (const fs::path& source : filesIn("src/ros", ".cpp")) {
    for (const std::string& name : parametersReadInSource(read(source))) {
      if (std::find(live.begin(), live.end(), name) == live.end()) names.push_back(name);
    }
  }
  return names;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

TEST(DocsReference, TheParsersFindWhatTheCodeDeclares) {
  // Guards the parsers themselves: an empty list would make the checks below vacuous.
  const std::vector<std::string> live = liveParameters(), startup = startupParameters();
  EXPECT_GE(live.size(), 20u);
  EXPECT_TRUE(contains(live, "k"));
  EXPECT_TRUE(contains(startup, "tf_timeout") && contains(startup, "initial_transform"));
  EXPECT_GE(filesIn("launch", ".launch").size(), 3u);
}

TEST(DocsReference, EveryLiveParameterIsDocumentedAndNoneIsStale) {
  const auto problems = compareWithTable(liveParameters(), "cfg/*.cfg", "parameter",
                                         read(kRepo / kNodeletPage), kNodeletPage, kLiveHeading);
  EXPECT_TRUE(problems.empty()) << joined(problems);
}

TEST(DocsReference, EveryStartupParameterIsDocumentedAndNoneIsStale) {
  const auto problems = compareWithTable(startupParameters(), "src/ros/*.cpp", "parameter",
                                         read(kRepo / kNodeletPage), kNodeletPage, kStartupHeading);
  EXPECT_TRUE(problems.empty()) << joined(problems);
}

TEST(DocsReference, EveryLaunchArgIsDocumentedAndNoneIsStale) {
  const std::string page = read(kRepo / kNodeletPage);
  std::vector<std::string> problems, existing;
  for (const fs::path& launch : filesIn("launch", ".launch")) {
    existing.push_back(launch.filename().string());
    for (const std::string& problem :
         checkLaunchFile(launch.filename().string(), read(launch), page, kNodeletPage)) {
      problems.push_back(problem);
    }
  }
  for (const std::string& problem : staleLaunchFileSections(existing, page, kNodeletPage)) {
    problems.push_back(problem);
  }
  EXPECT_TRUE(problems.empty()) << joined(problems);
}

TEST(DocsReference, ARenamedParameterIsCaughtBothWays) {
  // The real .cfg with its first entry renamed, as a careless edit would leave it.
  const std::string cfg = read(kRepo / "cfg/PdaRegistration.cfg");
  const std::string name = dynamicReconfigureEntries(cfg).at(0);
  const std::string renamed_cfg =
      std::regex_replace(cfg, std::regex("\"" + name + "\""), "\"" + name + "_renamed\"");
  const auto problems =
      compareWithTable(dynamicReconfigureEntries(renamed_cfg), "cfg/PdaRegistration.cfg",
                       "parameter", read(kRepo / kNodeletPage), kNodeletPage, kLiveHeading);
  const std::string all = joined(problems);
  EXPECT_NE(all.find("undocumented parameter \"" + name + "_renamed\""), std::string::npos) << all;
  EXPECT_NE(all.find("stale parameter \"" + name + "\""), std::string::npos) << all;
}

TEST(DocsLinks, EveryRelativeLinkResolves) {
  std::vector<fs::path> pages = filesIn("docs", ".md");
  pages.push_back(kRepo / "README.md");
  std::vector<std::string> problems;
  for (const fs::path& page : pages) {
    for (const std::string& problem : brokenRelativeLinks(page.string())) {
      problems.push_back(problem);
    }
  }
  EXPECT_TRUE(problems.empty()) << joined(problems);
}

TEST(Readme, StaysAFrontPage) {
  EXPECT_LE(fs::file_size(kRepo / "README.md"), 15000u) << "move detail into docs/";
  const std::string readme = read(kRepo / "README.md");
  // CI runs the README's test command: the section and the command must stay.
  EXPECT_NE(readme.find("## The two commands"), std::string::npos);
  EXPECT_NE(readme.find("scripts/test    #"), std::string::npos);
}

}  // namespace
}  // namespace pda_registration

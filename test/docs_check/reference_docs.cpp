#include "docs_check/reference_docs.hpp"

#include <algorithm>
#include <map>
#include <regex>
#include <set>

namespace pda_registration {
namespace docs_check {

namespace {

std::vector<std::string> matchesOf(const std::string& text, const std::regex& pattern) {
  std::vector<std::string> names;
  for (std::sregex_iterator it(text.begin(), text.end(), pattern), end; it != end; ++it) {
    const std::string name = (*it)[1];
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  }
  return names;
}

std::string withoutLineComments(const std::string& text, const std::string& marker) {
  return std::regex_replace(text, std::regex("(^|\n)[ \t]*" + marker + "[^\n]*"), "$1");
}

// "`name`" -> "name"; empty when the cell holds anything else.
std::string backtickedName(const std::string& cell) {
  std::smatch match;
  if (std::regex_match(cell, match, std::regex("`([^`]+)`"))) return match[1];
  return "";
}

std::string launchHeading(const std::string& launch_file) {
  return "### `launch/" + launch_file + "`";
}

// What the default cell of a launch arg's row must say (see the header's convention).
bool defaultCellFits(const LaunchArg& arg, const std::string& cell, std::string* expected) {
  switch (arg.kind) {
    case LaunchArg::Kind::kComputed:
      *expected = "**computed** ... (declared with value=)";
      return cell.rfind("**computed**", 0) == 0;
    case LaunchArg::Kind::kRequired:
      *expected = "*(required)* (no default)";
      return cell == "*(required)*";
    case LaunchArg::Kind::kDefault:
      *expected = arg.default_value.empty() ? "`\"\"`" : "`" + arg.default_value + "`";
      return cell == *expected;
  }
  return false;
}

}  // namespace

std::vector<std::string> dynamicReconfigureEntries(const std::string& cfg_text) {
  static const std::regex kAdd(R"re(\b[A-Za-z_]\w*\.add\(\s*["']([A-Za-z_]\w*)["'])re");
  return matchesOf(withoutLineComments(cfg_text, "#"), kAdd);
}

std::vector<std::string> parametersReadInSource(const std::string& cpp_text) {
  static const std::regex kRead(
      R"re(\b(?:param|getParam)\s*(?:<[^<>()]*>)?\s*\(\s*"([A-Za-z_]\w*)")re");
  return matchesOf(withoutLineComments(cpp_text, "//"), kRead);
}

std::vector<LaunchArg> declaredLaunchArgs(const std::string& launch_xml) {
  static const std::regex kComment("<!--[\\s\\S]*?-->");
  static const std::regex kSelfClosedInclude(R"re(<include\b(?:[^>"']|"[^"]*"|'[^']*')*/>)re");
  static const std::regex kIncludeBlock(R"re(<include\b[\s\S]*?</include\s*>)re");
  static const std::regex kArgTag(R"re(<arg\b((?:[^>"']|"[^"]*"|'[^']*')*)>)re");
  static const std::regex kAttribute(R"re(([\w:-]+)\s*=\s*(?:"([^"]*)"|'([^']*)'))re");
  std::string own = std::regex_replace(launch_xml, kComment, "");
  own = std::regex_replace(own, kSelfClosedInclude, "");
  own = std::regex_replace(own, kIncludeBlock, "");
  std::vector<LaunchArg> args;
  for (std::sregex_iterator tag(own.begin(), own.end(), kArgTag), end; tag != end; ++tag) {
    const std::string attributes = (*tag)[1];
    std::map<std::string, std::string> values;
    for (std::sregex_iterator a(attributes.begin(), attributes.end(), kAttribute); a != end; ++a) {
      values[(*a)[1]] = (*a)[2].matched ? (*a)[2] : (*a)[3];
    }
    LaunchArg arg;
    arg.name = values["name"];
    if (values.count("value")) {
      arg.kind = LaunchArg::Kind::kComputed;
    } else if (values.count("default")) {
      arg.kind = LaunchArg::Kind::kDefault;
      arg.default_value = values["default"];
    }
    args.push_back(arg);
  }
  return args;
}

std::vector<std::string> compareWithTable(const std::vector<std::string>& declared,
                                          const std::string& source, const std::string& what,
                                          const std::string& page, const std::string& page_name,
                                          const std::string& heading) {
  const std::string table = page_name + " under \"" + heading + "\"";
  std::string problem;
  const auto rows = tableAfterHeading(page, heading, &problem);
  if (!problem.empty()) return {page_name + ": " + problem};
  std::vector<std::string> problems;
  std::set<std::string> documented;
  for (const auto& row : rows) {
    const std::string name = row.empty() ? "" : backtickedName(row[0]);
    if (name.empty()) {
      problems.push_back("malformed row in " + table + ": the first cell must be a backticked " +
                         what + " name alone, got \"" + (row.empty() ? "" : row[0]) + "\"");
    } else if (!documented.insert(name).second) {
      problems.push_back(what + " \"" + name + "\" is documented twice in " + table);
    }
  }
  const std::set<std::string> existing(declared.begin(), declared.end());
  for (const std::string& name : declared) {
    if (!documented.count(name)) {
      problems.push_back("undocumented " + what + " \"" + name + "\" (declared in " + source +
                         "): add a row to " + table);
    }
  }
  for (const std::string& name : documented) {
    if (!existing.count(name)) {
      problems.push_back("stale " + what + " \"" + name + "\" documented in " + table +
                         " no longer exists in " + source);
    }
  }
  return problems;
}

std::vector<std::string> checkLaunchFile(const std::string& launch_file,
                                         const std::string& launch_xml, const std::string& page,
                                         const std::string& page_name) {
  const std::vector<LaunchArg> args = declaredLaunchArgs(launch_xml);
  std::vector<std::string> names;
  for (const LaunchArg& arg : args) names.push_back(arg.name);
  const std::string heading = launchHeading(launch_file);
  std::vector<std::string> problems =
      compareWithTable(names, "launch/" + launch_file, "launch arg", page, page_name, heading);
  std::string problem;
  for (const auto& row : tableAfterHeading(page, heading, &problem)) {
    if (row.size() < 2) continue;
    for (const LaunchArg& arg : args) {
      std::string expected;
      if (backtickedName(row[0]) == arg.name && !defaultCellFits(arg, row[1], &expected)) {
        problems.push_back("launch arg \"" + arg.name + "\" of launch/" + launch_file + ": " +
                           page_name + " gives the default as \"" + row[1] + "\", expected " +
                           expected);
      }
    }
  }
  return problems;
}

std::vector<std::string> staleLaunchFileSections(const std::vector<std::string>& existing,
                                                 const std::string& page,
                                                 const std::string& page_name) {
  static const std::regex kHeading(R"re((?:^|\n)### `launch/([^`]+)`)re");
  std::vector<std::string> problems;
  for (const std::string& file : matchesOf(page, kHeading)) {
    if (std::find(existing.begin(), existing.end(), file) == existing.end()) {
      problems.push_back("stale launch file section in " + page_name + ": launch/" + file +
                         " no longer exists");
    }
  }
  return problems;
}

}  // namespace docs_check
}  // namespace pda_registration

#include "docs_check/markdown.hpp"

#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace pda_registration {
namespace docs_check {

namespace {

std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream stream(text);
  for (std::string line; std::getline(stream, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

std::string trim(const std::string& text) {
  const size_t first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

bool startsWith(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0;
}

bool isFence(const std::string& line) { return startsWith(trim(line), "```"); }

// "## Title" -> "Title"; empty when the line is no heading.
std::string headingText(const std::string& line) {
  size_t level = 0;
  while (level < line.size() && line[level] == '#') ++level;
  if (level == 0 || level > 6 || level >= line.size() || line[level] != ' ') return "";
  return trim(line.substr(level + 1));
}

std::vector<std::string> tableCells(const std::string& row) {
  std::vector<std::string> cells;
  std::string inner = trim(row);
  if (startsWith(inner, "|")) inner.erase(0, 1);
  if (!inner.empty() && inner.back() == '|') inner.pop_back();
  std::istringstream stream(inner);
  for (std::string cell; std::getline(stream, cell, '|');) cells.push_back(trim(cell));
  return cells;
}

std::string readText(const std::filesystem::path& path) {
  std::ifstream file(path);
  return std::string(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
}

// Anchors of every heading outside code blocks; a repeated anchor gets "-1", "-2" as on GitHub.
std::set<std::string> headingAnchors(const std::string& markdown) {
  std::set<std::string> anchors;
  std::map<std::string, int> seen;
  bool in_code = false;
  for (const std::string& line : splitLines(markdown)) {
    if (isFence(line)) in_code = !in_code;
    const std::string text = in_code ? "" : headingText(line);
    if (text.empty()) continue;
    const std::string anchor = headingAnchor(text);
    const int repeats = seen[anchor]++;
    anchors.insert(repeats == 0 ? anchor : anchor + "-" + std::to_string(repeats));
  }
  return anchors;
}

// Code spans hold example syntax, not links: `[x](y)` must not be checked.
std::string withoutCodeSpans(const std::string& line) {
  return std::regex_replace(line, std::regex("`[^`]*`"), "");
}

}  // namespace

std::vector<std::vector<std::string>> tableAfterHeading(const std::string& markdown,
                                                        const std::string& heading,
                                                        std::string* problem) {
  const std::vector<std::string> lines = splitLines(markdown);
  size_t i = 0;
  while (i < lines.size() && lines[i] != heading) ++i;
  if (i == lines.size()) {
    *problem = "no heading \"" + heading + "\"";
    return {};
  }
  std::vector<std::vector<std::string>> rows;
  bool in_code = false;
  for (++i; i < lines.size(); ++i) {
    if (isFence(lines[i])) in_code = !in_code;
    if (in_code) continue;
    if (!headingText(lines[i]).empty()) break;
    if (!startsWith(trim(lines[i]), "|")) continue;
    // The table: header, separator, then rows until the first line that is not a row.
    for (i += 2; i < lines.size() && startsWith(trim(lines[i]), "|"); ++i) {
      rows.push_back(tableCells(lines[i]));
    }
    return rows;
  }
  *problem = "no table after the heading \"" + heading + "\"";
  return {};
}

std::string headingAnchor(const std::string& heading_text) {
  // UTF-8 punctuation GitHub drops from anchors (the ASCII ones are dropped below).
  static const std::vector<std::string> kDroppedPunctuation = {
      "\u2013", "\u2014", "\u2026", "\u2190", "\u2192", "\u00d7",
      "\u00b0", "\u00b7", "\u2018", "\u2019", "\u201c", "\u201d"};
  std::string anchor;
  for (size_t i = 0; i < heading_text.size();) {
    const unsigned char c = static_cast<unsigned char>(heading_text[i]);
    if (c < 0x80) {
      if (std::isalnum(c)) anchor += static_cast<char>(std::tolower(c));
      if (c == ' ') anchor += '-';
      if (c == '-' || c == '_') anchor += static_cast<char>(c);
      ++i;
      continue;
    }
    const size_t length = c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : 2;
    const std::string character = heading_text.substr(i, length);
    bool dropped = false;
    for (const std::string& punctuation : kDroppedPunctuation) {
      dropped = dropped || character == punctuation;
    }
    if (!dropped) anchor += character;
    i += length;
  }
  return anchor;
}

std::vector<std::string> brokenRelativeLinks(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path page(path);
  const std::regex link(R"re(\]\(([^)\s]+)(\s+"[^"]*")?\))re");
  std::vector<std::string> broken;
  const std::vector<std::string> lines = splitLines(readText(page));
  bool in_code = false;
  for (size_t n = 0; n < lines.size(); ++n) {
    if (isFence(lines[n])) in_code = !in_code;
    if (in_code) continue;
    const std::string line = withoutCodeSpans(lines[n]);
    for (std::sregex_iterator it(line.begin(), line.end(), link), end; it != end; ++it) {
      const std::string target = (*it)[1];
      if (startsWith(target, "http://") || startsWith(target, "https://") ||
          startsWith(target, "mailto:")) {
        continue;
      }
      const size_t hash = target.find('#');
      const std::string file = target.substr(0, hash);
      const std::string anchor = hash == std::string::npos ? "" : target.substr(hash + 1);
      const fs::path resolved = file.empty() ? page : page.parent_path() / file;
      const std::string where = path + ":" + std::to_string(n + 1) + ": link to \"" + target + "\"";
      if (!fs::exists(resolved)) {
        broken.push_back(where + ": no such file");
        continue;
      }
      if (anchor.empty() || resolved.extension() != ".md") continue;
      if (headingAnchors(readText(resolved)).count(anchor) == 0) {
        broken.push_back(where + ": no heading with the anchor #" + anchor + " in " +
                         resolved.filename().string());
      }
    }
  }
  return broken;
}

}  // namespace docs_check
}  // namespace pda_registration

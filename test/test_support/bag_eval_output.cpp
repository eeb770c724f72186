#include "test_support/bag_eval_output.hpp"

#include <gtest/gtest.h>

#include <regex>
#include <sstream>

#include "test_support/command_run.hpp"

namespace pda_registration {
namespace testing_support {

namespace {

std::vector<std::string> splitCsvLine(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"' && quoted && i + 1 < line.size() && line[i + 1] == '"') {
      fields.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

}  // namespace

Csv readCsv(const std::string& path) {
  Csv csv;
  std::istringstream in(readFile(path));
  std::string line;
  if (std::getline(in, line)) csv.header = splitCsvLine(line);
  while (std::getline(in, line)) {
    const std::vector<std::string> fields = splitCsvLine(line);
    EXPECT_EQ(fields.size(), csv.header.size()) << line;
    std::map<std::string, std::string> row;
    for (size_t i = 0; i < fields.size() && i < csv.header.size(); ++i) {
      row[csv.header[i]] = fields[i];
    }
    csv.rows.push_back(row);
  }
  return csv;
}

std::vector<std::vector<std::string>> summaryRows(const std::string& markdown) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(markdown);
  std::string line;
  const std::regex data_row(R"(^\| [0-9]+ \|.*)");
  while (std::getline(in, line)) {
    if (!std::regex_match(line, data_row)) continue;
    std::vector<std::string> cells;
    std::istringstream cell_stream(line.substr(1));
    std::string cell;
    while (std::getline(cell_stream, cell, '|')) {
      cells.push_back(std::regex_replace(cell, std::regex("^ +| +$"), ""));
    }
    rows.push_back(cells);
  }
  return rows;
}

}  // namespace testing_support
}  // namespace pda_registration

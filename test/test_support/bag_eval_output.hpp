#pragma once
// pda_bag_eval's outputs read back for checking: its CSV as rows of named fields and the data rows
// of its markdown summary table.

#include <map>
#include <string>
#include <vector>

namespace pda_registration {
namespace testing_support {

/// A CSV file as rows of named fields (quoted fields may hold commas).
struct Csv {
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  double number(size_t row, const std::string& column) const {
    return std::stod(rows.at(row).at(column));
  }
};

/// Reads `path`; a row with another field count than the header fails the current test.
Csv readCsv(const std::string& path);

/// The data rows of a summary's markdown table ("| 1 | ..."), as trimmed cells.
std::vector<std::vector<std::string>> summaryRows(const std::string& markdown);

}  // namespace testing_support
}  // namespace pda_registration

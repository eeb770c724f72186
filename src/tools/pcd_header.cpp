#include "pda_registration/tools/pcd_header.hpp"

#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace pda_registration {
namespace {

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  std::string word;
  while (in >> word) out.push_back(word);
  return out;
}

bool parseCount(const std::string& text, unsigned long long* value) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos ||
      text.size() > 12) {
    return false;
  }
  *value = std::stoull(text);
  return true;
}

}  // namespace

bool checkPcdHeader(const std::string& path, std::string* error) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    *error = "cannot open";
    return false;
  }
  return checkPcdHeader(file, error);
}

bool checkPcdHeader(std::istream& file, std::string* error) {
  std::map<std::string, std::vector<std::string>> header;
  std::string line;
  // A header is a few hundred bytes; 64 lines without DATA means this is not one.
  for (int lines = 0; lines < 64 && std::getline(file, line); ++lines) {
    if (line.size() > 4096) break;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> items = words(line);
    if (items.empty()) continue;
    header[items[0]] = std::vector<std::string>(items.begin() + 1, items.end());
    if (items[0] == "DATA") break;
  }
  for (const char* key : {"FIELDS", "SIZE", "TYPE", "WIDTH", "HEIGHT", "POINTS", "DATA"}) {
    if (!header.count(key)) {
      *error = std::string("no PCD header (missing ") + key + ")";
      return false;
    }
  }
  const size_t fields = header["FIELDS"].size();
  if (fields == 0 || header["SIZE"].size() != fields || header["TYPE"].size() != fields ||
      (header.count("COUNT") && header["COUNT"].size() != fields)) {
    *error = "PCD header: FIELDS, SIZE, TYPE and COUNT disagree";
    return false;
  }
  unsigned long long point_size = 0;
  for (size_t i = 0; i < fields; ++i) {
    unsigned long long size = 0, count = 1;
    if (!parseCount(header["SIZE"][i], &size) ||
        (size != 1 && size != 2 && size != 4 && size != 8) ||
        (header.count("COUNT") && (!parseCount(header["COUNT"][i], &count) || count == 0)) ||
        header["TYPE"][i].size() != 1 ||
        std::string("IUF").find(header["TYPE"][i]) == std::string::npos) {
      *error = "PCD header: bad SIZE/TYPE/COUNT for field '" + header["FIELDS"][i] + "'";
      return false;
    }
    // At most 8 x 10^12 per field and 2048 fields on a 4096-byte line: cannot overflow.
    point_size += size * count;
  }
  // Counts have up to 12 digits, so products of two can pass 2^64: multiplied with an overflow
  // check, or a wrapped product could make an absurd header look consistent.
  unsigned long long width = 0, height = 0, points = 0, cells = 0;
  if (header["WIDTH"].size() != 1 || header["HEIGHT"].size() != 1 || header["POINTS"].size() != 1 ||
      !parseCount(header["WIDTH"][0], &width) || !parseCount(header["HEIGHT"][0], &height) ||
      !parseCount(header["POINTS"][0], &points) || __builtin_mul_overflow(width, height, &cells) ||
      cells != points) {
    *error = "PCD header: WIDTH x HEIGHT does not equal POINTS";
    return false;
  }
  const std::string data = header["DATA"].empty() ? "" : header["DATA"][0];
  if (data != "ascii" && data != "binary" && data != "binary_compressed") {
    *error = "PCD header: DATA must be ascii, binary or binary_compressed";
    return false;
  }
  const std::streamoff data_start = file.tellg();
  file.seekg(0, std::ios::end);
  const unsigned long long remaining =
      data_start < 0 ? 0 : static_cast<unsigned long long>(file.tellg() - data_start);
  unsigned long long data_bytes = 0;
  if (data == "binary" &&
      (__builtin_mul_overflow(points, point_size, &data_bytes) || remaining < data_bytes)) {
    *error = "PCD data is shorter than POINTS x point size";
    return false;
  }
  if (data == "binary_compressed" && points > 0 && remaining < 8) {
    *error = "PCD compressed data is missing";
    return false;
  }
  return true;
}

}  // namespace pda_registration

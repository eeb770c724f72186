#include "pda_registration/core/transform_io.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <vector>

#include "pda_registration/core/nearest_rotation.hpp"

namespace pda_registration {

bool parseTransform(const std::string& text, Eigen::Isometry3d* T, std::string* error) {
  std::vector<double> values;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::string word;
    while (words >> word) {
      char* end = nullptr;
      const double v = std::strtod(word.c_str(), &end);
      if (end == word.c_str() || *end != '\0') {
        *error = "not a number: '" + word + "'";
        return false;
      }
      values.push_back(v);
    }
  }
  if (values.size() != 16) {
    *error = "expected 16 numbers (4x4 matrix), found " + std::to_string(values.size());
    return false;
  }
  Eigen::Matrix4d m;
  for (int i = 0; i < 16; ++i) m(i / 4, i % 4) = values[i];
  if (!m.allFinite()) {
    *error = "matrix contains NaN or Inf";
    return false;
  }
  if ((m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm() > 1e-9) {
    *error = "last row must be 0 0 0 1";
    return false;
  }
  Eigen::Matrix3d rotation;
  if (!nearestRotation(m.topLeftCorner<3, 3>(), &rotation)) {
    *error = "upper-left 3x3 block is not a rotation";
    return false;
  }
  *T = Eigen::Isometry3d::Identity();
  T->linear() = rotation;
  T->translation() = m.topRightCorner<3, 1>();
  return true;
}

bool readTransformFile(const std::string& path, Eigen::Isometry3d* T, std::string* error) {
  std::ifstream file(path);
  if (!file) {
    *error = "cannot open '" + path + "'";
    return false;
  }
  std::stringstream text;
  text << file.rdbuf();
  if (!parseTransform(text.str(), T, error)) {
    *error = "'" + path + "': " + *error;
    return false;
  }
  return true;
}

std::string formatTransform(const Eigen::Isometry3d& T) {
  std::ostringstream out;
  out << std::setprecision(17);
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) out << (c ? " " : "") << T.matrix()(r, c);
    out << '\n';
  }
  return out.str();
}

bool writeTransformFile(const std::string& path, const Eigen::Isometry3d& T, std::string* error) {
  std::ofstream file(path);
  if (!(file << formatTransform(T))) {
    *error = "cannot write '" + path + "'";
    return false;
  }
  return true;
}

}  // namespace pda_registration

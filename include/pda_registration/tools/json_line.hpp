#pragma once
// Builds one JSON object on one line, for machine-readable tool output.

#include <Eigen/Geometry>
#include <sstream>
#include <string>

namespace pda_registration {

class JsonLine {
 public:
  JsonLine& add(const std::string& key, double value);
  JsonLine& add(const std::string& key, int value) { return add(key, static_cast<double>(value)); }
  JsonLine& add(const std::string& key, size_t value) {
    return add(key, static_cast<double>(value));
  }
  JsonLine& add(const std::string& key, bool value);
  JsonLine& add(const std::string& key, const std::string& value);
  JsonLine& add(const std::string& key, const char* value) { return add(key, std::string(value)); }
  /// A transform as 16 numbers, row-major.
  JsonLine& add(const std::string& key, const Eigen::Isometry3d& T);
  /// Inserts an already-formatted JSON value (an object or array).
  JsonLine& addRaw(const std::string& key, const std::string& json);
  std::string str() const { return "{" + body_.str() + "}"; }

 private:
  std::ostringstream& next(const std::string& key);
  std::ostringstream body_;
  bool first_ = true;
};

}  // namespace pda_registration

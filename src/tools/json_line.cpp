#include "pda_registration/tools/json_line.hpp"

#include <cmath>
#include <iomanip>

namespace pda_registration {
namespace {
std::string escaped(const std::string& text) {
  std::ostringstream out;
  for (const char c : text) {
    if (c == '"' || c == '\\')
      out << '\\' << c;
    else if (c == '\n')
      out << "\\n";
    else if (static_cast<unsigned char>(c) < 0x20)
      out << ' ';
    else
      out << c;
  }
  return out.str();
}
}  // namespace

std::ostringstream& JsonLine::next(const std::string& key) {
  if (!first_) body_ << ',';
  first_ = false;
  body_ << '"' << escaped(key) << "\":";
  return body_;
}

JsonLine& JsonLine::add(const std::string& key, double value) {
  if (std::isfinite(value))
    next(key) << std::setprecision(10) << value;
  else
    next(key) << "null";  // JSON has no NaN/Inf
  return *this;
}

JsonLine& JsonLine::add(const std::string& key, bool value) {
  next(key) << (value ? "true" : "false");
  return *this;
}

JsonLine& JsonLine::add(const std::string& key, const std::string& value) {
  next(key) << '"' << escaped(value) << '"';
  return *this;
}

JsonLine& JsonLine::add(const std::string& key, const Eigen::Isometry3d& T) {
  std::ostream& out = next(key);
  out << std::setprecision(10) << '[';
  for (int i = 0; i < 16; ++i) out << (i ? "," : "") << T.matrix()(i / 4, i % 4);
  out << ']';
  return *this;
}

JsonLine& JsonLine::addRaw(const std::string& key, const std::string& json) {
  next(key) << json;
  return *this;
}

}  // namespace pda_registration

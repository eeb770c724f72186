#include "pda_registration/tools/command_line.hpp"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>

namespace pda_registration {

std::vector<std::string> splitList(const std::string& text, char separator) {
  std::vector<std::string> items;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, separator)) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

bool parseNumber(const std::string& text, double* value, bool allow_infinity) {
  if (text == "inf" || text == "+inf" || text == "infinity") {
    if (!allow_infinity) return false;
    *value = std::numeric_limits<double>::infinity();
    return true;
  }
  if (text.empty()) return false;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (*end != '\0' || !std::isfinite(v)) return false;
  *value = v;
  return true;
}

std::string escapeControlCharacters(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (byte < 0x20 || byte == 0x7f) {
      static const char kHex[] = "0123456789abcdef";
      out += std::string("\\x") + kHex[byte >> 4] + kHex[byte & 0xf];
    } else {
      out += c;
    }
  }
  return out;
}

std::string quoted(const std::string& text) { return "'" + escapeControlCharacters(text) + "'"; }

int reportError(const std::string& tool, const std::string& message) {
  std::cerr << tool << ": error: " << escapeControlCharacters(message) << "\n";
  return 2;
}

CommandLine::CommandLine(std::set<std::string> value_flags, std::set<std::string> switch_flags)
    : value_flags_(std::move(value_flags)), switch_flags_(std::move(switch_flags)) {}

bool CommandLine::setError(const std::string& message) {
  error_ = message;
  return false;
}

bool CommandLine::parse(int argc, const char* const* argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument.rfind("--", 0) != 0) return setError("unexpected argument " + quoted(argument));
    std::string flag = argument.substr(2);
    std::string value;
    const size_t equals = flag.find('=');
    const bool inline_value = equals != std::string::npos;
    if (inline_value) {
      value = flag.substr(equals + 1);
      flag = flag.substr(0, equals);
    }
    if (switch_flags_.count(flag)) {
      if (inline_value) return setError("--" + flag + " takes no value");
      values_[flag] = "";
    } else if (value_flags_.count(flag)) {
      if (!inline_value) {
        if (i + 1 >= argc) return setError("--" + flag + " needs a value");
        value = argv[++i];
      }
      values_[flag] = value;
    } else {
      return setError("unknown flag " + quoted("--" + flag) + " (see --help)");
    }
  }
  return true;
}

bool CommandLine::has(const std::string& flag) const { return values_.count(flag) > 0; }

std::string CommandLine::text(const std::string& flag, const std::string& fallback) const {
  const auto it = values_.find(flag);
  return it == values_.end() ? fallback : it->second;
}

bool CommandLine::number(const std::string& flag, double* value, double min, double max) {
  if (!has(flag)) return true;
  double v = 0.0;
  const bool allow_infinity = std::isinf(max);
  if (!parseNumber(text(flag), &v, allow_infinity) || v < min || v > max) {
    std::ostringstream message;
    message << "--" << flag << ": " << quoted(text(flag)) << " is not a number in [" << min << ", "
            << max << "]";
    return setError(message.str());
  }
  *value = v;
  return true;
}

bool CommandLine::integer(const std::string& flag, int* value, int min, int max) {
  if (!has(flag)) return true;
  const std::string& t = text(flag);
  char* end = nullptr;
  const long v = std::strtol(t.c_str(), &end, 10);
  if (t.empty() || *end != '\0' || v < min || v > max) {
    std::ostringstream message;
    message << "--" << flag << ": " << quoted(t) << " is not an integer in [" << min << ", " << max
            << "]";
    return setError(message.str());
  }
  *value = static_cast<int>(v);
  return true;
}

bool CommandLine::numberList(const std::string& flag, std::vector<double>* values, double min,
                             double max, bool allow_infinity) {
  if (!has(flag)) return true;
  std::vector<double> parsed;
  std::istringstream items(text(flag));
  std::string item;
  while (std::getline(items, item, ',')) {
    double v = 0.0;
    if (!parseNumber(item, &v, allow_infinity) || v < min || (v > max && !std::isinf(v))) {
      std::ostringstream message;
      message << "--" << flag << ": " << quoted(item) << " is not a number in [" << min << ", "
              << max << "]" << (allow_infinity ? " or inf" : "");
      return setError(message.str());
    }
    parsed.push_back(v);
  }
  if (parsed.empty()) return setError("--" + flag + ": empty list");
  *values = parsed;
  return true;
}

}  // namespace pda_registration

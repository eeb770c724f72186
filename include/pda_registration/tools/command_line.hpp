#pragma once
// A small "--flag value" parser shared by the command-line tools. Every error is one line that
// names the flag, so a tool can print it and exit with code 2.

#include <map>
#include <set>
#include <string>
#include <vector>

namespace pda_registration {

class CommandLine {
 public:
  /// `value_flags` take a value ("--k 10"), `switch_flags` do not ("--help").
  CommandLine(std::set<std::string> value_flags, std::set<std::string> switch_flags);

  /// Returns false with error() set on an unknown flag, a missing value or a stray argument.
  bool parse(int argc, const char* const* argv);
  const std::string& error() const { return error_; }
  /// Records an error found by the caller (e.g. a bad enum value); always returns false.
  bool setError(const std::string& message);

  bool has(const std::string& flag) const;
  std::string text(const std::string& flag, const std::string& fallback = "") const;

  // Typed getters: on a malformed or out-of-range value they set error() and return false.
  bool number(const std::string& flag, double* value, double min, double max);
  bool integer(const std::string& flag, int* value, int min, int max);
  /// Comma-separated list ("1,5,10"); "inf" accepted when allow_infinity.
  bool numberList(const std::string& flag, std::vector<double>* values, double min, double max,
                  bool allow_infinity = false);

 private:
  std::set<std::string> value_flags_, switch_flags_;
  std::map<std::string, std::string> values_;
  std::string error_;
};

/// The non-empty items of a separated list ("a,,b" -> a, b).
std::vector<std::string> splitList(const std::string& text, char separator = ',');

/// Parses one number; "inf" only when allow_infinity. False on trailing junk or NaN.
bool parseNumber(const std::string& text, double* value, bool allow_infinity);

/// `text` with control characters escaped (\n, \r, \xNN), so it prints as one line.
std::string escapeControlCharacters(const std::string& text);

/// `text` in single quotes, escaped as above: an error that echoes a command-line word stays one
/// line, whatever bytes the word holds.
std::string quoted(const std::string& text);

/// The tools' one way to fail on bad input: prints "tool: error: message" as one line on stderr
/// (a path or bag topic in the message may hold any byte) and returns exit code 2.
int reportError(const std::string& tool, const std::string& message);

}  // namespace pda_registration

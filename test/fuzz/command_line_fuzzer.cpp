// The tools' command line: CommandLine::parse, the typed getters and readSettingsFlags, as
// pda_align and pda_bag_eval use them. The input is argv: words separated by NUL bytes (a real
// argv word may hold any other byte, newlines included). Every refusal is a one-line error
// (the tools print it and exit 2); every accepted number is finite and within its flag's range.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_invariant.hpp"
#include "pda_registration/tools/settings_flags.hpp"

using namespace pda_registration;

namespace {

std::vector<std::string> splitAtNul(const uint8_t* data, size_t size) {
  std::vector<std::string> words(1);
  for (size_t i = 0; i < size; ++i) {
    if (data[i] == '\0') {
      words.emplace_back();
    } else {
      words.back() += static_cast<char>(data[i]);
    }
  }
  return words;
}

void requireOneLineError(const CommandLine& cl, const char* what) {
  fuzzing::require(fuzzing::isOneLineMessage(cl.error()), what, cl.error());
}

// pda_bag_eval's way: grid flags as comma-separated lists, the others through readSettingsFlags.
void readAsParameterGrid(CommandLine cl) {
  MethodSettings settings;
  if (!readSettingsFlags(&cl, &settings, {"k", "nu", "radius", "anisotropy"})) {
    requireOneLineError(cl, "readSettingsFlags (with skipped flags) error is one line");
    return;
  }
  std::vector<double> nus;
  if (!cl.numberList("nu", &nus, 1e-6, 1e6, true)) {
    requireOneLineError(cl, "numberList error is one line");
    return;
  }
  for (double nu : nus) fuzzing::require(nu >= 1e-6 && !std::isnan(nu), "list items in range");
}

// pda_align's way: every shared flag read once into the settings.
void readAsSingleRun(CommandLine cl) {
  MethodSettings settings;
  if (!readSettingsFlags(&cl, &settings)) {
    requireOneLineError(cl, "readSettingsFlags error is one line");
    return;
  }
  const RegistrationParameters& p = settings.pda;
  fuzzing::require(p.k >= 1 && p.k <= 1000 && p.radius > 0.0 && std::isfinite(p.radius) &&
                       p.nu > 0.0 && std::isfinite(p.fixed_sigma) && p.threads >= 1,
                   "accepted settings are in range");
  int repeat = 3;
  if (!cl.integer("repeat", &repeat, 1, 1000)) {
    requireOneLineError(cl, "integer error is one line");
  } else {
    fuzzing::require(repeat >= 1 && repeat <= 1000, "accepted integer is in range");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::vector<std::string> words = splitAtNul(data, size);
  std::vector<const char*> argv = {"tool"};
  for (const std::string& word : words) argv.push_back(word.c_str());

  for (const std::string& word : words) {
    double value = 0.0;
    if (parseNumber(word, &value, false)) fuzzing::require(std::isfinite(value), "finite number");
    if (parseNumber(word, &value, true)) fuzzing::require(!std::isnan(value), "number, not NaN");
  }

  CommandLine cl = commandLineWithSettings({"target", "source", "repeat", "perturb"});
  if (!cl.parse(static_cast<int>(argv.size()), argv.data())) {
    requireOneLineError(cl, "parse error is one line");
    return 0;
  }
  readAsSingleRun(cl);
  readAsParameterGrid(cl);
  return 0;
}

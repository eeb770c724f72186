#include "pda_registration/tools/perturbation_levels.hpp"

#include "pda_registration/tools/command_line.hpp"

namespace pda_registration {

bool parsePerturbationLevels(const std::string& text, std::vector<PerturbationLevel>* levels,
                             std::string* bad_item) {
  levels->clear();
  for (const std::string& item : splitList(text, ',')) {
    const std::vector<std::string> parts = splitList(item, ':');
    PerturbationLevel level;
    if (parts.size() != 2 || !parseNumber(parts[0], &level.degrees, false) ||
        !parseNumber(parts[1], &level.metres, false) || level.degrees < 0 || level.metres < 0) {
      *bad_item = item;
      return false;
    }
    levels->push_back(level);
  }
  return true;
}

}  // namespace pda_registration

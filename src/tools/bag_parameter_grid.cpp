#include "pda_registration/tools/bag_parameter_grid.hpp"

#include <set>
#include <sstream>

#include "pda_registration/tools/settings_flags.hpp"

namespace pda_registration {
namespace {

std::vector<std::string> splitItems(const std::string& text) {
  std::vector<std::string> items;
  std::string item;
  std::istringstream in(text);
  while (std::getline(in, item, ',')) items.push_back(item);
  // "1,5," names an empty value: keep it so it is reported rather than silently dropped.
  if (text.empty() || text.back() == ',') items.push_back("");
  return items;
}

// A grid value as the sets' labels show it: the parsed number, so "5" and "5.0" agree.
std::string label(const std::string& flag, const RegistrationParameters& p) {
  std::ostringstream text;
  if (flag == "k") text << p.k;
  if (flag == "nu") text << p.nu;
  if (flag == "radius") text << p.radius;
  if (flag == "anisotropy") text << p.surface_anisotropy;
  return text.str();
}

void copyGridValue(const std::string& flag, const RegistrationParameters& from,
                   RegistrationParameters* to) {
  if (flag == "k") to->k = from.k;
  if (flag == "nu") to->nu = from.nu;
  if (flag == "radius") to->radius = from.radius;
  if (flag == "anisotropy") to->surface_anisotropy = from.surface_anisotropy;
}

// One grid value applied to `settings` through the single-value parser, so lists and single values
// share names, limits and error messages.
bool applyGridValue(const std::string& flag, const std::string& value, CommandLine* reporter,
                    MethodSettings* settings) {
  const std::string option = "--" + flag;
  const char* argv[] = {"pda_bag_eval", option.c_str(), value.c_str()};
  CommandLine single(settingsFlagNames(), {});
  if (!single.parse(3, argv) || !readSettingsFlags(&single, settings)) {
    return reporter->setError(single.error());
  }
  return true;
}

}  // namespace

const std::vector<std::string>& gridFlagNames() {
  static const std::vector<std::string> names = {"k", "nu", "radius", "anisotropy"};
  return names;
}

bool readParameterGrid(CommandLine* cl, std::vector<ParameterSet>* sets) {
  const std::set<std::string> grid_flags(gridFlagNames().begin(), gridFlagNames().end());
  MethodSettings base;
  if (!readSettingsFlags(cl, &base, grid_flags)) return false;

  // Each axis: the distinct values of one grid flag (the default when the flag is absent).
  std::vector<std::vector<RegistrationParameters>> axes;
  for (const std::string& flag : gridFlagNames()) {
    std::vector<RegistrationParameters> axis;
    std::set<std::string> seen;
    const std::vector<std::string> items =
        cl->has(flag) ? splitItems(cl->text(flag)) : std::vector<std::string>{};
    if (items.empty()) axis.push_back(base.pda);
    for (const std::string& item : items) {
      MethodSettings settings = base;
      if (!applyGridValue(flag, item, cl, &settings)) return false;
      if (seen.insert(label(flag, settings.pda)).second) axis.push_back(settings.pda);
    }
    axes.push_back(axis);
  }

  // All combinations, the first axis varying slowest.
  size_t count = 1;
  for (const auto& axis : axes) count *= axis.size();
  sets->clear();
  for (size_t combination = 0; combination < count; ++combination) {
    ParameterSet set;
    set.id = static_cast<int>(combination) + 1;
    set.parameters = base.pda;
    size_t rest = combination;
    std::vector<size_t> choice(axes.size());
    for (size_t a = axes.size(); a-- > 0;) {
      choice[a] = rest % axes[a].size();
      rest /= axes[a].size();
    }
    for (size_t a = 0; a < axes.size(); ++a) {
      copyGridValue(gridFlagNames()[a], axes[a][choice[a]], &set.parameters);
      set.values.push_back(label(gridFlagNames()[a], set.parameters));
    }
    const std::string invalid = validateParameters(set.parameters);
    if (!invalid.empty()) {
      std::ostringstream message;
      message << "parameter set " << set.id << " (";
      for (size_t a = 0; a < set.values.size(); ++a) {
        message << (a ? " " : "") << gridFlagNames()[a] << "=" << set.values[a];
      }
      message << "): " << invalid;
      return cl->setError(message.str());
    }
    sets->push_back(set);
  }
  return true;
}

}  // namespace pda_registration

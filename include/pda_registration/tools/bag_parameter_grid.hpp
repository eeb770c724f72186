#pragma once
// The parameter sets pda_bag_eval tries: the shared registration flags, where --k, --nu, --radius
// and --anisotropy may be comma-separated lists; every combination of their values is one set.

#include <string>
#include <vector>

#include "pda_registration/core/registration_parameters.hpp"
#include "pda_registration/tools/command_line.hpp"

namespace pda_registration {

/// The flags (without "--") that accept a comma-separated grid, in the order they vary:
/// the first is the slowest.
const std::vector<std::string>& gridFlagNames();

struct ParameterSet {
  int id = 0;                       ///< 1-based, in combination order
  std::vector<std::string> values;  ///< one per gridFlagNames() entry, as a person reads it
  RegistrationParameters parameters;
};

/// Reads the shared registration flags and expands the grids (duplicate values dropped). Each
/// grid value is checked with the same limits as the single-value flag. False with
/// command_line->error() set on a bad value or a combination validateParameters rejects.
bool readParameterGrid(CommandLine* command_line, std::vector<ParameterSet>* sets);

}  // namespace pda_registration

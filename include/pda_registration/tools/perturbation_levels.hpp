#pragma once
// Perturbation levels as the accuracy tools take them: "DEGREES:METRES,..." (e.g. 5:0.25), each
// the size of the random rotation and translation added to the ground truth for one row.

#include <string>
#include <vector>

namespace pda_registration {

struct PerturbationLevel {
  double degrees = 0.0;
  double metres = 0.0;
};

/// Parses "2:0.10,5:0.25"; false with `bad_item` set to the first item that is not
/// DEGREES:METRES with both non-negative.
bool parsePerturbationLevels(const std::string& text, std::vector<PerturbationLevel>* levels,
                             std::string* bad_item);

}  // namespace pda_registration

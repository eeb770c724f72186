#include "pda_registration/core/wider_search.hpp"

#include <algorithm>

#include "pda_registration/core/alignment_verdict.hpp"

namespace pda_registration {

bool widerSearchWarranted(const RegistrationResult& first, const RegistrationParameters& p) {
  return !first.converged && !first.out_of_time && p.max_runs > 1 &&
         residualsSpanTheSearch(p, first.sigma);
}

RegistrationParameters widerSearchParameters(const RegistrationParameters& p) {
  RegistrationParameters wider = p;
  wider.radius = kWiderSearchFactor * p.radius;
  // A radius the user fixed (min_radius >= radius) stays the refine runs' floor, not the wider one.
  wider.min_radius = std::min(p.min_radius, p.radius);
  return wider;
}

bool widerSearchHolds(const RegistrationResult& wide, const RegistrationParameters& p) {
  return wide.converged && !wide.out_of_time && !residualsSpanTheSearch(p, wide.sigma);
}

}  // namespace pda_registration

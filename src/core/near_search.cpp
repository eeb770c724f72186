#include "pda_registration/core/near_search.hpp"

#include <algorithm>

namespace pda_registration {

double stepFollowingRadius(const RegistrationParameters& p, double last_rms_step) {
  const double floor = std::min(std::max(p.min_radius, 0.5 * p.radius), p.radius);
  return std::clamp(kNearSearchSteps * last_rms_step, floor, p.radius);
}

bool nearSearchWarranted(const RegistrationResult& usual, bool usual_questionable) {
  // A kept local start converged near the seed, as a false fit near the seed does as readily.
  return usual_questionable || (usual.converged && usual.local_start);
}

bool nearAnswerReplaces(bool usual_converged, const RegistrationResult& near,
                        bool near_questionable, bool near_fits_more) {
  if (!near.converged || near.out_of_time) return false;
  return usual_converged ? near_fits_more : !near_questionable;
}

bool nearSearchCanRejoin(const RegistrationResult& usual) {
  return usual.converged && !usual.out_of_time && !usual.local_start && !usual.roles_swapped &&
         !usual.search_widened && !usual.warp_polished && usual.sigma > 0.0;
}

bool rejoinsUsualAnswer(const RegistrationParameters& p, const UsualAnswer& usual,
                        double rms_displacement) {
  const double shortest_reach = stepFollowingRadius(p, 0.0);
  return refineRadius(p, usual.sigma * usual.sigma) <= shortest_reach &&
         rms_displacement <= kRejoinSigmas * usual.sigma;
}

}  // namespace pda_registration

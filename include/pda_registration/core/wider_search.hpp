#pragma once
// A wider search for a result that came to rest unresolved. From 20 deg off, a lidar scan of a car
// park gets its ground right at once (height, roll, pitch) while the yaw is set by buildings and
// poles whose points the turn has moved further than the candidate radius: the approach comes to
// rest 11-14 deg short in yaw with sigma as wide as its search (the "unresolved" verdict). Aligned
// again from the seed with the radius doubled, the same scan reaches those structures and converges
// (a held-out car park of pda_simulate, seed 6: 3 -> 5 of 5 from 20 deg; PCL GICP 5 of 5). Only a
// result that already failed pays for it: a converged alignment never runs a second time, but a
// local start that converged after a first that warranted it does (local_start.hpp).

#include "pda_registration/core/registration_parameters.hpp"
#include "pda_registration/core/registration_result.hpp"

namespace pda_registration {

/// The wider search's radius, in units of the user's.
constexpr double kWiderSearchFactor = 2.0;

/// Whether `first` (aligned with `p`) warrants the wider search: it did not converge, for any
/// reason but time (at rest, out of runs, or its overlap lost mid-way), with sigma estimated and
/// as wide as its search (6 sigma >= radius), in the multi-run mode.
bool widerSearchWarranted(const RegistrationResult& first, const RegistrationParameters& p);

/// `p` with the radius widened by kWiderSearchFactor; min_radius at most the user's radius (the
/// refine runs still shrink the radius to 6 sigma, not below it, so a converged result ends on
/// the user's radius and finer). The statistics of its result (overlap, support) are counted
/// within the wider radius.
RegistrationParameters widerSearchParameters(const RegistrationParameters& p);

/// Whether the wider search's result replaces the first: converged, and resolved at the user's
/// radius (6 sigma below it), not only at the wider one's.
bool widerSearchHolds(const RegistrationResult& wide, const RegistrationParameters& p);

}  // namespace pda_registration

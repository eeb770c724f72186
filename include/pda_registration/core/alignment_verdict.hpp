#pragma once
// The verdict on a finished alignment: converged, or not with a reason a person can act on
// (docs/algorithm.md "The verdict"). Checked in order: the runs did not come to rest; the
// geometry is degenerate; the residuals are as wide as the search ("unresolved"); too little
// of the source supports the estimate ("unsupported").

#include "pda_registration/core/em_run.hpp"
#include "pda_registration/core/registration_parameters.hpp"
#include "pda_registration/core/registration_result.hpp"

namespace pda_registration {

/// True when 6 sigma reaches the candidate radius (sigma estimated): the refine runs narrow the
/// candidates to 6 sigma, so here the radius cut them instead and the residuals are as wide as
/// the search itself.
bool residualsSpanTheSearch(const RegistrationParameters& p, double sigma);

/// Sets result->converged and result->reason from the result's statistics. `came_to_rest`: the
/// runs stopped on their own (not at the budget); `last_run_step`: the last run's move;
/// `search_name`: what p.radius is, in the "unresolved" reason (a near search judges its answer
/// against its own reach).
void judgeConvergence(const RegistrationParameters& p, bool came_to_rest,
                    const Increment& last_run_step, RegistrationResult* result,
                    const char* search_name = "radius");

}  // namespace pda_registration

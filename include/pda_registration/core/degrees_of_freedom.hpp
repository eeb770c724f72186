#pragma once
// The Student-t's degrees of freedom nu, estimated from the data by EM as sigma is (the ECM update
// of Liu & Rubin 1995, "ML estimation of the t distribution using EM and its extensions").
//
// With the latent precision w of each source point and its candidate association, the E-step
// gives, per candidate, the posterior P(a_i) and u_i = E[w | a_i] = (nu + d) / (nu + m_i). The
// expected complete-data log-likelihood is then maximised over nu by the root of
//   log(nu/2) - psi(nu/2) + 1 + mean_j sum_i P(a_i) (log u_i - u_i) + psi((nu_old + d)/2)
//     - log((nu_old + d)/2) = 0,
// which is monotone in nu. How heavy the residuals' tails are (parts of one map the other never
// saw, sampling coincidences, non-rigid drift) differs from pair to pair; a constant nu suits
// some and not others, so nu follows the data like sigma does.

#include "pda_registration/core/registration_parameters.hpp"

namespace pda_registration {

/// Bounds of the estimate. Below 1 the t has no mean; above kMaxDegreesOfFreedom it is Gaussian
/// for every residual EM meets.
constexpr double kMinDegreesOfFreedom = 1.0;
constexpr double kMaxDegreesOfFreedom = 60.0;

/// True when nu is estimated from the data (not fixed) and the estimate sits at the floor: the
/// residuals are as heavy-tailed as the model allows, the mark of a result that rests on a
/// fraction of the points. The ECM update clamps nu to the floor: an estimate there is exactly it.
bool nuEstimatedAtFloor(const RegistrationParameters& p, double nu);

/// The digamma function psi(x) for x > 0.
double digamma(double x);

/// One ECM update of nu, in [kMinDegreesOfFreedom, kMaxDegreesOfFreedom]. (Not rounded: ECM's
/// steps shrink near the optimum, and rounding them stalls it short of it; the E-steps weigh on a
/// grid instead, nuOfEStep, while nu itself walks, walkDegreesOfFreedom.) `mean_log_u_minus_u` is
/// mean_j sum_i P(a_i)(log u_i - u_i) from the E-step run with nu_old; `dimension` is d (3).
/// Returns nu_old when the statistic is not finite.
double updateDegreesOfFreedom(double nu_old, double mean_log_u_minus_u, double dimension);

/// The nu an E-step weighs with while EM estimates nu: the estimate's nearest multiple of 1/4 (in
/// the bounds), whose power in the t's density is products and square roots
/// (candidate_weighting.hpp). Any other nu costs a log and an exp per candidate, a quarter of a
/// small alignment (the room's scan on its 0.5-m map: nu 2.01 against 2, 465 against 368 ms for
/// 30 alignments, the same fit). A grid of 1/2 was too coarse near the floor, where a step of it
/// is a third of nu: RGB-D fragments sharing a third of their scene lost 4 of 160 trials.
double nuOfEStep(double nu);

/// One step of nu's ECM walk taken from an E-step run with `e_step_nu` (nuOfEStep(nu)): the step
/// ECM takes from there (updateDegreesOfFreedom), added to nu. The walk keeps its own pace, so
/// the rules that read where it is (nuEstimatedAtFloor) read what they would without the grid;
/// only at a bound, where an update held there is a step beyond it, it goes to the bound.
double walkDegreesOfFreedom(double nu, double e_step_nu, double mean_log_u_minus_u,
                            double dimension);

}  // namespace pda_registration

#pragma once
// A near search: the whole alignment once more from the seed, its first attempt searching only as
// far as its own steps still reach, run where the usual answer is questionable.
//
// The usual search radius (1 m) is reach: from 10-20 deg a lidar scan's yaw needs poles and walls
// metres away. It is also pull: on two RGB-D fragments that share a third of the scene the
// unshared two thirds still find candidates within it (indoors no wall is a metre away), hold
// sigma at 0.14-0.18 m and drag the source along the walkway. Nothing local to a run tells the two
// apart (a lidar scan's ground fits at once, so its steps are small while its yaw still needs the
// far points), so the near search is a second opinion, not the default: where the usual answer is
// questionable by the local start's test (it did not converge, or it converged with nu at its
// floor after moving the source at least the radius from the seed: local_start.hpp), or where it
// is a kept local start (a false fit near the seed passes that start's test as readily), the whole
// alignment (second starts, local start, other direction, wider search) runs again, its first
// attempt's approach and settle runs (and the second starts it asks at nu's floor) searching within
// three times the last run's RMS step, between max(min_radius, radius / 2) and radius: once the
// approach has settled, the unshared points a metre away stop pulling. Its refine runs search no
// further than the last of those runs: where the unshared points hold sigma up, 6 sigma would
// reach them again. Its answer is judged against that reach: 6 sigma at or beyond it is
// "unresolved", as at the whole radius otherwise. Simulated fragments sharing 30-34 % of the scene
// (scripts/benchmark_low_overlap, L = 0.4) from 10 deg / 0.5 m: 24 -> 34 of 40 within 5 cm; from
// 5 deg 36 -> 40.
//
// Where its approach or settle stage ends within 3 sigma of a converged usual answer (and the
// usual refine runs searched no further than it may), the near search has come back to that
// answer: it stops there, and the usual answer stands (rejoinsUsualAnswer). Its refine runs would
// come to the same rest and its fallbacks ask what the usual ones asked: factory_p64 on its 0.5-m
// map from 10 deg ran 15 more runs, a second start and a local start into the same answer.
//
// The near answer replaces a converged usual answer only if it fits more of the overlap (one
// yardstick, second_start.hpp's test); it replaces a failed one only if it converged and is not
// questionable itself (else a converged false fit would stand where the usual answer honestly
// said "not converged").

#include <Eigen/Geometry>

#include "pda_registration/core/registration_parameters.hpp"
#include "pda_registration/core/registration_result.hpp"

namespace pda_registration {

/// How many of the last run's RMS steps a near search's approach and settle runs search within.
constexpr double kNearSearchSteps = 3.0;

/// The candidate radius of a near search's approach or settle run after its first:
/// kNearSearchSteps x `last_rms_step` (the last run's RMS displacement of the source), clamped to
/// [max(min_radius, radius / 2), radius].
double stepFollowingRadius(const RegistrationParameters& p, double last_rms_step);

/// Whether the near search runs after the usual answer: where that is questionable
/// (`usual_questionable`: localStartWarranted) or a kept local start (it converged within the
/// radius of the seed, as a false fit near the seed does as readily: local_start.hpp).
bool nearSearchWarranted(const RegistrationResult& usual, bool usual_questionable);

/// Whether the near search's answer replaces the usual one. `usual_converged`: the usual answer
/// converged; `near_questionable`: the near answer itself warrants a local start
/// (localStartWarranted); `near_fits_more`: it fits more of the overlap than the usual answer
/// (fitsMoreOfTheOverlap, false when it did not converge).
bool nearAnswerReplaces(bool usual_converged, const RegistrationResult& near,
                        bool near_questionable, bool near_fits_more);

/// The usual answer as a near search sees it, where the near search can rejoin it: converged by
/// the usual model's refine runs (nearSearchCanRejoin).
struct UsualAnswer {
  Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();
  double sigma = 0.0;
};

/// How near the usual answer, in its sigmas of RMS displacement of the source, a stage of the near
/// search must end to have rejoined it: the inlier yardstick (3 sigma), half the first refine
/// run's search (6 sigma), so the points' candidates there are the usual answer's. The wide VLP-16
/// scan pairs settle 2.5-2.8 sigma from their usual answer and refine to within 2 mm of it; a
/// false rest the near search turns is metres away.
constexpr double kRejoinSigmas = 3.0;

/// Whether a near search can rejoin `usual`: it converged, and by the model and search the near
/// search's refine runs use (not a local start's outlier class, the other direction's roles, a
/// wider search's radius or a warp polish's Gaussian weights).
bool nearSearchCanRejoin(const RegistrationResult& usual);

/// Whether a near search whose approach or settle stage ends `rms_displacement` from the usual
/// answer (the source points' RMS displacement between the two poses) has rejoined it: its refine
/// runs would start within kRejoinSigmas of the usual answer and search as far as the usual
/// refine runs did there (6 sigma within the shortest reach a near search keeps), so they would
/// come to the same rest; its second starts, local start and the rest would then ask what the
/// usual alignment asked already.
bool rejoinsUsualAnswer(const RegistrationParameters& p, const UsualAnswer& usual,
                        double rms_displacement);

}  // namespace pda_registration

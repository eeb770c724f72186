#pragma once
// A least-squares polish for a result over a warped map. The Student-t weights (eq. 16) give a
// residual a few sigma out a fraction of the weight of one at zero: right against clutter (parts
// of the scene only one cloud saw), not against a warp, where the wide residuals are the same
// surfaces bent and down-weighting them fits the part of the overlap that happens to fit best. The
// covariance's cut test tells the two apart (pose_covariance.hpp): a warp makes the overlap's
// halves disagree as wholes beyond every term of it; clutter and sensor noise do not (no cut fired
// on a right result of any rigid visible or held-out case; on two false rests it did, and the
// polish turned both right: the office lattice directly, a scan pair by way of the wider search,
// once the Gaussian sigma read "unresolved"). Where they disagree, the refine
// runs go on from the result with Gaussian weights (nu = infinity): the rigid least-squares fit
// over the overlap, the fit a warped map's ground truth is defined as. Simulated RGB-D fragments
// with the dense fragment warped by 1 %: 7.6 -> 6.7 cm from that fit when it landed, 4.9 cm since
// the refine runs read normals at the candidates and the polish searches within 6 sigma (PCL GICP
// 6.4-6.8 cm).

#include <functional>

#include "pda_registration/core/em_run.hpp"
#include "pda_registration/core/registration_parameters.hpp"
#include "pda_registration/core/registration_result.hpp"
#include "pda_registration/core/target_index.hpp"

namespace pda_registration {

/// Runs the polish may take before it is abandoned (the warped fragment pairs came to rest in 8-9).
constexpr int kMaxWarpPolishRuns = 30;

/// Whether `result` (its final statistics filled, its estimate's nu `nu`) warrants the polish:
/// converged in the multi-run mode, halves of its overlap that disagree, and nu finite and above
/// its floor (nu at the floor is the second start's sign of a false rest, second_start.hpp, and
/// as heavy a tail as the model allows: clutter, not a smooth warp).
bool warpPolishWarranted(const RegistrationResult& result, const RegistrationParameters& p,
                         double nu);

/// The polish's candidate radius is kPolishRadiusSigmas sigma of its own Gaussian.
constexpr double kPolishRadiusSigmas = 6.0;

/// The polish's candidate radius: 6 sigma, within [floor, radius], where the floor is the shorter
/// of min_radius and `surface_scale` (the length over which the target resolves its surface: the
/// normal map's finest voxel, raised to the scan-line scale on a lidar map; min_radius alone when
/// it is 0). Its weights are normalised over each point's candidates, so with nu = infinity every
/// point that has a candidate counts in full, however far: the radius is the Gaussian's inlier
/// decision. The refine runs' fixed floor (0.25 m) admitted points beyond 6 sigma at full weight
/// and the largest leverage (the warped overlap's ragged edge): the warped fragment pair of seed 2
/// at sigma 3.9 cm, 5.17 cm from its fit with the floor, 4.90 cm at 6 sigma; ten held-out warped
/// pairs 0.24-0.85 cm nearer. The floor keeps a sparse target's samples in reach where sigma is far
/// below its spacing (a lidar lattice, sigma 3 mm); a radius the user fixed (min_radius >= radius)
/// stays.
double polishRadius(const RegistrationParameters& p, double sigma_squared, double surface_scale);

/// Refine runs (every source point, polishRadius) with nu = infinity from `state`, until a
/// run moves less than the epsilons or the runs cycle in place. True when it came to rest (then
/// `state` is the polished estimate); false when the M-step failed, kMaxWarpPolishRuns passed or
/// `out_of_time` said so (`state` untouched: the caller keeps its result). Counts into *runs and
/// *em_iterations either way (the work was done).
bool polishOverAWarp(const TargetIndex& index, const PointList& source,
                     const SurfaceNormalMap& normal_map, double surface_scale,
                     const RegistrationParameters& p, const PoseStep& step_metric,
                     const std::function<bool()>& out_of_time, RegistrationWorkspace* workspace,
                     EmState* state, int* runs, int* em_iterations);

}  // namespace pda_registration

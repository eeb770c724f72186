#pragma once
// One run of the EM loop (paper Sec. IV) on fixed candidate sets, and the pieces the registration
// and its final statistics share: the step between two estimates, the target normals at the
// moved source points, the inputs of the noise shapes.

#include <Eigen/Geometry>
#include <vector>

#include "pda_registration/core/point_list.hpp"
#include "pda_registration/core/pose_step.hpp"
#include "pda_registration/core/registration_parameters.hpp"
#include "pda_registration/core/registration_workspace.hpp"
#include "pda_registration/core/surface_normals.hpp"

namespace pda_registration {

/// How far one estimate is from another.
struct Increment {
  double translation;
  double rotation;  ///< angle [rad]
};

Increment incrementBetween(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to);

/// Below both convergence epsilons.
bool isSmall(const Increment& increment, const RegistrationParameters& p);

/// The part of the EM state that carries over from run to run.
struct EmState {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  double sigma_squared = 0.0;  ///< 0 until the first run estimates it
  double nu = 5.0;             ///< Student-t degrees of freedom (estimated or the parameter)
};

/// One run: EM on the workspace's candidate sets (fixed during the run) until a step is below
/// the epsilons (*settled = true) or max_em_iterations. With a `step_metric`, two successive
/// steps that agree are extrapolated to their tail (run_extrapolation.hpp), compared in it; null:
/// plain EM. Counts iterations into *em_iterations. Returns false when the M-step cannot solve.
bool runEm(const PointList& source, const SurfaceNormalMap& normal_map,
           const RegistrationParameters& p, const PoseStep* step_metric,
           RegistrationWorkspace* workspace, EmState* state, bool* settled, int* em_iterations);

/// The target surface normal at every moved source point (zero where unknown). With
/// `only_with_candidates`, only at the points that have candidates there (zero elsewhere): a
/// run's E-step reads no other, and on a partial overlap most points have none. `memos`, when
/// given, keeps each point's last answer (SurfaceNormalMap::Memo; resized as needed): runs move
/// the points little, and most stay in their voxel.
void lookupNormals(const SurfaceNormalMap& map, const PointList& source, const Eigen::Isometry3d& T,
                   int threads, PointList* normals,
                   const CandidateSets* only_with_candidates = nullptr,
                   std::vector<SurfaceNormalMap::Memo>* memos = nullptr);

/// What the noise shapes of one run are made from: the target normals at the moved source points
/// (not needed by the isotropic model: left empty) and the candidates' sampling spread (sampling
/// model only). Returns the target's thickness, sigma^2's floor from the target's own noise
/// (sampling model; 0 otherwise). The normals are looked up at the points with candidates only,
/// unless `every_point` (the final statistics' degeneracy check reads them all).
double computeShapeInputs(const SurfaceNormalMap& normal_map, const PointList& source,
                          const CandidateSets& candidates, const Eigen::Isometry3d& T,
                          const RegistrationParameters& p, PointList* normals,
                          std::vector<double>* spread, bool every_point = false,
                          std::vector<SurfaceNormalMap::Memo>* memos = nullptr);

}  // namespace pda_registration

#pragma once
// One run of the EM loop (paper Sec. IV) on fixed candidate sets, and the pieces the registration
// and its final statistics share: the step between two estimates, the source points' target
// normals, the inputs of the noise shapes.

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
  /// The outlier class (outlier_class.hpp): on for a local start only; its share w, estimated by
  /// EM from 0.5 (as likely an outlier as not), and the run's search radius, its width.
  bool outlier_class = false;
  double outlier_share = 0.5;
  double search_radius = 0.0;
  /// The sampling model's floor of sigma^2, the target's thickness about its surface
  /// (targetThickness), as measured by the last run whose candidate sets were whole: searched at
  /// the whole radius or beyond (0 until one was). A shorter refine radius truncates the sets.
  double whole_set_thickness = 0.0;
};

/// Where a source point's target normal is read from the normal map. At its nearest candidate, a
/// sample of the surface the point is associated with, the normal is the target's own and changes
/// only when that candidate does; at the moved point it is whatever surface the point's voxel
/// holds, and it jumps whenever the point crosses into another voxel. The refine runs (and the
/// final statistics) read it at the candidate: at the point, those jumps kept a run or two of
/// millimetre steps going after the pose had settled, and near a surface's edge or on a warped
/// map the point's voxel gave another surface's normal (a warped RGB-D fragment pair 6.7 -> 5.1
/// cm). The approach and settle runs read it at the point: there the nearest sample is often on
/// the wrong surface, and its shape would let the point slide along it (the VLP-16 office
/// lattice from 10 deg: 3 of 10 false rests at the candidate, none at the point).
enum class NormalLookup {
  kAtPoint,
  kAtCandidate,
};

/// One run: EM on the workspace's candidate sets (fixed during the run) until a step is below
/// the epsilons (*settled = true) or max_em_iterations. With a `step_metric`, two successive
/// steps that agree are extrapolated to their tail (run_extrapolation.hpp), compared in it; null:
/// plain EM. Counts iterations into *em_iterations. Returns false when the M-step cannot solve.
bool runEm(const PointList& source, const SurfaceNormalMap& normal_map, NormalLookup normals_at,
           const RegistrationParameters& p, const PoseStep* step_metric,
           RegistrationWorkspace* workspace, EmState* state, bool* settled, int* em_iterations);

/// The target surface normal of every source point (zero where unknown): read `normals_at` for
/// the points that have candidates, at the moved point for the others when `every_point` (the
/// final statistics' degeneracy check reads them all), zero otherwise (a run's E-step reads no
/// other, and on a partial overlap most points have none). `memos`, when given, keeps each
/// point's last answer (SurfaceNormalMap::Memo; resized as needed): runs move the points little,
/// and most stay in their voxel.
void lookupNormals(const SurfaceNormalMap& map, const PointList& source, const Eigen::Isometry3d& T,
                   int threads, const CandidateSets& candidates, NormalLookup normals_at,
                   bool every_point, PointList* normals,
                   std::vector<SurfaceNormalMap::Memo>* memos = nullptr);

/// What the noise shapes of one run are made from: the source points' target normals
/// (lookupNormals; not needed by the isotropic model: left empty) and the candidates' sampling
/// spread (sampling model only). Returns the target's thickness, sigma^2's floor from the
/// target's own noise (sampling model and `measure_thickness`; 0 otherwise).
double computeShapeInputs(const SurfaceNormalMap& normal_map, const PointList& source,
                          const CandidateSets& candidates, const Eigen::Isometry3d& T,
                          const RegistrationParameters& p, NormalLookup normals_at,
                          bool every_point, bool measure_thickness, PointList* normals,
                          std::vector<double>* spread,
                          std::vector<SurfaceNormalMap::Memo>* memos = nullptr);

}  // namespace pda_registration

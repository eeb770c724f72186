#pragma once
// The registration engine: EM with Probabilistic Data Association (Agamennoni et al., IROS 2016)
// and the "multiple runs" outer loop.
//
//   PdaRegistration registration(parameters);
//   registration.setTarget(dense_points);            // filtered and indexed once
//   RegistrationResult r = registration.align(sparse_points, T_initial);  // reuse for many sources
//
// align() never throws; a failure is a result with converged = false and a reason.

#include <Eigen/Geometry>
#include <memory>

#include "pda_registration/core/associations.hpp"
#include "pda_registration/core/point_list.hpp"
#include "pda_registration/core/registration_parameters.hpp"
#include "pda_registration/core/registration_result.hpp"
#include "pda_registration/core/surface_normals.hpp"
#include "pda_registration/core/target_index.hpp"

namespace pda_registration {

class PdaRegistration {
 public:
  explicit PdaRegistration(const RegistrationParameters& parameters = RegistrationParameters());

  /// Takes effect from the next align(). Re-indexes the target only if target_voxel_size changed
  /// and rebuilds the normal map only if normal_voxel_size (or the index) changed.
  /// Invalid parameters are stored anyway and make align() report why.
  void setParameters(const RegistrationParameters& parameters);
  const RegistrationParameters& parameters() const { return parameters_; }

  /// Drops non-finite points, downsamples (target_voxel_size), builds the search index and the
  /// surface normal map.
  /// Returns false (with the index cleared) when no finite point is left or indexing fails.
  bool setTarget(PointList target);
  bool hasTarget() const { return target_index_ != nullptr && target_index_->size() > 0; }
  /// The indexed target (after filtering); null before setTarget.
  std::shared_ptr<const TargetIndex> target() const { return target_index_; }
  size_t targetPointsDropped() const { return target_dropped_; }

  /// Aligns `source` to the target starting from T_target_source_initial. When `associations`
  /// is given, it receives the final weighted associations (empty when the alignment could not
  /// run at all).
  RegistrationResult align(const PointList& source,
                           const Eigen::Isometry3d& T_target_source_initial,
                           Associations* associations = nullptr) const;

 private:
  void rebuildIndex();
  void rebuildNormals();
  RegistrationResult alignUnchecked(const PointList& source,
                                    const Eigen::Isometry3d& T_target_source_initial,
                                    Associations* associations) const;

  RegistrationParameters parameters_;
  PointList raw_target_;  // kept so a new target_voxel_size can re-index without a new cloud
  size_t target_dropped_ = 0;
  std::shared_ptr<const TargetIndex> target_index_;
  std::shared_ptr<const SurfaceNormalMap> normal_map_;
};

}  // namespace pda_registration

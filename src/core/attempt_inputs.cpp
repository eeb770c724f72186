#include "pda_registration/core/pda_registration.hpp"
// What one attempt of align() runs on (staged_alignment.cpp): the initial guess checked, the
// source as aligned (source_budget.hpp) and the target's index for it (target_map.hpp).

#include <cmath>
#include <sstream>

#include "pda_registration/core/nearest_rotation.hpp"
#include "pda_registration/core/point_filter.hpp"
#include "pda_registration/core/source_budget.hpp"
#include "pda_registration/core/target_map.hpp"

namespace pda_registration {
namespace {

// Accepts a slightly non-orthonormal rotation (text files round it) and snaps it back; rejects
// anything that is not close to a rigid transform.
bool sanitiseInitialGuess(const Eigen::Isometry3d& initial, Eigen::Isometry3d* out) {
  if (!initial.matrix().allFinite()) return false;
  Eigen::Matrix3d rotation;
  if (!nearestRotation(initial.linear(), &rotation)) return false;
  *out = Eigen::Isometry3d::Identity();
  out->linear() = rotation;
  out->translation() = initial.translation();
  return true;
}

}  // namespace

bool PdaRegistration::prepareAttempt(const PointList& source_input,
                                     const Eigen::Isometry3d& T_initial, AttemptInputs* inputs,
                                     RegistrationResult* result) {
  const RegistrationParameters& p = parameters_;
  const std::string parameter_error = validateParameters(p);
  if (!parameter_error.empty()) {
    result->reason = "invalid parameters: " + parameter_error;
    return false;
  }
  if (!sanitiseInitialGuess(T_initial, &inputs->T)) {
    result->reason = "initial transform is not a finite rigid transform";
    return false;
  }
  result->target_points_dropped = target_map_.droppedPoints();
  result->target_points_total = target_map_.cloudSize();
  if (!hasTarget()) {
    result->reason = "target cloud is empty (no finite points)";
    return false;
  }

  PointList& source = workspace_.source;
  workspace_.search.forget();  // new points in the same memory, perhaps a new target
  const size_t finite_points = countFinitePoints(source_input);
  result->source_points_dropped = source_input.size() - finite_points;
  const bool budgeted_source = prepareAlignedSource(source_input, finite_points, p, &source);
  result->source_points_used = source.size();
  if (source.size() < static_cast<size_t>(p.min_correspondences)) {
    std::ostringstream reason;
    reason << "source cloud has " << source.size() << " finite points ("
           << result->source_points_dropped << " non-finite dropped); at least "
           << p.min_correspondences << " are needed";
    result->reason = reason.str();
    return false;
  }

  // A target much finer than a budgeted source samples it is indexed as its voxel means at the
  // source's spacing; a large one around the region this source can reach from its seed.
  followSourceSpacing(source, budgeted_source);
  const TargetIndexing how = indexing();
  AlignedBox reach;
  if (target_map_.croppingApplies(how)) {
    reach = reachableRegion(source, inputs->T, p.crop_max_translation,
                            p.crop_max_rotation_deg * M_PI / 180.0, p.radius);
  }
  const size_t builds_before = target_map_.builds();
  if (!target_map_.prepare(how, reach)) {
    result->reason =
        "no overlap: the target has no point within reach of the source (bounds "
        "plus crop_max_translation, crop_max_rotation_deg and radius)";
    return false;
  }
  if (target_map_.builds() != builds_before) result->target_index_ms = target_map_.lastBuildMs();
  result->target_cropped = target_map_.cropped();
  result->target_subset_voxel = target_map_.subsetVoxel();
  result->normal_voxel_size = target_map_.normalVoxelSize();
  inputs->index = target_map_.index();
  inputs->normal_map =
      target_map_.normals() ? target_map_.normals() : std::make_shared<const SurfaceNormalMap>();
  result->target_points_used = inputs->index->size();
  return true;
}

}  // namespace pda_registration

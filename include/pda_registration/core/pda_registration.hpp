#pragma once
// The registration engine: EM with Probabilistic Data Association (Agamennoni et al., IROS 2016)
// and the "multiple runs" outer loop.
//
//   PdaRegistration registration(parameters);
//   registration.setTarget(dense_points);            // filtered and indexed once (a large
//                                                    // map: around each source's reach)
//   RegistrationResult r = registration.align(sparse_points, T_initial);  // reuse for many sources
//
// align() never throws; a failure is a result with converged = false and a reason.

#include <Eigen/Geometry>
#include <chrono>
#include <memory>
#include <utility>

#include "pda_registration/core/alignment_trace.hpp"
#include "pda_registration/core/associations.hpp"
#include "pda_registration/core/point_list.hpp"
#include "pda_registration/core/registration_parameters.hpp"
#include "pda_registration/core/registration_result.hpp"
#include "pda_registration/core/registration_workspace.hpp"
#include "pda_registration/core/second_start.hpp"
#include "pda_registration/core/surface_normals.hpp"
#include "pda_registration/core/target_index.hpp"
#include "pda_registration/core/target_map.hpp"

namespace pda_registration {

class PdaRegistration {
 public:
  explicit PdaRegistration(const RegistrationParameters& parameters = RegistrationParameters());

  /// Takes effect from the next align(). A change of target_voxel_size, normal_voxel_size or
  /// crop_above_points re-indexes a whole-cloud target here and a cropped one in the next
  /// align(). Invalid parameters are stored anyway and make align() report why.
  void setParameters(const RegistrationParameters& parameters);
  const RegistrationParameters& parameters() const { return parameters_; }

  /// Drops non-finite points and keeps the cloud. A target of up to crop_above_points points is
  /// downsampled (target_voxel_size) and indexed (kd-tree and surface normal map) here, once; a
  /// larger one is indexed by align() around the region each source can reach (target_map.hpp).
  /// With target_subset, a source thinned to max_source_points is aligned to the target's voxel
  /// means at its spacing: until an align() has seen a source, the target is only kept (align()
  /// indexes it); later targets are indexed here as the last source asked.
  /// Returns false (with the target cleared) when no finite point is left or indexing fails.
  bool setTarget(PointList target);
  bool hasTarget() const { return target_map_.cloudSize() > 0; }
  /// Finite target points kept (before any downsampling or cropping).
  size_t targetCloudSize() const { return target_map_.cloudSize(); }
  /// The current index (after filtering, downsampling and cropping); null before it is built.
  std::shared_ptr<const TargetIndex> target() const { return target_map_.index(); }
  size_t targetPointsDropped() const { return target_map_.droppedPoints(); }
  /// How many times the target has been indexed so far (tests and reports).
  size_t targetIndexBuilds() const { return target_map_.builds(); }

  /// Aligns `source` to the target starting from T_target_source_initial. When `associations`
  /// is given, it receives the final weighted associations (empty when the alignment could not
  /// run at all). Not const: it may (re)index the part of a large target the source can reach.
  RegistrationResult align(const PointList& source,
                           const Eigen::Isometry3d& T_target_source_initial,
                           Associations* associations = nullptr);

  /// Receivers for every run and attempt of the next align() calls (alignment_trace.hpp); an
  /// empty trace (the default) turns it off. The answers are the same either way.
  void setTrace(AlignmentTrace trace) { trace_ = std::move(trace); }

 private:
  TargetIndexing indexing() const;
  /// `abandon_in`: a second start stops (not converged) once it enters the first's basin.
  /// `local_start`: every run uses the outlier class, and the alignment stops (not converged) once
  /// it moves the source further from the seed than its answer could be kept (local_start.hpp).
  RegistrationResult alignUnchecked(const PointList& source,
                                    const Eigen::Isometry3d& T_target_source_initial,
                                    Associations* associations,
                                    const FirstResultBasin* abandon_in = nullptr,
                                    bool local_start = false);
  /// Second alignments from the rotation the first found (two starts, in turn), the first that is
  /// better kept (second_start.hpp).
  void trySecondStart(const PointList& source, const Eigen::Isometry3d& T_initial,
                      std::chrono::steady_clock::time_point started, RegistrationResult* result,
                      Associations* associations);
  /// A failed result: once more from the seed with the outlier class, kept if that converges near
  /// the seed (local_start.hpp).
  void tryLocalStart(const PointList& source, const Eigen::Isometry3d& T_initial,
                     std::chrono::steady_clock::time_point started, RegistrationResult* result,
                     Associations* associations);
  /// A result that came to rest unresolved: once more from the seed with the radius widened,
  /// kept if that converges at a fit (wider_search.hpp).
  void tryWiderSearch(const PointList& source, const Eigen::Isometry3d& T_initial,
                      std::chrono::steady_clock::time_point started, RegistrationResult* result,
                      Associations* associations);
  /// A failed result on a source denser than the target: the other way round, with what is left
  /// of the time limit, kept if that converges (alignment_direction.hpp).
  void tryOtherDirection(const PointList& source, const Eigen::Isometry3d& T_initial,
                         std::chrono::steady_clock::time_point started, RegistrationResult* result,
                         Associations* associations);
  /// The target aligned onto `source` (the denser cloud), answered in the usual direction.
  RegistrationResult alignSwapped(const PointList& source,
                                  const Eigen::Isometry3d& T_target_source_initial,
                                  Associations* associations);
  /// Tells the trace that the attempt named attempt_ has ended (`adopted`: as align()'s answer).
  void traceAttempt(const RegistrationResult& attempt, bool adopted,
                    std::chrono::steady_clock::time_point started) const;

  /// The subset voxel for `source` (as aligned; `budgeted`: thinned to max_source_points): its
  /// spacing, or the current voxel while that still serves; 0 for a source aligned whole.
  void followSourceSpacing(const PointList& source, bool budgeted);

  RegistrationParameters parameters_;
  double subset_voxel_ = 0.0;  // target_subset: the budgeted sources' spacing (0: whole target)
  bool source_seen_ = false;   // target_subset: whether subset_voxel_ has been decided yet
  TargetMap target_map_;
  RegistrationWorkspace workspace_;  // scratch memory kept between alignments
  AlignmentTrace trace_;
  const char* attempt_ = "first";  // the attempt alignUnchecked() is running, for the trace
};

}  // namespace pda_registration

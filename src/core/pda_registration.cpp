#include "pda_registration/core/pda_registration.hpp"

// The engine's entry points: the target, the parameters, and align(), which runs the staged
// alignment (staged_alignment.cpp) and, where its result calls for one, a second start, a local
// start, the other direction or a wider search.

#include <chrono>
#include <cmath>
#include <exception>
#include <sstream>
#include <string>
#include <utility>

#include "pda_registration/core/alignment_direction.hpp"
#include "pda_registration/core/local_start.hpp"
#include "pda_registration/core/pose_covariance.hpp"
#include "pda_registration/core/representative_subset.hpp"
#include "pda_registration/core/second_start.hpp"
#include "pda_registration/core/wider_search.hpp"

namespace pda_registration {
namespace {

// An alignment that align() runs after the first one (a second start, a wider search): it gets
// what is left of the user's time limit, and the user's parameters come back however it ends
// (align() catches what alignUnchecked throws).
class NestedAlignment {
 public:
  NestedAlignment(RegistrationParameters* live, std::chrono::steady_clock::time_point started)
      : live_(live), user_(*live) {
    if (!(user_.time_limit_ms > 0.0)) return;  // no limit
    live_->time_limit_ms = user_.time_limit_ms - std::chrono::duration<double, std::milli>(
                                                     std::chrono::steady_clock::now() - started)
                                                     .count();
    time_left_ = live_->time_limit_ms > 0.0;
  }
  NestedAlignment(const NestedAlignment&) = delete;
  NestedAlignment& operator=(const NestedAlignment&) = delete;
  ~NestedAlignment() { *live_ = user_; }
  /// False when the user's time limit is already spent: the nested alignment is not run.
  bool timeLeft() const { return time_left_; }
  /// timeLeft(); when false, `result` notes that `nested` was cut by the time limit.
  bool timeLeftOrNote(const char* nested, RegistrationResult* result) const;
  /// Notes on `result` that `nested` was cut by the time limit, when it was and was not kept.
  void noteIfCut(const char* nested, bool kept, bool cut, RegistrationResult* result) const;

 private:
  RegistrationParameters* live_;
  const RegistrationParameters user_;
  bool time_left_ = true;
};

// A failed result whose nested alignment (the other direction, a wider search) was cut by the
// user's time limit, or found none of it left, is the deadline's verdict, not the data's: it
// says so, and a caller with a deadline (the nodelet's warm attempts) does not retry it from
// the seed as if the data had rejected it.
void noteCutByTheTimeLimit(const char* nested, double time_limit_ms, RegistrationResult* result) {
  result->out_of_time = true;
  std::ostringstream reason;
  reason << result->reason << "; " << nested << " was cut by the time limit of " << time_limit_ms
         << " ms";
  result->reason = reason.str();
}

bool NestedAlignment::timeLeftOrNote(const char* nested, RegistrationResult* result) const {
  if (!time_left_) noteCutByTheTimeLimit(nested, user_.time_limit_ms, result);
  return time_left_;
}

void NestedAlignment::noteIfCut(const char* nested, bool kept, bool cut,
                                RegistrationResult* result) const {
  if (!kept && cut) noteCutByTheTimeLimit(nested, user_.time_limit_ms, result);
}

// Names the attempt that align() runs while it lives (the trace's label), then restores the last.
class AttemptLabel {
 public:
  AttemptLabel(const char** live, const char* name) : live_(live), before_(*live) { *live = name; }
  AttemptLabel(const AttemptLabel&) = delete;
  AttemptLabel& operator=(const AttemptLabel&) = delete;
  ~AttemptLabel() { *live_ = before_; }

 private:
  const char** live_;
  const char* before_;
};

// What a nested alignment leaves: its result (and associations) replace the first's when `keep`;
// either way the answer counts the indexing both did in this call.
void adoptNested(bool keep, RegistrationResult* nested, Associations* nested_associations,
                 RegistrationResult* result, Associations* associations) {
  if (!keep) {
    result->target_index_ms += nested->target_index_ms;
    return;
  }
  nested->target_index_ms += result->target_index_ms;
  *result = std::move(*nested);
  if (associations) *associations = std::move(*nested_associations);
}

}  // namespace

PdaRegistration::PdaRegistration(const RegistrationParameters& parameters)
    : parameters_(parameters) {}

void PdaRegistration::followSourceSpacing(const PointList& source, bool budgeted) {
  if (!parameters_.target_subset) return;
  source_seen_ = true;
  // Only a source thinned to the budget asks for it: a sparse sensor's own points each need the
  // target's full detail (a 2600-point scan of a 4-cm room: 1.35 cm whole, 3.2 cm at its spacing).
  const double spacing = budgeted ? sampleSpacing(source) : 0.0;
  if (!(spacing > 0.0) || !std::isfinite(spacing)) {
    subset_voxel_ = 0.0;
  } else if (!subsetVoxelHolds(subset_voxel_, spacing)) {
    subset_voxel_ = spacing;
  }
}

void PdaRegistration::setParameters(const RegistrationParameters& parameters) {
  parameters_ = parameters;
  // A whole-cloud index follows a new voxel size right away (off the alignment's clock);
  // a cropped one is rebuilt by the next align(), which knows the region.
  const TargetIndexing how = indexing();
  const bool awaits_source = parameters_.target_subset && !source_seen_;
  if (hasTarget() && !target_map_.croppingApplies(how) && !awaits_source) {
    target_map_.prepare(how, AlignedBox());
  }
}

TargetIndexing PdaRegistration::indexing() const {
  TargetIndexing indexing;
  const double voxel = parameters_.target_voxel_size;
  indexing.voxel_size = voxel > 0.0 && std::isfinite(voxel) ? voxel : 0.0;
  indexing.subset_voxel = parameters_.target_subset ? subset_voxel_ : 0.0;
  indexing.normal_voxel_size = parameters_.normal_voxel_size;
  indexing.crop_above_points =
      parameters_.crop_above_points > 0 ? static_cast<size_t>(parameters_.crop_above_points) : 0;
  return indexing;
}

bool PdaRegistration::setTarget(PointList target) {
  if (!target_map_.setCloud(std::move(target))) return false;
  const TargetIndexing how = indexing();
  if (target_map_.croppingApplies(how)) return true;  // indexed by align(), around each source
  // Its subset needs a source's spacing: the first align() indexes it.
  if (parameters_.target_subset && !source_seen_) return true;
  if (!target_map_.prepare(how, AlignedBox())) {
    target_map_.clear();
    return false;
  }
  return true;
}

RegistrationResult PdaRegistration::align(const PointList& source,
                                          const Eigen::Isometry3d& T_target_source_initial,
                                          Associations* associations) {
  if (associations) *associations = Associations();
  const auto start = std::chrono::steady_clock::now();
  RegistrationResult result;
  try {
    result = alignUnchecked(source, T_target_source_initial, associations);
    traceAttempt(result, /*adopted=*/true, start);
    trySecondStart(source, T_target_source_initial, start, &result, associations);
    tryLocalStart(source, T_target_source_initial, start, &result, associations);
    tryOtherDirection(source, T_target_source_initial, start, &result, associations);
    tryWiderSearch(source, T_target_source_initial, start, &result, associations);
  } catch (const std::exception& error) {
    if (associations) *associations = Associations();
    result = RegistrationResult();
    result.T_target_source = T_target_source_initial;
    result.reason = std::string("internal error: ") + error.what();
  } catch (...) {
    if (associations) *associations = Associations();
    result = RegistrationResult();
    result.T_target_source = T_target_source_initial;
    result.reason = "internal error: unknown exception";
  }
  result.time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

void PdaRegistration::trySecondStart(const PointList& source, const Eigen::Isometry3d& T_initial,
                                     std::chrono::steady_clock::time_point started,
                                     RegistrationResult* result, Associations* associations) {
  const PointList& used = workspace_.source;  // the points the first alignment ran on
  if (used.empty()) return;
  Point centroid = Point::Zero();
  for (const Point& point : used) centroid += point;
  centroid /= static_cast<double>(used.size());
  FirstResultBasin basin;
  basin.T_found = result->T_target_source;
  basin.centroid = centroid;
  basin.final_radius = refineRadius(parameters_, result->sigma * result->sigma);
  if (!secondStartWarranted(*result, parameters_, T_initial, centroid, basin.final_radius)) return;
  for (const Point& point : used) basin.source_rms_radius += (point - centroid).squaredNorm();
  basin.source_rms_radius = std::sqrt(basin.source_rms_radius / static_cast<double>(used.size()));
  const Eigen::Isometry3d* tried = nullptr;
  const auto starts = secondStartPoses(result->T_target_source, T_initial, centroid);
  for (const Eigen::Isometry3d& start : starts) {
    // A start in the first result's basin would only find it again; one near the start just
    // tried is the same hypothesis.
    if (basin.contains(start) || (tried && basin.near(*tried, start))) continue;
    tried = &start;
    const NestedAlignment nested(&parameters_, started);
    const AttemptLabel label(&attempt_, "second start");
    if (!nested.timeLeft()) return;
    Associations second_associations;
    RegistrationResult second =
        alignUnchecked(source, start, associations ? &second_associations : nullptr, &basin);
    const bool better = secondStartIsBetter(*result, second);
    traceAttempt(second, better, started);
    adoptNested(better, &second, &second_associations, result, associations);
    if (better) return;
  }
}

void PdaRegistration::tryLocalStart(const PointList& source, const Eigen::Isometry3d& T_initial,
                                    std::chrono::steady_clock::time_point started,
                                    RegistrationResult* result, Associations* associations) {
  const double moved = rmsDisplacement(workspace_.source, result->T_target_source, T_initial);
  if (!localStartWarranted(*result, parameters_, moved)) return;
  const NestedAlignment nested(&parameters_, started);
  // A converged result stands when there is no time to question it; a failed one says why.
  const bool first_converged = result->converged;
  if (first_converged ? !nested.timeLeft() : !nested.timeLeftOrNote("a local start", result)) {
    return;
  }
  const AttemptLabel label(&attempt_, "local start");
  Associations local_associations;
  RegistrationResult local =
      alignUnchecked(source, T_initial, associations ? &local_associations : nullptr,
                     /*abandon_in=*/nullptr, /*local_start=*/true);
  local.local_start = true;
  const bool holds = local.converged &&
                     localStartStaysNear(workspace_.source, local.T_target_source, T_initial,
                                         parameters_);
  const bool cut = local.out_of_time;
  traceAttempt(local, holds, started);
  adoptNested(holds, &local, &local_associations, result, associations);
  if (!first_converged) nested.noteIfCut("a local start", holds, cut, result);
}

void PdaRegistration::tryOtherDirection(const PointList& source, const Eigen::Isometry3d& T_initial,
                                        std::chrono::steady_clock::time_point started,
                                        RegistrationResult* result, Associations* associations) {
  // PDA's natural direction failed and the source is the denser cloud: its model may hold the
  // other way round (alignment_direction.hpp). Kept only if that run converges. Only a whole
  // target is considered (one large enough to crop is a dense map already).
  const std::shared_ptr<const TargetIndex> target = target_map_.index();
  if (result->converged || result->out_of_time || !target || result->target_cropped ||
      result->source_points_used < static_cast<size_t>(parameters_.min_correspondences) ||
      !sourceIsDenser(countInOverlap(target->points(), source, T_initial))) {
    return;
  }
  const NestedAlignment nested(&parameters_, started);
  if (!nested.timeLeftOrNote("the other direction", result)) return;
  const AttemptLabel label(&attempt_, "other direction");
  Associations swapped_associations;
  RegistrationResult swapped =
      alignSwapped(source, T_initial, associations ? &swapped_associations : nullptr);
  traceAttempt(swapped, swapped.converged, started);
  if (swapped.converged) {
    *result = std::move(swapped);
    if (associations) *associations = std::move(swapped_associations);
  } else {
    nested.noteIfCut("the other direction", false, swapped.out_of_time, result);
  }
}

void PdaRegistration::tryWiderSearch(const PointList& source, const Eigen::Isometry3d& T_initial,
                                     std::chrono::steady_clock::time_point started,
                                     RegistrationResult* result, Associations* associations) {
  if (!widerSearchWarranted(*result, parameters_)) return;
  const RegistrationParameters user = parameters_;
  const NestedAlignment nested(&parameters_, started);
  if (!nested.timeLeftOrNote("a wider search", result)) return;
  parameters_ = widerSearchParameters(parameters_);  // the user's, with what is left of the time
  const AttemptLabel label(&attempt_, "wider search");
  Associations wide_associations;
  RegistrationResult wide =
      alignUnchecked(source, T_initial, associations ? &wide_associations : nullptr);
  wide.search_widened = true;
  const bool holds = widerSearchHolds(wide, user);
  const bool cut = wide.out_of_time;
  traceAttempt(wide, holds, started);
  adoptNested(holds, &wide, &wide_associations, result, associations);
  nested.noteIfCut("a wider search", holds, cut, result);
}

void PdaRegistration::traceAttempt(const RegistrationResult& attempt, bool adopted,
                                   std::chrono::steady_clock::time_point started) const {
  if (!trace_.attempt) return;
  AttemptRecord record;
  record.attempt = attempt_;
  record.converged = attempt.converged;
  record.adopted = adopted;
  record.reason = attempt.reason;
  record.runs = attempt.runs;
  record.sigma = attempt.sigma;
  record.time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
  trace_.attempt(record);
}

RegistrationResult PdaRegistration::alignSwapped(const PointList& source,
                                                 const Eigen::Isometry3d& T_target_source_initial,
                                                 Associations* associations) {
  PdaRegistration swapped(parameters_);
  swapped.trace_.run = trace_.run;  // its runs are this attempt's; align() notes the attempt
  swapped.attempt_ = attempt_;
  RegistrationResult result;
  if (!swapped.setTarget(source)) {
    result.T_target_source = T_target_source_initial;
    result.reason = "the source (the denser cloud, used as the target) could not be indexed";
    return result;
  }
  const std::shared_ptr<const TargetIndex> target = target_map_.index();
  result =
      swapped.alignUnchecked(target->points(), T_target_source_initial.inverse(), associations);
  const Eigen::Isometry3d T_source_target = result.T_target_source;
  result.T_target_source = T_source_target.inverse();
  result.covariance = invertedPoseCovariance(T_source_target, result.covariance);
  result.roles_swapped = true;
  std::swap(result.source_points_used, result.target_points_used);
  std::swap(result.source_points_dropped, result.target_points_dropped);
  result.target_points_total = target_map_.cloudSize();
  result.target_points_dropped = target_map_.droppedPoints();
  result.target_index_ms = swapped.target_map_.lastBuildMs();
  // The associations are in the source's frame: express them in the target's, like the result.
  if (associations) {
    for (Point& p : associations->source_points) p = result.T_target_source * p;
    for (Point& p : associations->candidates) p = result.T_target_source * p;
  }
  return result;
}

}  // namespace pda_registration

#include "pda_registration/core/pda_registration.hpp"

// The engine's entry points: the target, the parameters, and align(), which runs the staged
// alignment (staged_alignment.cpp) and, where its result calls for one, a second start
// (second_start_attempts.cpp: also while the first pauses at nu's floor), a local start, the
// other direction or a wider search; where that answer is questionable or a kept local start, all
// of it once more as a near search (near_search_attempt.cpp).

#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <sstream>
#include <string>
#include <utility>

#include "pda_registration/core/alignment_direction.hpp"
#include "pda_registration/core/em_run.hpp"
#include "pda_registration/core/final_statistics.hpp"
#include "pda_registration/core/local_start.hpp"
#include "pda_registration/core/nested_alignment.hpp"
#include "pda_registration/core/pose_covariance.hpp"
#include "pda_registration/core/representative_subset.hpp"
#include "pda_registration/core/second_start.hpp"
#include "pda_registration/core/wider_search.hpp"

namespace pda_registration {

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
  opening_runs_.clear();
  try {
    result = alignWithFallbacks(source, T_target_source_initial, start, associations);
    // Where that answer is questionable (or a kept local start), all of it once more, searching
    // near (near_search.hpp).
    tryNearSearch(source, T_target_source_initial, start, &result, associations);
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
  radius_follows_steps_ = false;  // however the attempts ended (an exception skips their resets)
  in_near_search_ = false;
  near_rejoined_ = false;
  deferred_attempts_ = nullptr;
  opening_runs_.clear();  // holds the target's index
  result.time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

RegistrationResult PdaRegistration::alignWithFallbacks(const PointList& source,
                                                       const Eigen::Isometry3d& T_initial,
                                                       std::chrono::steady_clock::time_point start,
                                                       Associations* associations,
                                                       bool near_search,
                                                       const UsualAnswer* rejoin) {
  // A first attempt whose refine runs leave nu at its floor is questioned there by the second
  // starts (second_start_attempts.cpp); otherwise they may follow its end.
  EarlySecondStarts early;
  const std::function<bool(const EmState&, const TargetIndex&)> at_nu_floor =
      [&](const EmState& first, const TargetIndex& index) {
        return secondStartsAtNuFloor(source, T_initial, start, first, index,
                                     associations != nullptr, &early);
      };
  AttemptOptions first_attempt;
  first_attempt.at_nu_floor = &at_nu_floor;
  first_attempt.rejoin = rejoin;
  // A near search's first attempt, and the second starts it asks at nu's floor, search as far as
  // their steps reach (near_search.hpp); the attempts after it, as usual.
  radius_follows_steps_ = near_search;
  RegistrationResult result = alignUnchecked(source, T_initial, associations, first_attempt);
  radius_follows_steps_ = false;
  traceAttempt(result, /*adopted=*/!early.adopted, start);
  // A near search back at the usual answer would only ask what the usual alignment asked already.
  if (near_rejoined_) return result;
  if (early.adopted) {
    adoptNested(true, &early.adopted_result, &early.adopted_associations, &result, associations);
  } else if (early.tried) {
    settleEarlySecondStarts(T_initial, start, &early, &result, associations);
  } else {
    trySecondStart(source, T_initial, start, &result, associations);
  }
  // What the first result warrants, before a local start may stand in for it: from a seed far
  // off the local start converges as readily on a false fit near it (local_start.hpp), so the
  // fallbacks the first warranted still meet it, the better supported kept.
  const bool other_direction_warranted = otherDirectionWarranted(result, source, T_initial);
  const bool wider_search_warranted = widerSearchWarranted(result, parameters_);
  tryLocalStart(source, T_initial, start, &result, associations);
  tryOtherDirection(source, T_initial, start, other_direction_warranted, &result, associations);
  tryWiderSearch(source, T_initial, start, wider_search_warranted, &result, associations);
  return result;
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
  const AttemptLabel label(&attempt_, attemptName("local start"));
  Associations local_associations;
  AttemptOptions options;
  options.local_start = true;
  RegistrationResult local =
      alignUnchecked(source, T_initial, associations ? &local_associations : nullptr, options);
  local.local_start = true;
  const bool holds = local.converged &&
                     localStartStaysNear(workspace_.source, local.T_target_source, T_initial,
                                         parameters_);
  const bool cut = local.out_of_time;
  traceAttempt(local, holds, started);
  adoptNested(holds, &local, &local_associations, result, associations);
  if (!first_converged) nested.noteIfCut("a local start", holds, cut, result);
}

bool PdaRegistration::otherDirectionWarranted(const RegistrationResult& first,
                                              const PointList& source,
                                              const Eigen::Isometry3d& T_initial) const {
  // PDA's natural direction failed and the source is the denser cloud: its model may hold the
  // other way round (alignment_direction.hpp). Only a whole target is considered (one large
  // enough to crop is a dense map already).
  const std::shared_ptr<const TargetIndex> target = target_map_.index();
  return !first.converged && !first.out_of_time && target && !first.target_cropped &&
         first.source_points_used >= static_cast<size_t>(parameters_.min_correspondences) &&
         sourceIsDenser(countInOverlap(target->points(), source, T_initial));
}

void PdaRegistration::tryOtherDirection(const PointList& source, const Eigen::Isometry3d& T_initial,
                                        std::chrono::steady_clock::time_point started,
                                        bool first_warranted_it, RegistrationResult* result,
                                        Associations* associations) {
  // Kept only if it converges; over an adopted local start, only if it also fits more of the
  // overlap (the reversed room from 20 deg: a local start 1.7 m off at support 0.1). Since the
  // first, only the local start has run: it converged (and was kept) or the result is the first's,
  // perhaps now cut by the time limit.
  if (!first_warranted_it || result->out_of_time) return;
  const bool contest = result->converged;
  const NestedAlignment nested(&parameters_, started);
  // A converged result stands when there is no time to question it; a failed one says why.
  if (contest ? !nested.timeLeft() : !nested.timeLeftOrNote("the other direction", result)) {
    return;
  }
  const AttemptLabel label(&attempt_, attemptName("other direction"));
  Associations swapped_associations;
  bool fits_more = false;
  RegistrationResult swapped =
      alignSwapped(source, T_initial, associations ? &swapped_associations : nullptr,
                   contest ? result : nullptr, &fits_more);
  const bool holds = swapped.converged && (!contest || fits_more);
  traceAttempt(swapped, holds, started);
  if (holds) {
    *result = std::move(swapped);
    if (associations) *associations = std::move(swapped_associations);
    // The other direction slides along a repeat as readily as the first attempt (the fragments of
    // seed 4 from 20 deg: 2.4 m off, nu at its floor): its answer meets the second starts too.
    trySecondStart(source, T_initial, started, result, associations);
  } else if (!contest) {
    nested.noteIfCut("the other direction", false, swapped.out_of_time, result);
  }
}

void PdaRegistration::tryWiderSearch(const PointList& source, const Eigen::Isometry3d& T_initial,
                                     std::chrono::steady_clock::time_point started,
                                     bool first_warranted_it, RegistrationResult* result,
                                     Associations* associations) {
  // A local start converges as readily on a false fit near a seed far off (local_start.hpp): one
  // adopted after a first attempt that warranted the wider search meets the wider search's answer.
  // One the other direction replaced stands; so does a result cut by the time limit since.
  if (!first_warranted_it || result->out_of_time) return;
  if (result->converged && !result->local_start) return;
  const bool contest = result->converged;
  const RegistrationParameters user = parameters_;
  const NestedAlignment nested(&parameters_, started);
  // A converged result stands when there is no time to question it; a failed one says why.
  if (contest ? !nested.timeLeft() : !nested.timeLeftOrNote("a wider search", result)) return;
  parameters_ = widerSearchParameters(parameters_);  // the user's, with what is left of the time
  const AttemptLabel label(&attempt_, attemptName("wider search"));
  Associations wide_associations;
  RegistrationResult wide =
      alignUnchecked(source, T_initial, associations ? &wide_associations : nullptr);
  wide.search_widened = true;
  parameters_ = user;  // the contest is judged with the user's radius
  const bool holds = widerSearchHolds(wide, user) &&
                     (!contest || fitsMoreOfTheOverlap(wide, result->T_target_source,
                                                       result->sigma, *target_map_.index()));
  const bool cut = wide.out_of_time;
  traceAttempt(wide, holds, started);
  adoptNested(holds, &wide, &wide_associations, result, associations);
  if (!contest) nested.noteIfCut("a wider search", holds, cut, result);
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
  record.T_target_source = attempt.T_target_source;
  record.time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
  if (deferred_attempts_) {
    deferred_attempts_->push_back(std::move(record));
  } else {
    trace_.attempt(record);
  }
}

RegistrationResult PdaRegistration::alignSwapped(const PointList& source,
                                                 const Eigen::Isometry3d& T_target_source_initial,
                                                 Associations* associations,
                                                 const RegistrationResult* incumbent,
                                                 bool* fits_more) {
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
  if (incumbent && fits_more) {
    // Both supports where a nearest sample measures a distance to the surface: the sparser
    // cloud's points against the denser one's index (the other way, the truth of the reversed
    // room fits less than a local start's false fit 1.7 m off).
    const double yardstick = commonYardstick(parameters_, incumbent->sigma, result.sigma);
    const auto supportAt = [&](const Eigen::Isometry3d& T) {
      return supportFractionAt(*swapped.target_map_.index(), swapped.workspace_.source, T,
                               yardstick, parameters_.radius, parameters_.threads);
    };
    *fits_more = secondStartIsBetter(result, supportAt(T_source_target),
                                     supportAt(incumbent->T_target_source.inverse()));
  }
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

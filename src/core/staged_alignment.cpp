#include "pda_registration/core/pda_registration.hpp"
// The staged runs of one alignment (approach, settle, refine; pda_registration.hpp) and what
// they need around them: the target's index for the source as aligned (source_budget.hpp), the
// final statistics and the verdict.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "pda_registration/core/alignment_verdict.hpp"
#include "pda_registration/core/candidate_sets.hpp"
#include "pda_registration/core/degrees_of_freedom.hpp"
#include "pda_registration/core/em_run.hpp"
#include "pda_registration/core/final_statistics.hpp"
#include "pda_registration/core/local_start.hpp"
#include "pda_registration/core/near_search.hpp"
#include "pda_registration/core/opening_runs.hpp"
#include "pda_registration/core/run_extrapolation.hpp"
#include "pda_registration/core/run_rest.hpp"
#include "pda_registration/core/run_tail.hpp"
#include "pda_registration/core/source_budget.hpp"
#include "pda_registration/core/warp_polish.hpp"

namespace pda_registration {
namespace {

enum class Stage { kApproach, kSettle, kRefine };

const char* nameOf(Stage stage) {
  return stage == Stage::kApproach ? "approach" : (stage == Stage::kSettle ? "settle" : "refine");
}

}  // namespace

RegistrationResult PdaRegistration::alignUnchecked(const PointList& source_input,
                                                   const Eigen::Isometry3d& T_target_source_initial,
                                                   Associations* associations,
                                                   const AttemptOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  const RegistrationParameters& p = parameters_;
  const FirstResultBasin* const abandon_in = options.abandon_in;
  const bool local_start = options.local_start;
  RegistrationResult result;
  result.T_target_source = T_target_source_initial;

  AttemptInputs inputs;
  if (!prepareAttempt(source_input, T_target_source_initial, &inputs, &result)) return result;
  Eigen::Isometry3d T = inputs.T;
  const PointList& source = workspace_.source;
  const std::shared_ptr<const TargetIndex> index = inputs.index;
  const std::shared_ptr<const SurfaceNormalMap> normal_map = inputs.normal_map;
  // A second start's distance from the first result where it began (second_start.hpp).
  const double apart_at_start =
      abandon_in ? rmsDisplacement(source, T_target_source_initial, abandon_in->T_found) : 0.0;

  // Three stages, each until a run moves less than 10 epsilons (the last: less than the
  // epsilons). Approach: the full radius on a strided subset of the source (these runs only need
  // to bring the estimate close, at a fraction of the cost). Settle: the full radius on every
  // point (a subset can stall where the whole cloud would not). Refine: every point, the
  // shrinking radius. Single-run mode (the paper's) is one refine run at the full radius.
  PointList& coarse_source = workspace_.coarse_source;
  coarse_source.clear();
  if (p.max_runs > 1 && p.coarse_stride > 1 &&
      source.size() / p.coarse_stride >= 20 * static_cast<size_t>(p.min_correspondences)) {
    coarse_source = randomSubsample(source, source.size() / p.coarse_stride);
  }
  Stage stage = p.max_runs == 1 ? Stage::kRefine
                                : (coarse_source.empty() ? Stage::kSettle : Stage::kApproach);

  // What one run hands the next (opening_runs.hpp), by its parts' names.
  const PoseStep step_metric = PoseStep::over(source);
  RunLoopState loop(step_metric);
  EmState& state = loop.state;
  state.T = T;
  state.nu = p.nu;
  state.outlier_class = local_start;
  if (p.sigma_mode == SigmaMode::kFixed) state.sigma_squared = p.fixed_sigma * p.fixed_sigma;
  CandidateSets& candidates = workspace_.candidates;
  Increment& last_run_step = loop.last_run_step;
  double& last_rms_step = loop.last_rms_step;
  bool& em_settled = loop.em_settled;
  bool asked_at_nu_floor = false;
  // max_runs bounds the work, counted in runs over the whole source: an approach run over the
  // subset counts as the subset's share. Sliding along a valley of the ground can take the
  // approach many cheap runs (a lidar scan from 10-20 deg away: 40-150 of them).
  double& work = loop.work;
  RunExtrapolation& extrapolation = loop.extrapolation;
  RunRest& rest = loop.rest;
  RunTail& tail = loop.tail;
  const auto outOfTime = [&] {
    return p.time_limit_ms > 0.0 &&
           std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started)
                   .count() > p.time_limit_ms;
  };
  double near_reach = p.radius;  // a near search's last approach or settle radius
  // The usual first attempt keeps its opening runs; a near search's first attempt resumes after
  // them (opening_runs.hpp).
  const bool first_attempt = options.at_nu_floor && !local_start && !abandon_in;
  const bool keep_opening = first_attempt && !radius_follows_steps_;
  if (keep_opening) opening_runs_.begin(&source_input, index, normal_map, T);
  const int first_run =
      first_attempt && radius_follows_steps_
          ? opening_runs_.resume(&source_input, index.get(), normal_map.get(), T, attempt_,
                                 trace_, &loop, &result)
          : 1;
  for (int run = first_run; work < p.max_runs; ++run) {
    if (run > 1 && outOfTime()) {
      result.out_of_time = true;
      break;
    }
    const PointList& active = stage == Stage::kApproach ? coarse_source : source;
    work += static_cast<double>(active.size()) / static_cast<double>(source.size());
    double radius =
        stage == Stage::kRefine && p.max_runs > 1 ? refineRadius(p, state.sigma_squared) : p.radius;
    // A near search (near_search.hpp): once its first run has moved, the approach and settle runs
    // search only as far as the steps still reach, so settled unshared points stop pulling, and
    // its refine runs no further than the settle stage's last run (where the unshared points hold
    // sigma up, 6 sigma would reach them again).
    if (radius_follows_steps_) {
      if (stage != Stage::kRefine && run > 1) radius = stepFollowingRadius(p, last_rms_step);
      if (stage == Stage::kRefine) radius = std::min(radius, near_reach);
      if (stage != Stage::kRefine) near_reach = radius;
    }
    // The settle stage's first run answers the approach subset's points from their last search
    // where that proves the answer (candidate_sets.hpp), as a run on the subset would.
    if (&active == &source) workspace_.search.carryToSuperset(coarse_source, source);
    findCandidateSets(*index, active, state.T, p.k, radius, p.threads, &workspace_.search,
                      &candidates);
    state.search_radius = radius;
    result.runs = run;
    result.source_points_with_candidates = candidates.sourcePointsWithCandidates();
    if (result.source_points_with_candidates < static_cast<size_t>(p.min_correspondences)) {
      std::ostringstream reason;
      reason << "no overlap: only " << result.source_points_with_candidates
             << " source points have a target point within radius " << radius << " (need "
             << p.min_correspondences << ")";
      result.reason = reason.str();
      result.sigma = std::sqrt(state.sigma_squared);
      return result;
    }
    const Eigen::Isometry3d T_run_start = state.T;
    // A stage ends when a run moves less than its epsilons: 10 epsilons before the refine stage,
    // the epsilons themselves in it; and once the distance still to go is negligible against
    // sigma (run_tail.hpp; the refine stage's 1 %, 10 % before it). The approach too: its last
    // runs moved 1-3 mm at sigma 7 cm on the room's 0.25-m map, and the settle stage, on every
    // point, moves the estimate as far again. A slide has a long tail and runs on.
    const double stage_scale = stage == Stage::kRefine ? 1.0 : 10.0;
    const bool sigma_estimated = p.sigma_mode == SigmaMode::kEstimated;
    // A run's EM need not settle finer than its stage asks of the runs: before the refine stage
    // its iterations stop at the stage's 10 epsilons. Below them they only polished a run that
    // was not the last (with the approach's tail: the room on its 0.25-m map from 5 deg, 66 -> 44
    // EM iterations and 15 -> 12 runs, its eq. 22 error the same to 0.01 mm).
    RegistrationParameters run_parameters = p;  // a few numbers: copied once a run
    run_parameters.nu_mode = nuModeOfRun(p, stage == Stage::kRefine);
    run_parameters.translation_epsilon *= stage_scale;
    run_parameters.rotation_epsilon *= stage_scale;
    // EM's own steps are extrapolated once the approach has chosen the basin: there, tails of
    // steps as wide as sigma sent a VLP-16 scan pair from 10 deg 1.6 m along its slide.
    const PoseStep* em_step_metric = stage == Stage::kApproach ? nullptr : &step_metric;
    const NormalLookup normals_at =
        stage == Stage::kRefine ? NormalLookup::kAtCandidate : NormalLookup::kAtPoint;
    const int em_iterations_before = result.em_iterations;
    if (!runEm(active, *normal_map, normals_at, run_parameters, em_step_metric, &workspace_, &state,
               &em_settled, &result.em_iterations)) {
      result.reason = "M-step failed: the weighted correspondences do not constrain the pose";
      return result;
    }
    last_run_step = incrementBetween(T_run_start, state.T);
    const bool keeping = keep_opening && opening_runs_.open();
    if (radius_follows_steps_ || keeping) {
      last_rms_step = rmsDisplacement(active, T_run_start, state.T);
    }
    const RunRecord record{attempt_, run, nameOf(stage), active.size(), radius,
                           std::sqrt(state.sigma_squared), state.nu, last_run_step.translation,
                           last_run_step.rotation, result.em_iterations - em_iterations_before};
    if (trace_.run) trace_.run(record);
    const double to_go = tail.record(T_run_start, state.T);
    const bool tail_negligible =
        sigma_estimated &&
        to_go <= stage_scale * kNegligibleTailSigmas * std::sqrt(state.sigma_squared);
    const bool steps_small = last_run_step.translation <= stage_scale * p.translation_epsilon &&
                             last_run_step.rotation <= stage_scale * p.rotation_epsilon;
    const bool stage_done = steps_small || tail_negligible;
    // A refine run whose residuals span the search has lost what makes it a refine run: its
    // radius, 6 sigma, is back at the whole search, so it is not at a fit (the "unresolved"
    // verdict) and stops there, as an approach at rest does below. On RGB-D fragments that share
    // a third of the scene the refine runs wandered so at sigma 0.16-0.18 m for 12-30 more runs,
    // a third of the failing attempt's work, into the same verdict.
    // (A near search's refine runs are judged against its reach only at their end: its first refine
    // runs start at sigma 9-12 cm, 6 sigma past a 0.5-m reach, and narrow from there.)
    if (stage == Stage::kRefine && p.max_runs > 1 &&
        residualsSpanTheSearch(p, std::sqrt(state.sigma_squared))) {
      result.converged = true;  // judgeConvergence says what it is
      break;
    }
    // The runs converge linearly, slowly on dense clouds: the next run starts at the steps' tail
    // (run_extrapolation.hpp), at most 2 sigma further, where the candidate sets are still
    // about the same (a longer jump traded lidar scans' reach for speed: car park from 10 deg,
    // 9 -> 7 of 10 at no limit, 9 at 2 sigma).
    // The approach chooses the basin, from steps as wide as sigma: there a tail is only taken
    // once three successive steps agree (two ratios both say "linear"), not two. Two were enough
    // for an RGB-D fragment pair from 10 deg to be pushed one more step (0.19 m) along its slide
    // after its second run (sigma 0.32 m), past its basin's ridge, and to end 2.3 m off; the
    // settle and refine stages keep two.
    extrapolation.setAgreementsNeeded(stage == Stage::kApproach ? 2 : 1);
    if (!stage_done && p.max_runs > 1) {
      const int jumps_before = extrapolation.extrapolations();
      state.T = extrapolation.next(T_run_start, state.T, stage_scale * p.translation_epsilon,
                                   kExtrapolationSigmas * std::sqrt(state.sigma_squared));
      if (extrapolation.extrapolations() != jumps_before) tail.reset();  // not a run's own step
    }
    if (abandon_in && abandon_in->contains(state.T)) {
      result.reason = "second start: back in the first result's basin";
      return result;
    }
    // Heading back counts from the second run: the first one's step is not yet a direction.
    if (abandon_in && run >= 2 &&
        headingBack(apart_at_start, rmsDisplacement(source, state.T, abandon_in->T_found))) {
      result.reason = "second start: heading back to the first result";
      return result;
    }
    // A turned start is a guess: one not at a fit within its runs is left (turned_start.hpp).
    if (options.fit_within_runs > 0 && run >= options.fit_within_runs &&
        residualsSpanTheSearch(p, std::sqrt(state.sigma_squared))) {
      result.reason = "turned start: not at a fit within its runs";
      result.sigma = std::sqrt(state.sigma_squared);
      return result;
    }
    // A local start that has left the seed's neighbourhood would not be kept: run after a lidar
    // scan pair's right answer from 20 deg, one wandered 2-7 m off over 12-58 runs, doubling the
    // time of the alignment.
    if (local_start && !localStartStaysNear(source, state.T, T_target_source_initial, p)) {
      result.reason = "local start: left the seed's neighbourhood";
      return result;
    }
    // An approach that comes to rest with residuals as wide as the search is not at a fit (the
    // "unresolved" verdict below), and the whole source would only wander on from there: stop,
    // so that the other direction (alignment_direction.hpp) or a wider search (wider_search.hpp)
    // is tried at once. (Stopping approaches
    // that are still moving at that sigma after a quarter of the budget cut off slides that
    // would have reached the truth.)
    if (stage == Stage::kApproach && stage_done &&
        residualsSpanTheSearch(p, std::sqrt(state.sigma_squared))) {
      result.converged = true;  // at rest: judgeConvergence says what it is
      break;
    }
    // Runs that cycle in place (run_rest.hpp) have come to rest as surely as a short step: that
    // ends any stage. An approach on a map that covered a third of its scan cycled between two
    // poses 1.4 mm apart (above its 10 epsilons) until the work bound, "not converged" at 5 mm.
    const bool cycling = rest.cameBack(T_run_start, state.T);
    if (stage != Stage::kRefine) {
      if (keeping && !(stage_done || cycling)) {
        opening_runs_.keep(loop, result, record,
                           stepFollowingRadius(p, last_rms_step) == p.radius);
      }
      if (stage_done || cycling) {
        opening_runs_.stop();
        stage = stage == Stage::kApproach ? Stage::kSettle : Stage::kRefine;
        rest.reset();  // all three look back over this stage's steps only
        extrapolation.reset();
        tail.reset();
        // A near search back at the usual answer stops: its refine runs would come to the
        // usual answer's rest (near_search.hpp).
        if (options.rejoin) {
          const double apart = rmsDisplacement(source, state.T, options.rejoin->T_target_source);
          if (rejoinsUsualAnswer(p, *options.rejoin, apart)) {
            near_rejoined_ = true;
            result.T_target_source = state.T;
            result.reason = "near search: back at the usual answer";
            return result;
          }
        }
      }
      continue;  // convergence is only declared in the refine stage
    }
    // Converged: a run below the epsilons, a negligible tail, or runs that cycle in place.
    if (stage_done || cycling) {
      result.converged = true;
      break;
    }
    // nu at its floor, half the points fitting and half not, marks a false rest (second_start.hpp)
    // long before the refine runs settle into it: a dozen more runs on RGB-D fragments from 20 deg,
    // a quarter of the alignment's time. The caller may question it here, once.
    if (options.at_nu_floor && !asked_at_nu_floor && nuEstimatedAtFloor(p, state.nu)) {
      asked_at_nu_floor = true;
      if ((*options.at_nu_floor)(state, *index)) {
        result.reason = "superseded by a second start that fits more of the overlap";
        result.sigma = std::sqrt(state.sigma_squared);
        result.nu = state.nu;
        result.T_target_source = state.T;
        return result;
      }
    }
  }
  // With max_runs = 1 (the paper's single-run mode) convergence means EM settled in that run.
  if (!result.converged && p.max_runs == 1) result.converged = em_settled;

  T = state.T;
  result.T_target_source = T;
  result.sigma = std::sqrt(state.sigma_squared);
  result.nu = state.nu;
  // Statistics on every source point (the loop may have stopped in the coarse stage).
  if (candidates.sourceCount() != source.size()) {
    findCandidateSets(*index, source, T, p.k, p.radius, p.threads, &workspace_.search, &candidates);
  }
  fillFinalStatistics(source, *index, *normal_map, p, state, &workspace_, &result, associations);
  // A near search's refine runs searched no further than its settled reach, so does its polish,
  // and residuals as wide as that search are unresolved there, as at the whole radius otherwise.
  RegistrationParameters within_reach = p;
  if (radius_follows_steps_) within_reach.radius = near_reach;
  if (warpPolishWarranted(result, p, state.nu) &&
      polishOverAWarp(*index, source, *normal_map, result.normal_voxel_size, within_reach,
                      step_metric, outOfTime, &workspace_, &state, &result.runs,
                      &result.em_iterations)) {
    result.T_target_source = state.T;
    result.sigma = std::sqrt(state.sigma_squared);
    result.nu = state.nu;
    result.warp_polished = true;
    fillFinalStatistics(source, *index, *normal_map, p, state, &workspace_, &result, associations);
  }

  judgeConvergence(within_reach, result.converged, last_run_step, &result,
                   radius_follows_steps_ ? "the near search's reach" : "radius");
  return result;
}

}  // namespace pda_registration

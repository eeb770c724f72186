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
#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "pda_registration/core/alignment_trace.hpp"
#include "pda_registration/core/associations.hpp"
#include "pda_registration/core/opening_runs.hpp"
#include "pda_registration/core/point_list.hpp"
#include "pda_registration/core/registration_parameters.hpp"
#include "pda_registration/core/registration_result.hpp"
#include "pda_registration/core/registration_workspace.hpp"
#include "pda_registration/core/second_start.hpp"
#include "pda_registration/core/surface_normals.hpp"
#include "pda_registration/core/target_index.hpp"
#include "pda_registration/core/target_map.hpp"

namespace pda_registration {

struct EmState;
struct UsualAnswer;

/// What one attempt of PdaRegistration::align() is besides its start (internal to the engine).
struct AttemptOptions {
  /// A second start: it stops (not converged) once it enters the first's basin.
  const FirstResultBasin* abandon_in = nullptr;
  /// A turned start (turned_start.hpp): it stops (not converged) when, after this many runs, its
  /// residuals still span the search (residualsSpanTheSearch); 0: never.
  int fit_within_runs = 0;
  /// Every run uses the outlier class, and the alignment stops (not converged) once it moves
  /// the source further from the seed than its answer could be kept (local_start.hpp).
  bool local_start = false;
  /// Asked once, after the first refine run that leaves nu (estimated) at its floor, with the
  /// run's state and the target it searched; true: the attempt stops there, superseded.
  const std::function<bool(const EmState&, const TargetIndex&)>* at_nu_floor = nullptr;
  /// A near search's first attempt: it stops (not converged) once its approach or settle stage
  /// ends where this usual answer is (rejoinsUsualAnswer, near_search.hpp).
  const UsualAnswer* rejoin = nullptr;
};

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
  /// The first attempt and the fallbacks its result calls for (second starts, a local start, the
  /// other direction, a wider search); `near_search`: the first attempt (and the second starts it
  /// asks at nu's floor) searches as far as its steps reach (near_search.hpp); `rejoin` (a near
  /// search's only): the usual answer, where the first attempt stops if it comes back to it, and
  /// the fallbacks with it.
  RegistrationResult alignWithFallbacks(const PointList& source, const Eigen::Isometry3d& T_initial,
                                        std::chrono::steady_clock::time_point start,
                                        Associations* associations, bool near_search = false,
                                        const UsualAnswer* rejoin = nullptr);
  /// A questionable `result` (localStartWarranted): alignWithFallbacks() once more from the seed as
  /// a near search, its answer kept as near_search.hpp says (near_search_attempt.cpp).
  void tryNearSearch(const PointList& source, const Eigen::Isometry3d& T_initial,
                     std::chrono::steady_clock::time_point started, RegistrationResult* result,
                     Associations* associations);
  /// Whether `answer` warrants a near search (localStartWarranted, with how far it moved the
  /// source aligned last from the seed T_initial).
  bool questionable(const RegistrationResult& answer, const Eigen::Isometry3d& T_initial) const;
  /// The trace's name of an attempt: `usual`, or its "near search: " variant within a near search.
  const char* attemptName(const char* usual) const;
  RegistrationResult alignUnchecked(const PointList& source,
                                    const Eigen::Isometry3d& T_target_source_initial,
                                    Associations* associations,
                                    const AttemptOptions& options = AttemptOptions());
  /// What an attempt runs on (attempt_inputs.cpp): the initial guess as a rigid transform, and
  /// the target's index and normals for the source as aligned (workspace_.source).
  struct AttemptInputs {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    std::shared_ptr<const TargetIndex> index;
    std::shared_ptr<const SurfaceNormalMap> normal_map;
  };
  /// Checks the parameters, the guess and both clouds and prepares them; false: `result` says why.
  bool prepareAttempt(const PointList& source_input, const Eigen::Isometry3d& T_initial,
                      AttemptInputs* inputs, RegistrationResult* result);
  /// What the second starts asked at the first attempt's nu floor left
  /// (second_start_attempts.cpp).
  struct EarlySecondStarts {
    bool tried = false;    ///< the question was warranted and the starts ran
    bool adopted = false;  ///< one of them superseded the first attempt: `adopted_result`
    RegistrationResult adopted_result;
    Associations adopted_associations;
    /// Those that converged without superseding it, for the comparison at its end.
    std::vector<RegistrationResult> pending;
    std::vector<Associations> pending_associations;
    double dropped_index_ms = 0.0;  ///< indexing by the starts that neither superseded nor pend
  };
  /// The second starts (second_start.hpp) from the first attempt as it stands once nu reaches its
  /// floor in the refine runs, where the first would spend a dozen more runs on a false rest: one
  /// that fits more of the overlap than the first as it stands, both measured with its yardstick,
  /// supersedes it (returns true). Runs in spare_workspace_: the first's own is left as it was.
  bool secondStartsAtNuFloor(const PointList& source, const Eigen::Isometry3d& T_initial,
                             std::chrono::steady_clock::time_point started, const EmState& first,
                             const TargetIndex& first_index, bool want_associations,
                             EarlySecondStarts* early);
  /// Whether `second` replaces a first result at T_first, sigma_first (secondStartIsBetter: both
  /// supports measured on `index` with one yardstick, over the points the first ran on). Also
  /// whether a wider search replaces an adopted local start.
  bool fitsMoreOfTheOverlap(const RegistrationResult& second, const Eigen::Isometry3d& T_first,
                            double sigma_first, const TargetIndex& index) const;
  /// The first attempt ended: the pending second starts meet it under fitsMoreOfTheOverlap(), as a
  /// second start run at its end would.
  void settleEarlySecondStarts(const Eigen::Isometry3d& T_initial,
                               std::chrono::steady_clock::time_point started,
                               EarlySecondStarts* early, RegistrationResult* result,
                               Associations* associations);
  /// The turn of T_initial (turned_start.hpp) worth a second start, ranked on the points the
  /// first attempt ran on; none if no turn gives as many of them a candidate as the seed.
  std::optional<Eigen::Isometry3d> turnedStart(const Eigen::Isometry3d& T_initial) const;
  /// The second starts out of `basin` (second_start.hpp), then the turned start, in turn, until
  /// `keep` takes one (returns true); `in_spare_workspace`: run in spare_workspace_, leaving
  /// workspace_ as it was.
  void runSecondStarts(const PointList& source, const Eigen::Isometry3d& T_initial,
                       std::chrono::steady_clock::time_point started,
                       const FirstResultBasin& basin, bool want_associations,
                       bool in_spare_workspace,
                       const std::function<bool(RegistrationResult*, Associations*)>& keep);
  /// Second alignments from the rotation the first found (two starts, in turn) and from a turned
  /// seed, the first that is better kept (second_start.hpp, turned_start.hpp).
  void trySecondStart(const PointList& source, const Eigen::Isometry3d& T_initial,
                      std::chrono::steady_clock::time_point started, RegistrationResult* result,
                      Associations* associations);
  /// A failed result: once more from the seed with the outlier class, kept if that converges near
  /// the seed (local_start.hpp).
  void tryLocalStart(const PointList& source, const Eigen::Isometry3d& T_initial,
                     std::chrono::steady_clock::time_point started, RegistrationResult* result,
                     Associations* associations);
  /// A result that came to rest unresolved: once more from the seed with the radius widened,
  /// kept if that converges at a fit (wider_search.hpp). Runs only where the first attempt
  /// warranted it (`first_warranted_it`); a local start adopted since then meets it, and the
  /// better supported stays.
  void tryWiderSearch(const PointList& source, const Eigen::Isometry3d& T_initial,
                      std::chrono::steady_clock::time_point started, bool first_warranted_it,
                      RegistrationResult* result, Associations* associations);
  /// Whether a failed `first` on a source denser than the target warrants the other direction.
  bool otherDirectionWarranted(const RegistrationResult& first, const PointList& source,
                               const Eigen::Isometry3d& T_initial) const;
  /// A failed result on a source denser than the target: the other way round, with what is left
  /// of the time limit, kept if that converges (alignment_direction.hpp). Runs only where the
  /// first attempt warranted it (`first_warranted_it`, computed once, before the local start); a
  /// local start adopted since meets it, as in tryWiderSearch. An answer kept meets the second
  /// starts, as the first attempt's does (trySecondStart).
  void tryOtherDirection(const PointList& source, const Eigen::Isometry3d& T_initial,
                         std::chrono::steady_clock::time_point started, bool first_warranted_it,
                         RegistrationResult* result, Associations* associations);
  /// The target aligned onto `source` (the denser cloud), answered in the usual direction. With
  /// an `incumbent`, *fits_more says whether the answer fits more of the overlap than it does
  /// (secondStartIsBetter, one yardstick, the target's points against the source's index).
  RegistrationResult alignSwapped(const PointList& source,
                                  const Eigen::Isometry3d& T_target_source_initial,
                                  Associations* associations,
                                  const RegistrationResult* incumbent = nullptr,
                                  bool* fits_more = nullptr);
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
  RegistrationWorkspace spare_workspace_;  // for attempts run while another one pauses
  AlignmentTrace trace_;
  const char* attempt_ = "first";  // the attempt alignUnchecked() is running, for the trace
  bool radius_follows_steps_ = false;  // approach and settle radius: stepFollowingRadius()
  bool in_near_search_ = false;        // the attempts running are a near search's
  bool near_rejoined_ = false;         // its first attempt stopped at the usual answer
  OpeningRuns opening_runs_;  // the usual first attempt's, for a near search to resume after
  // A near search's attempt records wait here until it is known whether its answer is adopted.
  std::vector<AttemptRecord>* deferred_attempts_ = nullptr;
};

}  // namespace pda_registration

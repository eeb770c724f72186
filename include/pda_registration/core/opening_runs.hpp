#pragma once
// The usual first attempt's opening runs, kept for the near search (near_search.hpp). A near
// search's first attempt starts from the same seed, on the same points and target, as the usual
// first attempt, and differs from it only in its radius once a run has moved
// (stepFollowingRadius): while that is still the whole radius, its runs are the usual attempt's
// runs to the digit. So it resumes after them, from the loop state they ended in, instead of
// running them again (wide_vlp16_vlp16_seed3 from 10 deg: the first 5 of its 14 runs; factory_p64
// on its 0.5-m map from 10 deg: 3 of 6, 11 ms of the alignment's 130).
//
// Kept: the runs of the usual first attempt's first stage (approach, or settle without a coarse
// subset) up to the first after which a near search's radius would be shorter; a stage change ends
// them (a near search checks there whether it is back at the usual answer).

#include <Eigen/Geometry>
#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "pda_registration/core/alignment_trace.hpp"
#include "pda_registration/core/em_run.hpp"
#include "pda_registration/core/registration_result.hpp"
#include "pda_registration/core/run_extrapolation.hpp"
#include "pda_registration/core/run_rest.hpp"
#include "pda_registration/core/run_tail.hpp"
#include "pda_registration/core/surface_normals.hpp"
#include "pda_registration/core/target_index.hpp"

namespace pda_registration {

/// What one run of the staged loop hands the next, besides the stage (staged_alignment.cpp).
struct RunLoopState {
  explicit RunLoopState(const PoseStep& metric)
      : extrapolation(metric), rest(metric), tail(metric) {}

  EmState state;
  Increment last_run_step{0.0, 0.0};
  double last_rms_step = 0.0;  ///< the last run's RMS displacement of the points it aligned
  bool em_settled = false;     ///< did the last run's EM loop stop on the epsilons?
  double work = 0.0;           ///< runs over the whole source so far (max_runs bounds it)
  RunExtrapolation extrapolation;
  RunRest rest;
  RunTail tail;
};

class OpeningRuns {
 public:
  /// Forget the runs kept (a new align(); its end, so the target is not held).
  void clear();

  /// A usual first attempt begins: on `source` (align()'s input), `index` and `normals`, from T.
  void begin(const PointList* source, std::shared_ptr<const TargetIndex> index,
             std::shared_ptr<const SurfaceNormalMap> normals, const Eigen::Isometry3d& T);
  /// Whether runs are still being kept (none after the first a near search would run otherwise).
  bool open() const { return open_; }
  /// A run of the first stage ended with `loop` and the attempt's `result` so far (`record`, its
  /// trace); `next_radius_whole`: a near search's next run would search the whole radius too.
  void keep(const RunLoopState& loop, const RegistrationResult& result, const RunRecord& record,
            bool next_radius_whole);
  /// The stage changed: no more runs are kept.
  void stop() { open_ = false; }

  /// A near search's first attempt on these inputs: where the kept runs apply, `loop` and the
  /// result's run counts become theirs, their records go to the trace as `attempt`'s (replayed),
  /// and the run to go on with is returned; 1 (nothing changed) where they do not.
  int resume(const PointList* source, const TargetIndex* index, const SurfaceNormalMap* normals,
             const Eigen::Isometry3d& T, const char* attempt, const AlignmentTrace& trace,
             RunLoopState* loop, RegistrationResult* result) const;

 private:
  bool open_ = false;
  const PointList* source_ = nullptr;
  std::shared_ptr<const TargetIndex> index_;
  std::shared_ptr<const SurfaceNormalMap> normals_;
  Eigen::Isometry3d T_ = Eigen::Isometry3d::Identity();
  std::optional<RunLoopState> last_;
  int runs_ = 0;
  int em_iterations_ = 0;
  size_t points_with_candidates_ = 0;
  std::vector<RunRecord> records_;
};

}  // namespace pda_registration

#include "pda_registration/core/opening_runs.hpp"

#include <utility>

namespace pda_registration {

void OpeningRuns::clear() { *this = OpeningRuns(); }

void OpeningRuns::begin(const PointList* source, std::shared_ptr<const TargetIndex> index,
                        std::shared_ptr<const SurfaceNormalMap> normals,
                        const Eigen::Isometry3d& T) {
  clear();
  open_ = true;
  source_ = source;
  index_ = std::move(index);
  normals_ = std::move(normals);
  T_ = T;
}

void OpeningRuns::keep(const RunLoopState& loop, const RegistrationResult& result,
                       const RunRecord& record, bool next_radius_whole) {
  if (!open_) return;
  last_ = loop;
  runs_ = result.runs;
  em_iterations_ = result.em_iterations;
  points_with_candidates_ = result.source_points_with_candidates;
  records_.push_back(record);
  open_ = next_radius_whole;
}

int OpeningRuns::resume(const PointList* source, const TargetIndex* index,
                        const SurfaceNormalMap* normals, const Eigen::Isometry3d& T,
                        const char* attempt, const AlignmentTrace& trace, RunLoopState* loop,
                        RegistrationResult* result) const {
  // The same align() input, target and seed: the same prepared source, coarse subset and runs.
  if (!last_ || source != source_ || index != index_.get() || normals != normals_.get() ||
      T.matrix() != T_.matrix()) {
    return 1;
  }
  *loop = *last_;
  result->runs = runs_;
  result->em_iterations = em_iterations_;
  result->source_points_with_candidates = points_with_candidates_;
  if (trace.run) {
    for (RunRecord record : records_) {
      record.attempt = attempt;
      record.replayed = true;
      trace.run(record);
    }
  }
  return runs_ + 1;
}

}  // namespace pda_registration

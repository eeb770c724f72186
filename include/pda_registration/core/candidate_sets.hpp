#pragma once
// Candidate sets C_j (paper Sec. IV): for each source point, the up-to-k nearest target points
// within the radius, found once per run at the current estimate and then held fixed while EM
// re-weights them. Stored flat (CSR layout): candidates of source j are entries
// offsets[j] .. offsets[j+1] of target_indices and points. The positions are gathered once per run
// so every EM iteration streams through them instead of jumping around the target cloud.

#include <Eigen/Geometry>
#include <vector>

#include "pda_registration/core/point_list.hpp"
#include "pda_registration/core/target_index.hpp"

namespace pda_registration {

struct CandidateSets {
  std::vector<size_t> offsets;         ///< size = source points + 1
  std::vector<size_t> target_indices;  ///< all candidates, grouped by source point
  PointList points;                    ///< their positions (target frame), same order

  size_t sourceCount() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  size_t candidateCount(size_t j) const { return offsets[j + 1] - offsets[j]; }
  size_t sourcePointsWithCandidates() const;
};

/// The search's scratch space, kept between calls (see registration_workspace.hpp).
struct CandidateSearchBuffers {
  std::vector<size_t> slots;              ///< k per source point
  std::vector<double> squared_distances;  ///< k per source point
  std::vector<size_t> found;              ///< per source point
};

/// Searches candidates for every source point transformed by T_target_source. `threads` > 1
/// splits the source points among threads; the result is identical for any thread count.
CandidateSets findCandidateSets(const TargetIndex& target, const PointList& source,
                                const Eigen::Isometry3d& T_target_source, int k, double radius,
                                int threads);

/// The same into *sets, reusing its memory and the buffers' (an alignment calls this every run).
void findCandidateSets(const TargetIndex& target, const PointList& source,
                       const Eigen::Isometry3d& T_target_source, int k, double radius, int threads,
                       CandidateSearchBuffers* buffers, CandidateSets* sets);

}  // namespace pda_registration

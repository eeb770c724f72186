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

/// The search's scratch space and its last answers, kept between calls (see
/// registration_workspace.hpp). The last answers serve the next call on the same source points
/// and target: as hints, and to certify a point's candidates unchanged without a search
/// (candidate_sets.cpp).
struct CandidateSearchBuffers {
  std::vector<size_t> slots;              ///< per source point: its nearest, candidates first
  std::vector<double> squared_distances;  ///< the same slots' squared distances
  std::vector<size_t> found;              ///< candidates per source point (at most k)
  std::vector<size_t> kept;               ///< target points kept per source point (>= found)
  /// Per source point, a lower bound on the squared distance of every target point not kept
  /// (the nearest of them, or the squared radius when there is none within it).
  std::vector<double> outsider_bound;
  std::vector<unsigned char> answered;  ///< per source point: from the kept points (last call)
  // What the last answers were found for; certification needs exactly these points and target.
  const Point* source = nullptr;
  const TargetIndex* target = nullptr;
  size_t target_size = 0;
  int k = 0;
  Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();
  bool have_answers = false;
  size_t answered_from_kept = 0;  ///< by the last call, without a search

  /// The next call searches afresh (call when the source points' values or the target may have
  /// changed under the same memory: a new alignment).
  void forget() { have_answers = false; }
  /// The last answers were for `subset`, points of `superset` in its order (the approach's coarse
  /// subset of the source): they become the answers of the same points of `superset`, and the
  /// others have none yet, so that the next call on `superset` answers those points from them
  /// where it can, as it would on `subset`. Nothing changes when they were for other points.
  void carryToSuperset(const PointList& subset, const PointList& superset);
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

#pragma once
// Which cloud the EM runs on. PDA's model is a sparse source against a dense target: every source
// point finds target samples around it, and the sampling model tolerates the target's spacing
// along its surface. Given the other way round (a dense map as the source of a 16-row scan), most
// source points lie between the target's scan lines with nothing to match, and EM can diverge.
// So when the usual direction does not converge and the source is clearly the denser cloud where
// the two overlap, PDA aligns the target onto the source and inverts the answer (kept only if
// that converges). Point counts alone do not decide it: a target thinned to 0.5 m voxels is
// sparser than a lidar scan by count, yet PDA fits the scan onto it better than the reverse.

#include <Eigen/Geometry>

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

/// How much denser (points in the common bounding box) the source must be before the roles are
/// swapped: a swap indexes the source, which only pays off when the densities clearly differ.
constexpr double kSwapDensityRatio = 2.0;

/// Points of `target` and of the finite points of `source` (moved by T_target_source) inside the
/// intersection of their bounding boxes.
struct OverlapCounts {
  size_t target = 0;
  size_t source = 0;
};
OverlapCounts countInOverlap(const PointList& target, const PointList& source,
                             const Eigen::Isometry3d& T_target_source);

/// True when the source has more than kSwapDensityRatio times the target's points in the overlap.
bool sourceIsDenser(const OverlapCounts& counts);

}  // namespace pda_registration

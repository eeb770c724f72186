#pragma once
// The final weighted associations of an alignment, for inspection (rviz markers, debugging):
// each source point with candidates, its candidate target points and their posterior
// association probabilities P(a_jk), which sum to 1 per source point.

#include <vector>

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

struct Associations {
  PointList source_points;        ///< moved into the target frame, one per source point
  std::vector<size_t> offsets;    ///< candidates of source i: [offsets[i], offsets[i+1])
  PointList candidates;           ///< candidate target points (target frame)
  std::vector<double> posterior;  ///< P(a_jk) per candidate

  size_t size() const { return source_points.size(); }
};

}  // namespace pda_registration

#pragma once
// The weighted associations as rviz markers: one LINE_LIST from every source point to each of its
// candidates. A line's alpha is exactly its posterior P(a_jk), so the alphas of the lines that
// leave one source point sum to 1; its colour runs from blue (weight 0) to red (weight 1). When
// there are more lines than `max_lines`, a uniform subsample of source points keeps all lines of
// the points it keeps.

#include <visualization_msgs/MarkerArray.h>

#include "pda_registration/core/associations.hpp"

namespace pda_registration {

visualization_msgs::MarkerArray associationMarkers(const Associations& associations,
                                                   const std_msgs::Header& header, size_t max_lines,
                                                   double line_width);

}  // namespace pda_registration

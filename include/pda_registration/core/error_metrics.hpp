#pragma once
// Accuracy against ground truth, as the paper measures it (eq. 22) plus the usual pose errors.

#include <Eigen/Geometry>

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

struct PoseError {
  double mean_distance = 0.0;  ///< eq. 22: mean over finite source points of |T_est x - T_gt x|
  double rotation_deg = 0.0;   ///< angle of R_est R_gt^T
  double translation = 0.0;    ///< |t_est - t_gt| [length]
};

PoseError poseError(const PointList& source, const Eigen::Isometry3d& T_estimate,
                    const Eigen::Isometry3d& T_ground_truth);

}  // namespace pda_registration

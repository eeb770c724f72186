#pragma once
// The nodelet's static settings (private parameters read once at start-up); everything that can
// change at run time lives in dynamic_reconfigure (cfg/PdaRegistration.cfg, live_parameters.hpp).

#include <ros/node_handle.h>

#include <Eigen/Geometry>
#include <string>

namespace pda_registration {

struct NodeSettings {
  bool dense_is_target = true;  ///< ~target_cloud: "dense" (paper) or "sparse"
  double tf_timeout = 0.1;      ///< ~tf_timeout [s]: wait for the seed at the cloud's stamp
  bool has_initial_transform = false;
  Eigen::Isometry3d initial_transform = Eigen::Isometry3d::Identity();  ///< dense <- sparse
  bool publish_tf = true;
  std::string tf_parent_frame;  ///< empty: the dense cloud's frame
  std::string tf_child_frame;   ///< empty: "<sparse frame>_aligned"
  double tf_publish_rate =
      10.0;  ///< [Hz] re-broadcast of the last good estimate (0 = only on updates)
  std::string expected_dense_frame;  ///< non-empty: clouds in another frame are refused
  std::string expected_sparse_frame;
  double marker_line_width = 0.01;  ///< [m]
};

/// Reads the settings; false with a one-line reason on a bad value (e.g. a malformed
/// ~initial_transform: 16 numbers row-major, 6 [x y z roll pitch yaw] or 7 [x y z qx qy qz qw]).
bool readNodeSettings(const ros::NodeHandle& private_node, NodeSettings* settings,
                      std::string* error);

}  // namespace pda_registration

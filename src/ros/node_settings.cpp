#include "pda_registration/ros/node_settings.hpp"

#include <vector>

#include "pda_registration/ros/initial_transform.hpp"

namespace pda_registration {

bool readNodeSettings(const ros::NodeHandle& nh, NodeSettings* s, std::string* error) {
  const std::string target = nh.param<std::string>("target_cloud", "dense");
  if (target != "dense" && target != "sparse") {
    *error = "~target_cloud must be 'dense' or 'sparse', got '" + target + "'";
    return false;
  }
  s->dense_is_target = target == "dense";
  s->tf_timeout = nh.param("tf_timeout", s->tf_timeout);
  s->publish_tf = nh.param("publish_tf", s->publish_tf);
  s->tf_parent_frame = nh.param<std::string>("tf_parent_frame", "");
  s->tf_child_frame = nh.param<std::string>("tf_child_frame", "");
  s->tf_publish_rate = nh.param("tf_publish_rate", s->tf_publish_rate);
  s->expected_dense_frame = nh.param<std::string>("expected_dense_frame", "");
  s->expected_sparse_frame = nh.param<std::string>("expected_sparse_frame", "");
  s->marker_line_width = nh.param("marker_line_width", s->marker_line_width);
  if (!(s->tf_timeout >= 0.0 && s->tf_timeout < 60.0)) {
    *error = "~tf_timeout must be in [0, 60) s";
    return false;
  }
  if (!(s->tf_publish_rate >= 0.0 && s->tf_publish_rate <= 1000.0)) {
    *error = "~tf_publish_rate must be in [0, 1000] Hz";
    return false;
  }
  if (nh.hasParam("initial_transform")) {
    std::vector<double> values;
    if (!nh.getParam("initial_transform", values)) {
      *error = "~initial_transform must be a list of numbers";
      return false;
    }
    if (!initialTransformFromList(values, &s->initial_transform, error)) return false;
    s->has_initial_transform = true;
  }
  return true;
}

}  // namespace pda_registration

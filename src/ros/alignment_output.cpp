// The publishing half of the alignment job: an accepted estimate goes out on ~transform, ~pose,
// ~aligned_cloud and ~associations (the last two only while subscribed) and on the tf edge.
#include "pda_registration/core/pose_covariance.hpp"
#include "pda_registration/ros/alignment_job.hpp"

namespace pda_registration {

Eigen::Matrix<double, 6, 6> AlignmentJob::publishedCovariance(
    const RegistrationResult& result) const {
  return c_.settings->dense_is_target
             ? result.covariance
             : invertedPoseCovariance(result.T_target_source, result.covariance);
}

void AlignmentJob::noteEdgeStamp(const TfEdge& edge) {
  bool was_at_stamp = true;
  c_.status->update([&](AlignmentStatusValues& s) {
    was_at_stamp = s.last_edge_at_stamp;
    s.last_edge_at_stamp = edge.at_stamp;
    if (!edge.at_stamp) ++s.edges_from_latest_tf;
  });
  if (edge.at_stamp == was_at_stamp) return;
  c_.log.info(edge.at_stamp ? "tf edge " + edge.parent + " -> " + edge.child +
                                  ": composed at the clouds' stamps again"
                            : "tf edge " + edge.parent + " -> " + edge.child +
                                  ": tf has nothing at the cloud's stamp, composing with the "
                                  "latest tf (off by what moved since)");
}

void AlignmentJob::publish(const Accepted& a) {
  const NodeSettings& settings = *c_.settings;
  const RegistrationResult& result = *a.result;
  const std::string& dense_frame = *a.dense_frame;
  const std::string& sparse_frame = a.cloud->header.frame_id;
  const ros::Time& stamp = a.cloud->header.stamp;
  AlignmentOutput output;
  output.stamp = stamp;
  output.dense_frame = dense_frame;
  output.sparse_frame = sparse_frame;
  output.T_dense_sparse =
      settings.dense_is_target ? result.T_target_source : result.T_target_source.inverse();
  output.covariance = publishedCovariance(result);
  output.target_frame = settings.dense_is_target ? dense_frame : sparse_frame;
  PointList aligned;
  if (c_.publisher->hasAlignedCloudSubscribers()) {
    aligned.reserve(a.source->size());
    for (const Point& p : *a.source) aligned.push_back(result.T_target_source * p);
    output.aligned = &aligned;
  }
  output.associations = a.associations;
  output.max_markers = a.live->max_markers;
  output.marker_line_width = settings.marker_line_width;
  c_.publisher->publish(output);
  if (!settings.publish_tf) return;
  TfEdge edge;
  std::string error;
  if (expressOnTfEdge(*c_.tf_buffer, output.T_dense_sparse, dense_frame, sparse_frame,
                      settings.tf_parent_frame, settings.tf_child_frame, stamp,
                      ros::Duration(settings.tf_timeout), &edge, &error)) {
    c_.edges->sendFresh(edge, stamp);
    noteEdgeStamp(edge);
  } else {
    c_.log.problem(
        "tf edge",
        "cannot express the estimate as " + edge.parent + " -> " + edge.child + ": " + error,
        false);
  }
}

}  // namespace pda_registration

#pragma once
// The alignment job: one sparse cloud in, one gated estimate out. Converts the cloud, looks up
// its seed on tf, aligns it with the dense map the keeper holds, judges the result and, when it
// is accepted, publishes it (topics and the tf edge). Runs on the nodelet's worker thread.

#include <sensor_msgs/PointCloud2.h>
#include <tf2_ros/buffer.h>

#include <string>

#include "pda_registration/core/associations.hpp"
#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/warm_start.hpp"
#include "pda_registration/ros/alignment_publisher.hpp"
#include "pda_registration/ros/alignment_status.hpp"
#include "pda_registration/ros/dense_map_keeper.hpp"
#include "pda_registration/ros/edge_broadcaster.hpp"
#include "pda_registration/ros/idle_cores.hpp"
#include "pda_registration/ros/live_parameters.hpp"
#include "pda_registration/ros/node_settings.hpp"
#include "pda_registration/ros/rate_budget.hpp"
#include "pda_registration/ros/seed_lookup.hpp"
#include "pda_registration/ros/tf_edge.hpp"

namespace pda_registration {

struct SparseJob {
  sensor_msgs::PointCloud2ConstPtr cloud;
  ros::WallTime received;
};

/// What the job uses; all owned by the nodelet and alive as long as the job.
struct AlignmentJobContext {
  const NodeSettings* settings;
  const tf2_ros::Buffer* tf_buffer;
  AlignmentPublisher* publisher;
  EdgeBroadcaster* edges;
  AlignmentStatus* status;
  DenseMapKeeper* keeper;
  IdleCores* idle_cores;
  RateBudget* rate_budget;
  NodeletLog log;
  std::string sparse_topic, dense_topic;
};

class AlignmentJob {
 public:
  explicit AlignmentJob(AlignmentJobContext context) : c_(std::move(context)) {}

  void run(const SparseJob& job, const LiveParameters& live);

 private:
  struct Accepted {
    const sensor_msgs::PointCloud2* cloud;
    const std::string* dense_frame;
    const RegistrationResult* result;
    const PointList* source;
    const Associations* associations;  // null: nobody watches the markers
    const LiveParameters* live;
  };
  /// ~transform, ~pose, ~aligned_cloud, ~associations and the tf edge (alignment_output.cpp).
  void publish(const Accepted& accepted);
  /// The result's covariance as ~pose carries it: in the dense map's frame, whichever cloud
  /// was the target.
  Eigen::Matrix<double, 6, 6> publishedCovariance(const RegistrationResult& result) const;
  /// Counts an edge composed with the latest tf, and logs when that starts or stops.
  void noteEdgeStamp(const TfEdge& edge);

  /// Whether this alignment starts from the seed corrected by the last accepted correction
  /// (core/warm_start.hpp): kWarmStartUsed, or why not.
  std::string warmStartUse(const Seed& seed, const std::string& dense_frame,
                           const std::string& sparse_frame, const LiveParameters& live) const;
  static const char* const kWarmStartUsed;

  /// Tells the keeper the sparse clouds' sample spacing (for the dense map's subset), measured
  /// on the first cloud and then every kSpacingPeriod seconds, after the answer is out.
  void reportSpacing(const PointList& sparse);

  AlignmentJobContext c_;
  PdaRegistration sparse_target_;  // the registration when the sparse cloud is the target
  WarmStart warm_start_;           // the worker thread's alone
  int abandoned_in_a_row_ = 0;     // warm alignments cut by the deadline since one ran its course
  ros::WallTime last_spacing_;
};

}  // namespace pda_registration

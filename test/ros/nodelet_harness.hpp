#pragma once
// Test-side companion of the map-alignment nodelet for rostest: publishes clouds and seeds the
// way a robot stack would, records everything the nodelet publishes (and its WARNs on /rosout),
// and waits for it with timeouts (the waits: nodelet_harness_waits.cpp).

#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <Eigen/Geometry>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "parameter_change.hpp"
#include "pda_registration/core/point_list.hpp"
#include "test_support/shared_data.hpp"

namespace pda_registration {
namespace testing_support {

class NodeletHarness {
 public:
  /// `nodelet_name` is the nodelet's node name (its private topics live below it).
  explicit NodeletHarness(const std::string& nodelet_name);
  /// Unsubscribes before the recorded messages go: the spinner's threads keep delivering
  /// (/rosout, /diagnostics) until then, and a callback must not reach a destroyed vector.
  ~NodeletHarness();

  void publishDense(const PointList& points, const std::string& frame);
  void publishSparse(const PointList& points, const std::string& frame);
  void publishRaw(const sensor_msgs::PointCloud2& cloud, bool dense);
  /// Takes the dense map's publisher away (the nodelet then sees none) and brings a new one.
  void closeDense();
  void reopenDense();
  /// Sets live parameters through dynamic_reconfigure's service; false when the call fails.
  /// `applied`, when given, receives the configuration the node reports back as in force.
  bool reconfigure(const ParameterChange& change, dynamic_reconfigure::Config* applied = nullptr);
  /// Static tf dense_frame -> sparse_frame (the seed). Waits until a listener besides this
  /// process's own (the nodelet's) is connected to /tf_static, publishes, and returns once this
  /// process's listener holds the seed (false after 10 s): the nodelet's gets it about then.
  bool publishSeed(const Eigen::Isometry3d& T_dense_sparse, const std::string& dense_frame,
                   const std::string& sparse_frame);

  /// Waits until `condition` holds (checked under the harness lock, so it must not call the
  /// harness's own accessors) or the timeout passes.
  bool waitFor(const std::function<bool()>& condition, double timeout_s);
  /// Waits for the (n+1)-th ~transform, n = transforms already received.
  bool waitForNextTransform(double timeout_s);
  /// Waits until more than `count` ~transforms have been received.
  bool waitForTransformsBeyond(size_t count, double timeout_s);
  /// Waits for the ~transform (markers) of the cloud stamped `stamp`: the result of that very
  /// cloud, not of one still in flight when it was published.
  bool waitForTransformStamped(const ros::Time& stamp, double timeout_s,
                               geometry_msgs::TransformStamped* found);
  bool waitForMarkersStamped(const ros::Time& stamp, double timeout_s,
                             visualization_msgs::MarkerArray* found);
  bool waitForWarnContaining(const std::string& text, double timeout_s);
  /// Any level (INFO and up) from the nodelet's log on /rosout.
  bool waitForLogContaining(const std::string& text, double timeout_s);
  /// Waits until all publishers and subscribers are connected to the nodelet.
  bool waitForConnections(double timeout_s);
  /// Waits only until this harness hears the nodelet's ~transform and diagnostics (when the
  /// clouds come from elsewhere, e.g. a bag).
  bool waitForOutputConnections(double timeout_s);

  /// Waits until more than `count` marker arrays (or poses) have been received.
  bool waitForMarkersBeyond(size_t count, double timeout_s);
  bool waitForPosesBeyond(size_t count, double timeout_s);

  size_t transformCount();
  geometry_msgs::TransformStamped lastTransform();
  std::vector<geometry_msgs::TransformStamped> transforms();
  geometry_msgs::PoseWithCovarianceStamped lastPose();
  size_t markerCount();
  visualization_msgs::MarkerArray lastMarkers();
  std::vector<std::string> warnings();
  /// The nodelet's diagnostics: how many statuses arrived, the latest one, and one of its values
  /// ("" when absent).
  size_t diagnosticsCount();
  diagnostic_msgs::DiagnosticStatus lastDiagnostics();
  std::string diagnosticValue(const std::string& key);
  /// Waits for a diagnostics status published after this call.
  bool waitForFreshDiagnostics(double timeout_s);
  /// Waits until a fresh diagnostics status counts as "accepted" exactly the transforms received.
  /// While the nodelet keeps aligning, a status can trail or lead the transform in flight, so
  /// this retries until one agrees; on timeout `detail` says what was seen last.
  bool waitForAcceptedToMatchTransforms(double timeout_s, std::string* detail);
  /// Everything logged on /rosout so far, one line per message (for failure messages).
  std::string logText();
  /// tf's transform between two frames, the latest or at `stamp` (throws
  /// tf2::TransformException).
  Eigen::Isometry3d lookup(const std::string& parent, const std::string& child, double timeout_s,
                           const ros::Time& stamp = ros::Time(0));
  /// The last ~transform received, once tf's latest dense_map -> sparse_map_aligned carries it
  /// too (the edge can reach the listener a little after the message); false on timeout.
  bool lastTransformOnTf(double timeout_s, Eigen::Isometry3d* last);

 private:
  ros::NodeHandle node_;
  std::string nodelet_name_;
  ros::Publisher dense_, sparse_;
  ros::Subscriber transform_, pose_, markers_, rosout_, diagnostics_;
  // Like tf2_ros::StaticTransformBroadcaster (one latched message holding every static
  // transform), but with the publisher at hand, to wait until the nodelet's listener connects.
  ros::Publisher tf_static_;
  tf2_msgs::TFMessage static_transforms_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  std::mutex mutex_;
  std::vector<geometry_msgs::TransformStamped> transforms_;
  std::vector<geometry_msgs::PoseWithCovarianceStamped> poses_;
  std::vector<visualization_msgs::MarkerArray> markers_received_;
  std::vector<std::string> warnings_, logs_;
  std::vector<diagnostic_msgs::DiagnosticStatus> diagnostics_received_;
};

/// The start of most nodelet tests: loads `case_name` of ../shared/data into `data` and waits
/// until the nodelet is connected to `harness` (20 s at most).
::testing::AssertionResult loadCaseAndConnect(NodeletHarness* harness, const std::string& case_name,
                                              SharedCase* data);

/// geometry_msgs/Transform as an isometry.
Eigen::Isometry3d toEigen(const geometry_msgs::Transform& transform);

/// Lines per source point and the alpha sum of each point's lines, grouped by line start.
struct MarkerGroups {
  std::vector<size_t> lines_per_point;
  std::vector<double> alpha_sum_per_point;
};
MarkerGroups groupAssociationLines(const visualization_msgs::MarkerArray& markers);

}  // namespace testing_support
}  // namespace pda_registration

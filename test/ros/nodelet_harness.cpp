#include "nodelet_harness.hpp"

#include <dynamic_reconfigure/Reconfigure.h>
#include <tf2_eigen/tf2_eigen.h>

#include <algorithm>
#include <map>
#include <tuple>

#include "pda_registration/ros/point_cloud_conversion.hpp"

namespace pda_registration {
namespace testing_support {

NodeletHarness::NodeletHarness(const std::string& nodelet_name)
    : nodelet_name_(nodelet_name),
      dense_(node_.advertise<sensor_msgs::PointCloud2>("dense_cloud", 1, true)),
      sparse_(node_.advertise<sensor_msgs::PointCloud2>("sparse_cloud", 5)),
      tf_static_(node_.advertise<tf2_msgs::TFMessage>("/tf_static", 10, true)),
      tf_listener_(tf_buffer_) {
  const std::string prefix = "/" + nodelet_name + "/";
  transform_ = node_.subscribe<geometry_msgs::TransformStamped>(
      prefix + "transform", 100, [this](const geometry_msgs::TransformStamped::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex_);
        transforms_.push_back(*m);
      });
  pose_ = node_.subscribe<geometry_msgs::PoseWithCovarianceStamped>(
      prefix + "pose", 10, [this](const geometry_msgs::PoseWithCovarianceStamped::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex_);
        poses_.push_back(*m);
      });
  markers_ = node_.subscribe<visualization_msgs::MarkerArray>(
      prefix + "associations", 2, [this](const visualization_msgs::MarkerArray::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex_);
        markers_received_.push_back(*m);
      });
  rosout_ = node_.subscribe<rosgraph_msgs::Log>("/rosout", 100,
                                                [this](const rosgraph_msgs::Log::ConstPtr& m) {
                                                  std::lock_guard<std::mutex> lock(mutex_);
                                                  logs_.push_back(m->msg);
                                                  if (m->level >= rosgraph_msgs::Log::WARN) {
                                                    warnings_.push_back(m->msg);
                                                  }
                                                });
  // The updater names its status "<node name>: alignment".
  diagnostics_ = node_.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 20, [this](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        std::lock_guard<std::mutex> lock(mutex_);
        for (const diagnostic_msgs::DiagnosticStatus& status : m->status) {
          if (status.name.find(nodelet_name_ + ": alignment") != std::string::npos) {
            diagnostics_received_.push_back(status);
          }
        }
      });
}

NodeletHarness::~NodeletHarness() {
  // Members go in reverse order of declaration: the vectors and their mutex before the
  // subscribers. Shutting the subscribers down first waits out any callback in flight.
  for (ros::Subscriber* subscriber : {&transform_, &pose_, &markers_, &rosout_, &diagnostics_}) {
    subscriber->shutdown();
  }
}

void NodeletHarness::closeDense() { dense_.shutdown(); }

void NodeletHarness::reopenDense() {
  dense_ = node_.advertise<sensor_msgs::PointCloud2>("dense_cloud", 1, true);
}

bool NodeletHarness::reconfigure(const ParameterChange& change,
                                 dynamic_reconfigure::Config* applied) {
  dynamic_reconfigure::Reconfigure call;
  call.request.config = change.config();
  if (!ros::service::call("/" + nodelet_name_ + "/set_parameters", call)) return false;
  if (applied) *applied = call.response.config;
  return true;
}

void NodeletHarness::publishDense(const PointList& points, const std::string& frame) {
  std_msgs::Header header;
  header.frame_id = frame;
  header.stamp = ros::Time::now();
  dense_.publish(toPointCloud2(points, header));
}

void NodeletHarness::publishSparse(const PointList& points, const std::string& frame) {
  std_msgs::Header header;
  header.frame_id = frame;
  header.stamp = ros::Time::now();
  sparse_.publish(toPointCloud2(points, header));
}

void NodeletHarness::publishRaw(const sensor_msgs::PointCloud2& cloud, bool dense) {
  (dense ? dense_ : sparse_).publish(cloud);
}

bool NodeletHarness::publishSeed(const Eigen::Isometry3d& T, const std::string& dense_frame,
                                 const std::string& sparse_frame) {
  geometry_msgs::TransformStamped seed = tf2::eigenToTransform(T);
  seed.header.stamp = ros::Time::now();
  seed.header.frame_id = dense_frame;
  seed.child_frame_id = sparse_frame;
  // A latched message reaches a listener only once it has connected, and a busy machine can take
  // over a second to connect the nodelet's listener to this new publisher.
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(10.0);
  while (ros::ok() && tf_static_.getNumSubscribers() < 2 && ros::WallTime::now() < end) {
    ros::WallDuration(0.02).sleep();
  }
  auto& transforms = static_transforms_.transforms;
  transforms.erase(std::remove_if(transforms.begin(), transforms.end(),
                                  [&](const geometry_msgs::TransformStamped& t) {
                                    return t.child_frame_id == sparse_frame;
                                  }),
                   transforms.end());
  transforms.push_back(seed);
  tf_static_.publish(static_transforms_);
  while (ros::ok() && ros::WallTime::now() < end) {
    try {
      const Eigen::Isometry3d on_tf = lookup(dense_frame, sparse_frame, 0.0);
      if (on_tf.isApprox(T, 1e-9)) return true;
    } catch (const tf2::TransformException&) {
      // not there yet
    }
    ros::WallDuration(0.02).sleep();
  }
  return false;
}

size_t NodeletHarness::transformCount() {
  std::lock_guard<std::mutex> lock(mutex_);
  return transforms_.size();
}

geometry_msgs::TransformStamped NodeletHarness::lastTransform() {
  std::lock_guard<std::mutex> lock(mutex_);
  return transforms_.empty() ? geometry_msgs::TransformStamped() : transforms_.back();
}

std::vector<geometry_msgs::TransformStamped> NodeletHarness::transforms() {
  std::lock_guard<std::mutex> lock(mutex_);
  return transforms_;
}

size_t NodeletHarness::diagnosticsCount() {
  std::lock_guard<std::mutex> lock(mutex_);
  return diagnostics_received_.size();
}

diagnostic_msgs::DiagnosticStatus NodeletHarness::lastDiagnostics() {
  std::lock_guard<std::mutex> lock(mutex_);
  return diagnostics_received_.empty() ? diagnostic_msgs::DiagnosticStatus()
                                       : diagnostics_received_.back();
}

std::string NodeletHarness::diagnosticValue(const std::string& key) {
  for (const diagnostic_msgs::KeyValue& entry : lastDiagnostics().values) {
    if (entry.key == key) return entry.value;
  }
  return "";
}

geometry_msgs::PoseWithCovarianceStamped NodeletHarness::lastPose() {
  std::lock_guard<std::mutex> lock(mutex_);
  return poses_.empty() ? geometry_msgs::PoseWithCovarianceStamped() : poses_.back();
}

size_t NodeletHarness::markerCount() {
  std::lock_guard<std::mutex> lock(mutex_);
  return markers_received_.size();
}

visualization_msgs::MarkerArray NodeletHarness::lastMarkers() {
  std::lock_guard<std::mutex> lock(mutex_);
  return markers_received_.empty() ? visualization_msgs::MarkerArray() : markers_received_.back();
}

std::vector<std::string> NodeletHarness::warnings() {
  std::lock_guard<std::mutex> lock(mutex_);
  return warnings_;
}

std::string NodeletHarness::logText() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::string text;
  for (const std::string& line : logs_) text += line + "\n";
  return text;
}

Eigen::Isometry3d NodeletHarness::lookup(const std::string& parent, const std::string& child,
                                         double timeout_s, const ros::Time& stamp) {
  return tf2::transformToEigen(
      tf_buffer_.lookupTransform(parent, child, stamp, ros::Duration(timeout_s)));
}

::testing::AssertionResult loadCaseAndConnect(NodeletHarness* harness, const std::string& case_name,
                                              SharedCase* data) {
  std::string error;
  if (!loadSharedCase(case_name, data, &error)) return ::testing::AssertionFailure() << error;
  if (!harness->waitForConnections(20.0)) {
    return ::testing::AssertionFailure() << "the nodelet did not connect within 20 s";
  }
  return ::testing::AssertionSuccess();
}

Eigen::Isometry3d toEigen(const geometry_msgs::Transform& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(t.rotation.w, t.rotation.x, t.rotation.y, t.rotation.z)
                   .normalized()
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(t.translation.x, t.translation.y, t.translation.z);
  return T;
}

MarkerGroups groupAssociationLines(const visualization_msgs::MarkerArray& markers) {
  std::map<std::tuple<double, double, double>, std::pair<size_t, double>> groups;
  for (const visualization_msgs::Marker& m : markers.markers) {
    if (m.type != visualization_msgs::Marker::LINE_LIST) continue;
    for (size_t i = 0; i + 1 < m.points.size(); i += 2) {
      auto& g = groups[std::make_tuple(m.points[i].x, m.points[i].y, m.points[i].z)];
      ++g.first;
      g.second += m.colors[i].a;
    }
  }
  MarkerGroups out;
  for (const auto& g : groups) {
    out.lines_per_point.push_back(g.second.first);
    out.alpha_sum_per_point.push_back(g.second.second);
  }
  return out;
}

}  // namespace testing_support
}  // namespace pda_registration

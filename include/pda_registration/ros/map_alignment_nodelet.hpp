#pragma once
// pda_registration/MapAlignmentNodelet: keeps the transform between a dense and a sparse map
// corrected online. Callbacks only queue the newest clouds; a worker thread converts them,
// indexes the target, looks up the seed on tf, aligns, gates the result and publishes it, so a
// slow registration never blocks tf, other callbacks or other nodelets of the manager.

#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <nodelet/nodelet.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <boost/thread/recursive_mutex.hpp>
#include <memory>
#include <mutex>
#include <thread>

#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/ros/alignment_publisher.hpp"
#include "pda_registration/ros/latest_input_queue.hpp"
#include "pda_registration/ros/live_parameters.hpp"
#include "pda_registration/ros/node_settings.hpp"
#include "pda_registration/ros/seed_lookup.hpp"
#include "pda_registration/ros/tf_edge.hpp"

namespace pda_registration {

class MapAlignmentNodelet : public nodelet::Nodelet {
 public:
  MapAlignmentNodelet() = default;
  ~MapAlignmentNodelet() override;

 private:
  struct SparseJob {
    sensor_msgs::PointCloud2ConstPtr cloud;
    ros::WallTime received;
  };

  // What the diagnostics report; guarded by status_mutex_.
  struct Status {
    size_t sparse_received = 0, dense_received = 0, dense_unchanged = 0;
    size_t dropped_stale = 0, dropped_throttled = 0;
    size_t input_errors = 0, missing_seed = 0;
    size_t aligned = 0, accepted = 0, rejected = 0;
    bool have_result = false, last_accepted = false;
    RegistrationResult last_result;
    SeedSource last_seed = SeedSource::kNone;
    std::string last_problem;  // the latest rejection or input error, for the WARN status
    double last_latency_ms = 0.0;
    ros::Time last_problem_time;
    // The dense map in use: its size, when it arrived (wall clock: sim time may jump back or
    // stand still), and the size of the current (possibly cropped) index.
    size_t dense_points = 0, indexed_points = 0;
    bool target_cropped = false;
    ros::WallTime dense_arrival;
  };

  void onInit() override;
  void denseCallback(const sensor_msgs::PointCloud2ConstPtr& cloud);
  void sparseCallback(const sensor_msgs::PointCloud2ConstPtr& cloud);
  void reconfigure(PdaRegistrationConfig& config, uint32_t level);
  void workerLoop();
  void updateDenseCloud(const sensor_msgs::PointCloud2ConstPtr& cloud);
  void alignSparseCloud(const SparseJob& job);
  void republishTf(const ros::TimerEvent& event);
  /// Sends `fresh` on tf and keeps it for re-broadcasts; null: the timer's re-broadcast of the
  /// kept edge.
  void broadcastEdge(const TfEdge* fresh, const ros::Time& stamp);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);
  /// Records a problem for diagnostics and logs a WARN, throttled per `kind`.
  void reportProblem(const std::string& kind, const std::string& problem, bool input_error);
  bool checkFrame(const sensor_msgs::PointCloud2& cloud, const std::string& expected,
                  const char* kind);

  NodeSettings settings_;
  bool settings_ok_ = false;
  std::string settings_error_;

  std::mutex live_mutex_;
  LiveParameters live_;
  // The last configuration accepted, handed back when a change is refused (only touched in the
  // reconfigure callback, which dynamic_reconfigure serialises).
  PdaRegistrationConfig accepted_config_;
  bool have_accepted_config_ = false;
  ros::Time last_sparse_accepted_;

  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  std::unique_ptr<AlignmentPublisher> publisher_;
  std::unique_ptr<dynamic_reconfigure::Server<PdaRegistrationConfig>> reconfigure_server_;
  boost::recursive_mutex reconfigure_mutex_;  // dynamic_reconfigure requires boost's
  std::unique_ptr<diagnostic_updater::Updater> diagnostics_;
  ros::Subscriber dense_subscriber_, sparse_subscriber_;
  ros::Timer tf_timer_;
  ros::WallTimer diagnostics_timer_;  // wall clock: diagnostics flow while a bag pauses or loops

  // Worker-thread state (touched only by the worker after start).
  LatestInputQueue<sensor_msgs::PointCloud2ConstPtr, SparseJob> queue_;
  std::thread worker_;
  PdaRegistration registration_;
  PointList dense_points_;  // kept when the dense cloud is the registration source
  std::string dense_frame_;
  bool have_dense_ = false;
  uint64_t dense_fingerprint_ = 0;  // of the map in use: an unchanged re-publication is skipped

  // The last accepted estimate as our tf edge, re-broadcast unchanged; guarded by edge_mutex_.
  std::mutex edge_mutex_;
  bool have_edge_ = false;
  TfEdge edge_;
  ros::Time last_tf_stamp_;  // newest stamp broadcast on our edge (tf drops older data loudly)

  std::mutex status_mutex_;
  Status status_;
};

}  // namespace pda_registration

#pragma once
// pda_registration/MapAlignmentNodelet: keeps the transform between a dense and a sparse map
// corrected online. Callbacks only queue the newest clouds. The keeper's thread indexes each new
// dense map beside the alignments (double-buffered); a worker thread converts each sparse cloud,
// looks up the seed on tf, aligns it with the newest ready map, gates the result and publishes
// it, so a slow registration or index build never blocks tf, other callbacks or other nodelets
// of the manager, and an alignment never waits for an index build.
//
// Where each concern lives:
//   map_alignment_nodelet.cpp   start-up, dynamic_reconfigure, diagnostics hook-up
//   map_alignment_intake.cpp    subscriber callbacks, the mailbox and the worker loop
//   dense_map_keeper.*          index keeping (each new dense map, on its own thread)
//   alignment_job.*             one sparse cloud -> seed -> align -> gate
//   alignment_output.cpp        publishing an accepted estimate; edge_broadcaster.* the tf edge
//   alignment_status.*          what the diagnostics report

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

#include "pda_registration/ros/alignment_job.hpp"
#include "pda_registration/ros/alignment_publisher.hpp"
#include "pda_registration/ros/alignment_status.hpp"
#include "pda_registration/ros/dense_map_keeper.hpp"
#include "pda_registration/ros/edge_broadcaster.hpp"
#include "pda_registration/ros/idle_cores.hpp"
#include "pda_registration/ros/latest_input_queue.hpp"
#include "pda_registration/ros/live_parameters.hpp"
#include "pda_registration/ros/node_settings.hpp"
#include "pda_registration/ros/rate_budget.hpp"

namespace pda_registration {

class MapAlignmentNodelet : public nodelet::Nodelet {
 public:
  MapAlignmentNodelet() = default;
  ~MapAlignmentNodelet() override;

 private:
  void onInit() override;
  void reconfigure(PdaRegistrationConfig& config, uint32_t level);
  LiveParameters liveParameters();
  /// Records a problem for diagnostics and logs a WARN, throttled per `kind`.
  void reportProblem(const std::string& kind, const std::string& problem, bool input_error);
  NodeletLog nodeletLog();

  // Intake (map_alignment_intake.cpp).
  void denseCallback(const sensor_msgs::PointCloud2ConstPtr& cloud);
  void sparseCallback(const sensor_msgs::PointCloud2ConstPtr& cloud);
  void workerLoop();

  NodeSettings settings_;
  bool settings_ok_ = false;
  std::string settings_error_;

  std::mutex live_mutex_;
  LiveParameters live_;
  // The last configuration accepted, handed back when a change is refused (only touched in the
  // reconfigure callback, which dynamic_reconfigure serialises).
  PdaRegistrationConfig accepted_config_;
  bool have_accepted_config_ = false;
  ros::Time last_sparse_accepted_;  // guarded by the status lock (sparse callback only)

  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  std::unique_ptr<AlignmentPublisher> publisher_;
  std::unique_ptr<EdgeBroadcaster> edges_;
  std::unique_ptr<dynamic_reconfigure::Server<PdaRegistrationConfig>> reconfigure_server_;
  boost::recursive_mutex reconfigure_mutex_;  // dynamic_reconfigure requires boost's
  std::unique_ptr<diagnostic_updater::Updater> diagnostics_;
  ros::Subscriber dense_subscriber_, sparse_subscriber_;
  ros::Timer tf_timer_;
  ros::WallTimer diagnostics_timer_;  // wall clock: diagnostics flow while a bag pauses or loops

  AlignmentStatus status_;
  // Sampled every second by the diagnostics timer, so the alignments' thread count follows the
  // last second's load, not the whole time since the previous alignment (or start-up).
  IdleCores idle_cores_;
  RateBudget rate_budget_;  // arrivals noted by the sparse callback, budgets by the job
  LatestInputQueue<sensor_msgs::PointCloud2ConstPtr, SparseJob> queue_;
  std::unique_ptr<DenseMapKeeper> keeper_;  // indexes dense maps on its own thread
  std::unique_ptr<AlignmentJob> job_;       // worker thread only
  std::thread worker_;
};

}  // namespace pda_registration

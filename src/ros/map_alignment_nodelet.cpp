// Start-up of the nodelet: settings, tf, publishers, dynamic_reconfigure, diagnostics, and the
// parts that do the work (see map_alignment_nodelet.hpp for where each concern lives).
#include "pda_registration/ros/map_alignment_nodelet.hpp"

#include <pluginlib/class_list_macros.hpp>

namespace pda_registration {

MapAlignmentNodelet::~MapAlignmentNodelet() {
  if (keeper_) keeper_->stop();  // wakes an alignment waiting for the first map
  queue_.stop();
  if (worker_.joinable()) worker_.join();
}

void MapAlignmentNodelet::onInit() {
  ros::NodeHandle& node = getNodeHandle();
  ros::NodeHandle& private_node = getPrivateNodeHandle();

  // Named after the nodelet, not the manager it shares: "<nodelet name>: alignment".
  diagnostics_ = std::make_unique<diagnostic_updater::Updater>(node, private_node, getName());
  diagnostics_->setHardwareID(getName());
  diagnostics_->add("alignment", [this](diagnostic_updater::DiagnosticStatusWrapper& status) {
    if (!settings_ok_) {
      status.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "not started: " + settings_error_);
      return;
    }
    status_.fill(status, dense_subscriber_.getNumPublishers());
  });
  // force_update on our own wall-clock timer: Updater::update() compares against ROS time and
  // would fall silent for the length of a bag after a loop jumps simulated time back.
  diagnostics_timer_ =
      node.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) {
        idle_cores_.sample();
        diagnostics_->force_update();
      });

  settings_ok_ = readNodeSettings(private_node, &settings_, &settings_error_);
  if (!settings_ok_) {
    // A bad static parameter disables this nodelet, never the manager it shares.
    NODELET_ERROR("not started: %s", settings_error_.c_str());
    return;
  }

  tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
  tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_, node);
  publisher_ = std::make_unique<AlignmentPublisher>(private_node);
  edges_ = std::make_unique<EdgeBroadcaster>(publisher_.get());
  reconfigure_server_ = std::make_unique<dynamic_reconfigure::Server<PdaRegistrationConfig>>(
      reconfigure_mutex_, private_node);
  reconfigure_server_->setCallback(boost::bind(&MapAlignmentNodelet::reconfigure, this,
                                               boost::placeholders::_1, boost::placeholders::_2));

  const std::string dense_topic = node.resolveName("dense_cloud");
  const std::string sparse_topic = node.resolveName("sparse_cloud");
  keeper_ = std::make_unique<DenseMapKeeper>(settings_.dense_is_target,
                                             settings_.expected_dense_frame, dense_topic, &status_,
                                             nodeletLog(), [this] { return liveParameters(); });
  job_ = std::make_unique<AlignmentJob>(AlignmentJobContext{
      &settings_, tf_buffer_.get(), publisher_.get(), edges_.get(), &status_, keeper_.get(),
      &idle_cores_, &rate_budget_, nodeletLog(), sparse_topic, dense_topic});
  worker_ = std::thread(&MapAlignmentNodelet::workerLoop, this);
  dense_subscriber_ = node.subscribe("dense_cloud", 2, &MapAlignmentNodelet::denseCallback, this);
  sparse_subscriber_ =
      node.subscribe("sparse_cloud", 5, &MapAlignmentNodelet::sparseCallback, this);
  if (settings_.publish_tf && settings_.tf_publish_rate > 0.0) {
    tf_timer_ = node.createTimer(ros::Duration(1.0 / settings_.tf_publish_rate),
                                 [this](const ros::TimerEvent&) { edges_->rebroadcast(); });
  }
  NODELET_INFO("aligning %s (target: %s cloud) with seeds from tf%s",
               sparse_subscriber_.getTopic().c_str(),
               settings_.dense_is_target ? "dense" : "sparse",
               settings_.has_initial_transform ? " or ~initial_transform" : "");
}

void MapAlignmentNodelet::reconfigure(PdaRegistrationConfig& config, uint32_t) {
  const LiveParameters live = liveParametersFrom(config);
  const std::string problem = validateParameters(live.registration);
  if (!problem.empty()) {
    // The .cfg limits make this rare (e.g. closed_form with surface_anisotropy > 1): keep the
    // previous parameters, say why, and hand them back, so that what dynamic_reconfigure
    // publishes (rqt_reconfigure, dynparam) is what runs.
    NODELET_WARN("reconfigure refused: %s; keeping the previous parameters", problem.c_str());
    if (have_accepted_config_) config = accepted_config_;
    return;
  }
  accepted_config_ = config;
  have_accepted_config_ = true;
  bool subset_switched;
  {
    std::lock_guard<std::mutex> lock(live_mutex_);
    subset_switched = live_.dense_subset != live.dense_subset;
    live_ = live;
  }
  if (subset_switched && keeper_) keeper_->reindexLatest();
}

LiveParameters MapAlignmentNodelet::liveParameters() {
  std::lock_guard<std::mutex> lock(live_mutex_);
  return live_;
}

void MapAlignmentNodelet::reportProblem(const std::string& kind, const std::string& problem,
                                        bool input_error) {
  if (status_.recordProblem(kind, problem, input_error)) NODELET_WARN("%s", problem.c_str());
}

NodeletLog MapAlignmentNodelet::nodeletLog() {
  return {[this](const std::string& kind, const std::string& problem, bool input_error) {
            reportProblem(kind, problem, input_error);
          },
          [this](const std::string& line) { NODELET_INFO("%s", line.c_str()); }};
}

}  // namespace pda_registration

PLUGINLIB_EXPORT_CLASS(pda_registration::MapAlignmentNodelet, nodelet::Nodelet)

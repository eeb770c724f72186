#pragma once
// Keeps the last accepted estimate as the node's tf edge and (re-)broadcasts it. Stamps on the
// edge only move forward: tf listeners drop data older than what they hold (TF_OLD_DATA) or at a
// stamp they already have (TF_REPEATED_DATA), each with a warning. Thread-safe.

#include <ros/time.h>

#include <mutex>

#include "pda_registration/ros/alignment_publisher.hpp"
#include "pda_registration/ros/tf_edge.hpp"

namespace pda_registration {

class EdgeBroadcaster {
 public:
  explicit EdgeBroadcaster(AlignmentPublisher* publisher) : publisher_(publisher) {}

  /// Keeps `edge` and sends it stamped `stamp` (or later, if tf already has that stamp).
  void sendFresh(const TfEdge& edge, const ros::Time& stamp) { send(&edge, stamp); }
  /// The timer's re-broadcast of the kept edge, stamped now (nothing before the first edge).
  void rebroadcast();

 private:
  void send(const TfEdge* fresh, const ros::Time& requested_stamp);

  AlignmentPublisher* publisher_;
  std::mutex mutex_;
  bool have_edge_ = false;
  TfEdge edge_;
  ros::Time last_stamp_;  // newest stamp broadcast on our edge
};

}  // namespace pda_registration

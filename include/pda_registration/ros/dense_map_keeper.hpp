#pragma once
// Index keeping: turns each dense map message into the map the alignments use. As the
// registration target (the default) the map is filtered and indexed (PdaRegistration::setTarget);
// as the registration source it is only converted. A map re-published unchanged (same 64-bit
// fingerprint of frame, layout and bytes) is recognised and skipped.

#include <sensor_msgs/PointCloud2.h>

#include <functional>
#include <string>

#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/ros/alignment_status.hpp"

namespace pda_registration {

/// How the nodelet's parts report: a problem (WARN, throttled per kind, and the diagnostics) and
/// an INFO line.
struct NodeletLog {
  std::function<void(const std::string& kind, const std::string& problem, bool input_error)>
      problem;
  std::function<void(const std::string& line)> info;
};

class DenseMapKeeper {
 public:
  DenseMapKeeper(bool dense_is_target, std::string expected_frame, std::string topic,
                 AlignmentStatus* status, NodeletLog log)
      : dense_is_target_(dense_is_target),
        expected_frame_(std::move(expected_frame)),
        topic_(std::move(topic)),
        status_(status),
        log_(std::move(log)) {}

  /// Takes a new dense map message; `parameters` decide how the target is indexed.
  void update(const sensor_msgs::PointCloud2ConstPtr& cloud,
              const RegistrationParameters& parameters);

  bool haveMap() const { return have_dense_; }
  const std::string& frame() const { return dense_frame_; }
  /// The registration holding the indexed map as its target (dense map = target).
  PdaRegistration& registration() { return registration_; }
  /// The map's points (dense map = source).
  const PointList& points() const { return dense_points_; }

 private:
  const bool dense_is_target_;
  const std::string expected_frame_, topic_;
  AlignmentStatus* status_;
  NodeletLog log_;

  PdaRegistration registration_;
  PointList dense_points_;  // kept when the dense cloud is the registration source
  std::string dense_frame_;
  bool have_dense_ = false;
  uint64_t fingerprint_ = 0;  // of the map in use: an unchanged re-publication is skipped
};

}  // namespace pda_registration

#pragma once
// Where the next alignment of a running system starts: its seed corrected by the last accepted
// correction. A seed publisher's error (odometry drift, a calibration or map offset) changes
// slowly, so the correction that fixed the last sparse cloud is the best guess for the next one,
// the way amcl's map -> odom correction carries over from scan to scan: the alignment starts near
// its answer and needs fewer runs. The correction is kept on the dense side,
//   C = T_estimate * T_seed^-1   (dense <- dense),
// because that is where drift accumulates: it stays valid while the sensor moves under it.
// ROS-free; the nodelet decides whether it applies (not while its own tf edge is part of the
// seed: the seed then already holds the correction).

#include <Eigen/Geometry>
#include <functional>
#include <string>

namespace pda_registration {

class WarmStart {
 public:
  /// True when a correction is held for these frames.
  bool holds(const std::string& dense_frame, const std::string& sparse_frame) const;
  /// The seed (dense <- sparse) corrected: C * seed. Only meaningful when holds() for its frames.
  Eigen::Isometry3d corrected(const Eigen::Isometry3d& T_dense_sparse_seed) const;
  /// Keeps the correction from an accepted estimate and the seed it started from.
  void remember(const Eigen::Isometry3d& T_dense_sparse_seed,
                const Eigen::Isometry3d& T_dense_sparse_estimate, const std::string& dense_frame,
                const std::string& sparse_frame);
  void forget();

 private:
  bool have_ = false;
  Eigen::Isometry3d correction_ = Eigen::Isometry3d::Identity();
  std::string dense_frame_, sparse_frame_;
};

/// How one attempt of alignFromWarmStart ended.
enum class AttemptOutcome {
  kAccepted,
  kRejected,
  kOutOfTime,  ///< stopped by its time limit: the time for a retry is spent as well
};

/// One alignment of a running system: `attempt` (align from an initial dense <- sparse transform;
/// `warm` says whether that is the corrected seed) from `warm`'s corrected seed when `use_warm` is
/// set, and from the seed itself when it is not, or when the warm attempt was rejected (the
/// correction may be stale: the seed's publisher jumped, relocalised). A warm attempt that ran out
/// of time is not retried. Returns true when it retried.
bool alignFromWarmStart(
    const WarmStart& warm, bool use_warm, const Eigen::Isometry3d& T_dense_sparse_seed,
    const std::function<AttemptOutcome(const Eigen::Isometry3d& initial, bool warm)>& attempt);

}  // namespace pda_registration

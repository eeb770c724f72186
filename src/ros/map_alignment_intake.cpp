// Intake: the subscriber callbacks only count and queue (one-slot mailbox per input kind, the
// newest wins): dense maps to the keeper's thread, sparse clouds to the worker thread, which hands
// each to the alignment job.
#include <malloc.h>

#include "pda_registration/ros/map_alignment_nodelet.hpp"

namespace pda_registration {

void MapAlignmentNodelet::denseCallback(const sensor_msgs::PointCloud2ConstPtr& cloud) {
  status_.update([](AlignmentStatusValues& s) { ++s.dense_received; });
  keeper_->put(cloud);  // indexed on the keeper's thread
}

void MapAlignmentNodelet::sparseCallback(const sensor_msgs::PointCloud2ConstPtr& cloud) {
  const double min_interval = liveParameters().min_interval;
  const ros::Time now = ros::Time::now();
  status_.update([&](AlignmentStatusValues& s) {
    ++s.sparse_received;
    if (now < last_sparse_accepted_) last_sparse_accepted_ = ros::Time();  // clock jumped back
    if (min_interval > 0.0 && !last_sparse_accepted_.isZero() &&
        (now - last_sparse_accepted_).toSec() < min_interval) {
      ++s.dropped_throttled;
      return;
    }
    last_sparse_accepted_ = now;
    const ros::WallTime received = ros::WallTime::now();
    rate_budget_.noteArrival(received.toSec());
    if (queue_.putSparse({cloud, received})) ++s.dropped_stale;
  });
}

void MapAlignmentNodelet::workerLoop() {
  sensor_msgs::PointCloud2ConstPtr dense;
  SparseJob sparse;
  bool has_dense = false, has_sparse = false;
  while (queue_.waitAndTake(&dense, &has_dense, &sparse, &has_sparse)) {
    try {
      if (has_sparse) job_->run(sparse, liveParameters());
    } catch (const std::exception& error) {
      reportProblem("internal", std::string("internal error: ") + error.what(), false);
    }
    // Let go of the messages now rather than when the next ones arrive, and hand the freed
    // megabytes back to the system: glibc otherwise keeps them in its per-thread arenas, and a
    // stream of large maps (freed by one thread, allocated by another) ratchets the manager's
    // RSS up by tens of MB a minute (measured by the stress rostest; flat with the trim).
    dense.reset();
    sparse = SparseJob();
    malloc_trim(0);
  }
}

}  // namespace pda_registration

#include "pda_registration/ros/dense_map_keeper.hpp"

#include <malloc.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <cstdio>

#include "pda_registration/ros/input_checks.hpp"
#include "pda_registration/ros/point_cloud_conversion.hpp"

namespace pda_registration {
namespace {

// CPU time of the calling thread [ms]: what an update costs, whatever else runs on the machine
// (the keeper runs at a low priority, so its wall time also holds the time it yielded).
double threadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

}  // namespace

DenseMapKeeper::DenseMapKeeper(bool dense_is_target, std::string expected_frame,
                               std::string topic, AlignmentStatus* status, NodeletLog log,
                               ParameterSource parameters)
    : dense_is_target_(dense_is_target),
      expected_frame_(std::move(expected_frame)),
      topic_(std::move(topic)),
      status_(status),
      log_(std::move(log)),
      parameters_(std::move(parameters)) {
  thread_ = std::thread(&DenseMapKeeper::loop, this);
}

DenseMapKeeper::~DenseMapKeeper() {
  stop();
  if (thread_.joinable()) thread_.join();
}

void DenseMapKeeper::stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopped_ = true;
  }
  changed_.notify_all();
  queue_.stop();
}

void DenseMapKeeper::put(const sensor_msgs::PointCloud2ConstPtr& cloud) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (front_ < 0) pending_first_ = true;
  }
  queue_.putDense(cloud);  // maps are slow; a replaced pending map needs no counting
  fold_cancel_ = true;     // after the put: a fold that starts later sees the map waiting
}

void DenseMapKeeper::noteSparseSpacing(double spacing) {
  if (!(spacing > 0.0) || !std::isfinite(spacing)) return;
  const double current = sparse_spacing_.load();
  // Scans of one sensor vary a little: only a real change re-indexes.
  if (subsetVoxelHolds(current, spacing)) return;
  sparse_spacing_ = spacing;
  reindexLatest();
}

void DenseMapKeeper::reindexLatest() {
  sensor_msgs::PointCloud2ConstPtr latest;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    latest = latest_;
  }
  if (latest && !queue_.denseWaiting()) put(latest);
}

DenseMapKeeper::Borrowed::~Borrowed() {
  if (slot_) keeper_->giveBack(slot_);
}

DenseMapKeeper::Borrowed DenseMapKeeper::borrow(double first_map_timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait_for(lock, std::chrono::duration<double>(first_map_timeout),
                    [this] { return stopped_ || front_ >= 0 || !pending_first_; });
  if (front_ < 0 || stopped_) return Borrowed();
  ++borrowed_[front_];
  return Borrowed(this, &slots_[front_]);
}

void DenseMapKeeper::giveBack(DenseMapSlot* slot) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    --borrowed_[slot - slots_];
  }
  changed_.notify_all();
}

void DenseMapKeeper::loop() {
  // Indexing is background work: at a lower priority (nice +10, this thread only) it yields the
  // CPU to the alignments, whose latency is what users see; the diagnostics show the index age.
  if (setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 10) != 0) {
    log_.info("could not lower the priority of the indexing thread; it competes with alignments");
  }
  sensor_msgs::PointCloud2ConstPtr dense;
  int unused;
  bool has_dense = false, has_unused = false;
  while (queue_.waitAndTake(&dense, &has_dense, &unused, &has_unused)) {
    try {
      if (has_dense) update(dense);
    } catch (const std::exception& error) {
      log_.problem("internal", std::string("internal error indexing a dense map: ") + error.what(),
                   false);
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (front_ < 0) pending_first_ = false;  // that one failed: alignments need not wait
    }
    changed_.notify_all();
    // Release the message now and hand freed memory back (see the worker loop).
    dense.reset();
    malloc_trim(0);
    foldLatest();
  }
}

void DenseMapKeeper::foldLatest() {
  const std::shared_ptr<const TargetIndex> index = std::move(to_fold_);
  to_fold_.reset();
  if (!index || index->trees() <= 1) return;
  // Two trees: the new map first (its update adds a third). More: every query descends each, and
  // on a busy machine a fold at nice +10 outlasts the map period, so cancelling it would let the
  // trees pile up: the fold goes first and the waiting map is indexed right after.
  const bool yield_to_maps = index->trees() <= 2;
  fold_cancel_ = false;
  if (yield_to_maps && queue_.denseWaiting()) return;
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = threadCpuMs();
  if (!index->fold(yield_to_maps ? &fold_cancel_ : nullptr)) return;
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const double cpu_ms = threadCpuMs() - cpu_start;
  status_->update([&](AlignmentStatusValues& s) {
    s.index_fold_ms = ms;
    ++s.index_folds;
  });
  char line[200];
  std::snprintf(line, sizeof(line),
                "index of %zu points folded into one tree in %.0f ms (%.0f ms CPU)",
                index->size(), ms, cpu_ms);
  log_.info(line);
}

bool DenseMapKeeper::keptWhole(DenseMapSlot* front, const PointList& map, double sparse_spacing) {
  // The subset fields are the keeper's own: alignments borrowing the front never read them.
  if (front->subset && front->subset->thinned()) return false;
  std::unique_ptr<RepresentativeSubset> subset;
  if (sparse_spacing > 0.0) {
    subset = std::make_unique<RepresentativeSubset>(sparse_spacing);
    subset->update(map);
    if (subset->thinned()) return false;
  }
  front->subset = std::move(subset);
  front->sparse_spacing = sparse_spacing;
  status_->update([&](AlignmentStatusValues& s) { s.sparse_spacing = sparse_spacing; });
  char line[200];
  std::snprintf(line, sizeof(line),
                "dense map kept whole: not much finer than the sparse clouds' spacing %.1f cm",
                100.0 * sparse_spacing);
  log_.info(line);
  return true;
}

void DenseMapKeeper::update(const sensor_msgs::PointCloud2ConstPtr& cloud) {
  const std::string frame_problem = frameProblem(*cloud, expected_frame_, "dense");
  if (!frame_problem.empty()) {
    log_.problem("frame", frame_problem, true);
    return;
  }
  const uint64_t fingerprint = cloudFingerprint(*cloud);
  const LiveParameters live = parameters_();
  const double sparse_spacing =
      dense_is_target_ && live.dense_subset ? sparse_spacing_.load() : 0.0;
  int back, front;
  bool same_map;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    if (dense_is_target_) latest_ = cloud;
    front = front_;
    same_map = front_ >= 0 && slots_[front_].fingerprint == fingerprint;
    if (same_map && slots_[front_].sparse_spacing == sparse_spacing) {
      lock.unlock();
      status_->update([](AlignmentStatusValues& s) {
        ++s.dense_unchanged;
        s.dense_arrival = ros::WallTime::now();  // the map is alive, just not new
      });
      return;
    }
    back = front_ < 0 ? 0 : 1 - front_;
  }
  const auto start = std::chrono::steady_clock::now();
  CloudConversion converted = fromPointCloud2(*cloud);
  if (!converted.ok()) {
    log_.problem("dense " + converted.error.substr(0, 12),
                 "dense cloud " + describeCloud(*cloud, topic_) + " refused: " + converted.error +
                     "; keeping the previous map",
                 true);
    return;
  }
  const double convert_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (same_map && dense_is_target_ && keptWhole(&slots_[front], converted.points, sparse_spacing)) {
    return;
  }
  {
    // An alignment that began before the last swap may still use the back slot: let it finish.
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return stopped_ || borrowed_[back] == 0; });
    if (stopped_) return;
  }
  DenseMapSlot& slot = slots_[back];
  const auto index_start = std::chrono::steady_clock::now();
  const double index_cpu_start = threadCpuMs();
  const char* how = "stored";
  size_t appended = 0;
  if (dense_is_target_) {
    slot.registration.setParameters(live.registration);
    const std::shared_ptr<const TargetIndex> previous = slot.registration.target();
    slot.map_points = converted.points.size();
    if (!(sparse_spacing > 0.0)) {
      slot.subset.reset();
    } else if (!slot.subset || slot.subset->voxelSize() != sparse_spacing) {
      slot.subset = std::make_unique<RepresentativeSubset>(sparse_spacing);
    }
    slot.sparse_spacing = sparse_spacing;
    if (slot.subset) slot.subset->update(converted.points);
    PointList target = slot.subset && slot.subset->thinned() ? slot.subset->points()
                                                             : std::move(converted.points);
    if (!slot.registration.setTarget(std::move(target))) {
      // The previous map is gone with it: no map until the next one, and a re-publication of
      // this one is tried again rather than skipped as unchanged.
      {
        std::lock_guard<std::mutex> lock(mutex_);
        front_ = -1;
      }
      slot.fingerprint = 0;
      slot.subset.reset();
      log_.problem("dense index",
                   "dense cloud " + describeCloud(*cloud, topic_) +
                       " could not be indexed; no map until the next one",
                   true);
      return;
    }
    const std::shared_ptr<const TargetIndex> index = slot.registration.target();
    to_fold_ = index;
    if (index && previous && index->extends(*previous)) {
      how = "extended";
      appended = index->size() - previous->size();
    } else if (index) {
      how = "indexed";
    } else {
      how = "stored; a large map is cropped by the next alignment";
    }
  } else {
    slot.points = std::move(converted.points);
    slot.map_points = slot.points.size();
  }
  slot.frame = cloud->header.frame_id;
  slot.fingerprint = fingerprint;
  const auto end = std::chrono::steady_clock::now();
  const double ms = std::chrono::duration<double, std::milli>(end - start).count();
  const double index_ms = std::chrono::duration<double, std::milli>(end - index_start).count();
  const double index_cpu_ms = threadCpuMs() - index_cpu_start;
  const ros::WallTime now = ros::WallTime::now();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    slot.ready = now;
    front_ = back;
  }
  changed_.notify_all();
  const size_t points = slot.map_points;
  const double subset_voxel =
      slot.subset && slot.subset->thinned() ? slot.subset->voxelSize() : 0.0;
  status_->update([&](AlignmentStatusValues& s) {
    s.dense_points = points;
    s.sparse_spacing = sparse_spacing;
    s.dense_subset_voxel = subset_voxel;
    s.dense_arrival = now;
    s.index_ready = now;
    s.index_update_ms = index_ms;
    s.index_update_cpu_ms = index_cpu_ms;
    s.index_update = how;
    ++s.index_updates;
  });
  char subset[120] = "";
  if (subset_voxel > 0.0) {
    std::snprintf(subset, sizeof(subset), "; indexed: a subset of %zu points at %.1f cm",
                  slot.subset->points().size(), 100.0 * subset_voxel);
  }
  char line[500];
  std::snprintf(line, sizeof(line),
                "dense map from %s: %zu points (%zu non-finite dropped)%s, ready in %.0f ms "
                "(converted in %.0f ms, %s in %.0f ms, %.0f ms CPU%s)",
                topic_.c_str(), points, converted.non_finite, subset, ms, convert_ms, how,
                index_ms, index_cpu_ms,
                appended > 0 ? (", " + std::to_string(appended) + " points appended").c_str() : "");
  log_.info(line);
}

}  // namespace pda_registration

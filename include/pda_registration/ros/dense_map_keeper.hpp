#pragma once
// Index keeping, beside the alignments (double-buffered). Each dense map message is converted and
// indexed on the keeper's own thread into the back one of two slots, which then becomes the
// front; an alignment borrows the front slot, so it never waits for an index build (only the
// very first alignment waits for the first map). Each slot keeps its own PdaRegistration, so a
// map that grows by appended points (a SLAM map re-published whole) only extends the slot's index
// (TargetMap::setCloud), and a map re-published unchanged (same 64-bit fingerprint of frame,
// layout and bytes) is skipped. As the registration source (target_cloud: sparse) a map is only
// converted.
//
// A dense map much finer than the sparse clouds is indexed as its representative subset at the
// sparse clouds' sample spacing (core/representative_subset.hpp), which the alignment job
// measures and reports (noteSparseSpacing); the latest map is kept so that it can be indexed
// again when that spacing first becomes known or changes.
//
// An extended index is several kd-trees and every query descends each; after each update the
// keeper folds the front index's trees into one (TargetIndex::fold, same answers, faster
// queries). Of two trees the fold gives way to a new map; of more, the new map waits for it.

#include <sensor_msgs/PointCloud2.h>

#include <atomic>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/representative_subset.hpp"
#include "pda_registration/ros/alignment_status.hpp"
#include "pda_registration/ros/live_parameters.hpp"
#include "pda_registration/ros/latest_input_queue.hpp"

namespace pda_registration {

/// How the nodelet's parts report: a problem (WARN, throttled per kind, and the diagnostics) and
/// an INFO line.
struct NodeletLog {
  std::function<void(const std::string& kind, const std::string& problem, bool input_error)>
      problem;
  std::function<void(const std::string& line)> info;
};

/// One buffer: a dense map ready to align against.
struct DenseMapSlot {
  PdaRegistration registration;  // the indexed map as target (dense map = target)
  PointList points;              // the map (dense map = source)
  std::string frame;
  uint64_t fingerprint = 0;
  size_t map_points = 0;
  ros::WallTime ready;  // when it became the front
  // The subset indexed instead of the map (dense map = target), for the spacing below.
  std::unique_ptr<RepresentativeSubset> subset;
  double sparse_spacing = 0.0;  // the sparse clouds' spacing it was made for (0: unknown)
};

class DenseMapKeeper {
 public:
  using ParameterSource = std::function<LiveParameters()>;
  DenseMapKeeper(bool dense_is_target, std::string expected_frame, std::string topic,
                 AlignmentStatus* status, NodeletLog log, ParameterSource parameters);
  ~DenseMapKeeper();  // stops the thread

  /// Stops the thread and wakes an alignment waiting for the first map (for shutdown).
  void stop();

  /// Queues a map for the keeper thread (a newer one replaces a pending one).
  void put(const sensor_msgs::PointCloud2ConstPtr& cloud);

  /// The sample spacing of the sparse clouds (core sampleSpacing). A change beyond a factor of
  /// sqrt(2) from the one in use (or the first one) has the latest map indexed again.
  void noteSparseSpacing(double spacing);
  /// The spacing in use (0: none known yet).
  double sparseSpacing() const { return sparse_spacing_.load(); }
  /// Indexes the latest map again (dense_subset was switched), unless a newer one waits.
  void reindexLatest();

  /// The front slot, borrowed until the Borrowed goes away; empty when there is no map. Waits
  /// (at most `first_map_timeout` s) only while the first map is being indexed.
  class Borrowed {
   public:
    Borrowed() = default;
    Borrowed(DenseMapKeeper* keeper, DenseMapSlot* slot) : keeper_(keeper), slot_(slot) {}
    Borrowed(Borrowed&& o) noexcept : keeper_(o.keeper_), slot_(o.slot_) { o.slot_ = nullptr; }
    Borrowed& operator=(Borrowed&&) = delete;
    ~Borrowed();
    DenseMapSlot* operator->() const { return slot_; }
    explicit operator bool() const { return slot_ != nullptr; }

   private:
    DenseMapKeeper* keeper_ = nullptr;
    DenseMapSlot* slot_ = nullptr;
  };
  Borrowed borrow(double first_map_timeout);

 private:
  void loop();
  void update(const sensor_msgs::PointCloud2ConstPtr& cloud);
  /// The front's map again, with a new sparse spacing: true (nothing to re-index) when the map
  /// stays whole, as the front has it.
  bool keptWhole(DenseMapSlot* front, const PointList& map, double sparse_spacing);
  /// Folds the trees of the index update() made last, unless a map arrives first.
  void foldLatest();
  void giveBack(DenseMapSlot* slot);

  const bool dense_is_target_;
  const std::string expected_frame_, topic_;
  AlignmentStatus* status_;
  NodeletLog log_;
  ParameterSource parameters_;

  LatestInputQueue<sensor_msgs::PointCloud2ConstPtr, int> queue_;  // dense side only
  std::mutex mutex_;  // guards front_, borrowed_, pending_first_
  std::condition_variable changed_;
  DenseMapSlot slots_[2];
  int front_ = -1;             // -1: no map yet
  int borrowed_[2] = {0, 0};   // alignments using each slot
  bool pending_first_ = false;  // a map is on its way and none is ready yet
  bool stopped_ = false;
  std::shared_ptr<const TargetIndex> to_fold_;  // keeper thread only
  std::atomic<double> sparse_spacing_{0.0};
  sensor_msgs::PointCloud2ConstPtr latest_;       // guarded by mutex_: indexed again on a change
  std::atomic<bool> fold_cancel_{false};          // a map arrived: stop folding
  std::thread thread_;
};

}  // namespace pda_registration

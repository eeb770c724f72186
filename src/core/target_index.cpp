#include "pda_registration/core/target_index.hpp"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace pda_registration {
namespace {

constexpr uint32_t kLeafSize = 16;
// A build checks for cancellation at the nodes of these top levels (up to 2^10 checks).
constexpr int kCancelCheckDepth = 10;

struct Cancelled {};

uint64_t newLineage() {
  static std::atomic<uint64_t> next{1};
  return next++;
}

double squaredDistance(const Point& a, const Point& b) {
  const double dx = a.x() - b.x(), dy = a.y() - b.y(), dz = a.z() - b.z();
  return dx * dx + dy * dy + dz * dz;
}

// The k best (squared distance, index) pairs strictly within the radius, in lexicographic order:
// the same set whatever order the points are offered in.
class NearestWithinRadius {
 public:
  NearestWithinRadius(size_t capacity, double squared_radius, size_t* indices, double* distances)
      : indices_(indices),
        distances_(distances),
        capacity_(capacity),
        squared_radius_(squared_radius) {}

  size_t size() const { return count_; }
  // Subtrees farther than this cannot hold a better point (equal distances may: they are visited).
  double bound() const { return count_ == capacity_ ? distances_[capacity_ - 1] : squared_radius_; }

  void offer(double distance, size_t index) {
    if (count_ == capacity_) {
      const double worst = distances_[capacity_ - 1];
      if (distance > worst || (distance == worst && index >= indices_[capacity_ - 1])) return;
    } else if (!(distance < squared_radius_)) {
      return;
    }
    // The insertion point; a point already held (offered as a hint, then met in the tree) is
    // exactly equal to the entry before it.
    size_t at = count_ < capacity_ ? count_ : capacity_ - 1;
    while (at > 0 && (distances_[at - 1] > distance ||
                      (distances_[at - 1] == distance && indices_[at - 1] > index))) {
      --at;
    }
    if (at > 0 && distances_[at - 1] == distance && indices_[at - 1] == index) return;
    size_t i = count_ < capacity_ ? count_ : capacity_ - 1;
    for (; i > at; --i) {
      distances_[i] = distances_[i - 1];
      indices_[i] = indices_[i - 1];
    }
    distances_[i] = distance;
    indices_[i] = index;
    if (count_ < capacity_) ++count_;
  }

 private:
  size_t* indices_;
  double* distances_;
  size_t capacity_;
  size_t count_ = 0;
  double squared_radius_;
};

}  // namespace

// A kd-tree over points [begin, end) of the index's point list (which it reads at query time, so
// the same tree serves every index that shares those points). Median splits on the axis of
// largest spread; each inner node keeps the largest coordinate of its left half and the smallest
// of its right half on that axis, for the incremental distance bound of the search.
struct TargetIndex::Tree {
  struct Node {
    uint32_t first, last;  // leaf: range in order; inner: children in nodes
    int axis = -1;         // -1: leaf
    double low = 0.0, high = 0.0;
  };
  size_t begin = 0, end = 0;
  std::vector<uint32_t> order;  // point indices, leaves' points contiguous
  std::vector<Node> nodes;
  Point box_min = Point::Zero(), box_max = Point::Zero();

  // Built on a contiguous copy of the points with their indices (the partitioning moves them
  // in memory order, not through the index), then only the indices are kept.
  struct Entry {
    Point p;
    uint32_t index;
  };

  Tree(const PointList& points, size_t first, size_t last,
       const std::atomic<bool>* cancel = nullptr)
      : begin(first), end(last), cancel_(cancel) {
    if (last > std::numeric_limits<uint32_t>::max()) throw std::length_error("target too large");
    std::vector<Entry> entries(last - first);
    for (size_t i = 0; i < entries.size(); ++i) {
      entries[i].p = points[first + i];
      entries[i].index = static_cast<uint32_t>(first + i);
    }
    nodes.reserve(2 * entries.size() / kLeafSize + 2);
    build(&entries, 0, static_cast<uint32_t>(entries.size()), 0, &box_min, &box_max);
    cancel_ = nullptr;
    order.resize(entries.size());
    for (size_t i = 0; i < entries.size(); ++i) order[i] = entries[i].index;
  }

  uint32_t build(std::vector<Entry>* entries, uint32_t lo, uint32_t hi, int depth, Point* mn,
                 Point* mx) {
    if (cancel_ && depth < kCancelCheckDepth && cancel_->load(std::memory_order_relaxed)) {
      throw Cancelled();
    }
    std::vector<Entry>& e = *entries;
    Point bmin = Point::Constant(std::numeric_limits<double>::infinity());
    Point bmax = -bmin;
    for (uint32_t i = lo; i < hi; ++i) {
      bmin = bmin.cwiseMin(e[i].p);
      bmax = bmax.cwiseMax(e[i].p);
    }
    *mn = bmin;
    *mx = bmax;
    const uint32_t id = static_cast<uint32_t>(nodes.size());
    nodes.emplace_back();
    int axis;
    const double spread = (bmax - bmin).maxCoeff(&axis);
    if (hi - lo <= kLeafSize || !(spread > 0.0)) {
      nodes[id].first = lo;
      nodes[id].last = hi;
      return id;
    }
    // Split at the middle of the box (one pass); a split leaving less than a quarter on one
    // side falls back to the median, so the depth stays logarithmic.
    const double middle = 0.5 * (bmin[axis] + bmax[axis]);
    uint32_t mid = static_cast<uint32_t>(
        std::partition(e.begin() + lo, e.begin() + hi,
                       [axis, middle](const Entry& a) { return a.p[axis] < middle; }) -
        e.begin());
    const uint32_t quarter = (hi - lo) / 4;
    if (mid < lo + quarter || mid > hi - quarter) {
      mid = lo + (hi - lo) / 2;
      std::nth_element(e.begin() + lo, e.begin() + mid, e.begin() + hi,
                       [axis](const Entry& a, const Entry& b) { return a.p[axis] < b.p[axis]; });
    }
    Point lmin, lmax, rmin, rmax;
    const uint32_t left = build(entries, lo, mid, depth + 1, &lmin, &lmax);
    const uint32_t right = build(entries, mid, hi, depth + 1, &rmin, &rmax);
    Node& node = nodes[id];
    node.first = left;
    node.last = right;
    node.axis = axis;
    node.low = lmax[axis];
    node.high = rmin[axis];
    return id;
  }

  void search(const PointList& points, const Point& q, NearestWithinRadius* result) const {
    double dists[3];
    double mindist = 0.0;
    for (int d = 0; d < 3; ++d) {
      dists[d] = 0.0;
      if (q[d] < box_min[d]) dists[d] = (box_min[d] - q[d]) * (box_min[d] - q[d]);
      if (q[d] > box_max[d]) dists[d] = (q[d] - box_max[d]) * (q[d] - box_max[d]);
      mindist += dists[d];
    }
    if (mindist <= result->bound()) searchNode(points, 0, q, mindist, dists, result);
  }

  void searchNode(const PointList& points, uint32_t id, const Point& q, double mindist,
                  double* dists, NearestWithinRadius* result) const {
    const Node& node = nodes[id];
    if (node.axis < 0) {
      // The query and the bound in locals: only offer() changes the bound, and the compiler
      // cannot tell that the result's stores leave the query alone (it reloaded both per point).
      const Point query = q;
      double bound = result->bound();
      for (uint32_t i = node.first; i < node.last; ++i) {
        const uint32_t index = order[i];
        const double d = squaredDistance(query, points[index]);
        if (d <= bound) {
          result->offer(d, index);
          bound = result->bound();
        }
      }
      return;
    }
    const int axis = node.axis;
    const double diff_low = q[axis] - node.low, diff_high = q[axis] - node.high;
    uint32_t near, far;
    double cut;
    if (diff_low + diff_high < 0.0) {
      near = node.first;
      far = node.last;
      cut = diff_high * diff_high;
    } else {
      near = node.last;
      far = node.first;
      cut = diff_low * diff_low;
    }
    searchNode(points, near, q, mindist, dists, result);
    const double saved = dists[axis];
    mindist = mindist + cut - saved;
    dists[axis] = cut;
    if (mindist <= result->bound()) searchNode(points, far, q, mindist, dists, result);
    dists[axis] = saved;
  }

 private:
  const std::atomic<bool>* cancel_ = nullptr;  // only while building
};

TargetIndex::TargetIndex(PointList points)
    : points_(std::move(points)), lineage_(newLineage()), last_indexed_(points_.size()) {
  if (!points_.empty()) trees_.push_back(std::make_shared<const Tree>(points_, 0, points_.size()));
}

TargetIndex::~TargetIndex() = default;

bool TargetIndex::sharesPrefix(const PointList& points) const {
  if (points.size() < points_.size()) return false;
  // Bitwise: the same bytes (an exact copy) is what sharing means here.
  return points_.empty() ||
         std::memcmp(points.data(), points_.data(), points_.size() * sizeof(Point)) == 0;
}

std::shared_ptr<const TargetIndex> TargetIndex::extended(
    const std::shared_ptr<const TargetIndex>& previous, PointList points) {
  std::shared_ptr<TargetIndex> index(new TargetIndex());
  index->points_ = std::move(points);
  const bool reuse = previous && previous->size() <= index->points_.size();
  if (reuse) {
    // From the fold's one tree when there is one (it is published after folded_tree_ is set).
    if (previous->folded_.load(std::memory_order_acquire)) {
      std::lock_guard<std::mutex> lock(previous->fold_mutex_);
      index->trees_ = {previous->folded_tree_};
    } else {
      index->trees_ = previous->trees_;
    }
  }
  index->lineage_ = reuse ? previous->lineage_ : newLineage();
  const size_t start = reuse ? previous->size() : 0;
  index->last_indexed_ = index->points_.size() - start;
  if (start < index->points_.size()) {
    index->trees_.push_back(
        std::make_shared<const Tree>(index->points_, start, index->points_.size()));
  }
  // Binary-counter merging: a tree as large as the one before it is merged with it (one tree
  // over both ranges), so sizes strictly grow towards the front: O(log n) trees, each point
  // re-indexed O(log n) times over the map's growth, and the first tree rebuilt only when the
  // points after it outnumber it (the map doubled).
  auto& trees = index->trees_;
  while (trees.size() >= 2) {
    const Tree& last = *trees[trees.size() - 1];
    const Tree& before = *trees[trees.size() - 2];
    if (last.end - last.begin < before.end - before.begin) break;
    index->last_indexed_ += before.end - before.begin;  // its points are indexed again
    auto merged = std::make_shared<const Tree>(index->points_, before.begin, last.end);
    trees.pop_back();
    trees.back() = std::move(merged);
  }
  return index;
}

bool TargetIndex::fold(const std::atomic<bool>* cancel) const {
  std::lock_guard<std::mutex> lock(fold_mutex_);
  if (trees_.size() <= 1 || folded_tree_) return false;
  try {
    auto tree = std::make_shared<const Tree>(points_, 0, points_.size(), cancel);
    folded_tree_ = std::move(tree);
  } catch (const Cancelled&) {
    return false;
  }
  folded_.store(folded_tree_.get(), std::memory_order_release);
  return true;
}

size_t TargetIndex::nearestWithinRadius(const Point& query, int k, double radius, size_t* indices,
                                        double* squared_distances, const size_t* hints,
                                        size_t n_hints) const {
  if (points_.empty() || k <= 0 || !(radius > 0.0)) return 0;
  NearestWithinRadius result(static_cast<size_t>(k), radius * radius, indices, squared_distances);
  for (size_t h = 0; h < n_hints; ++h) {
    if (hints[h] < points_.size())
      result.offer(squaredDistance(query, points_[hints[h]]), hints[h]);
  }
  if (const Tree* folded = folded_.load(std::memory_order_acquire)) {
    folded->search(points_, query, &result);
  } else {
    for (const auto& tree : trees_) tree->search(points_, query, &result);
  }
  return result.size();
}

}  // namespace pda_registration

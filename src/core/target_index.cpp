#include "pda_registration/core/target_index.hpp"

#include <limits>
#include <nanoflann.hpp>

namespace pda_registration {
namespace {

// nanoflann reads points through this adaptor, so the tree stores indices only.
struct PointListAdaptor {
  const PointList* points;
  size_t kdtree_get_point_count() const { return points->size(); }
  double kdtree_get_pt(size_t index, size_t dim) const { return (*points)[index][dim]; }
  template <class BoundingBox>
  bool kdtree_get_bbox(BoundingBox&) const {
    return false;
  }
};

// A k-NN result set that starts with the radius as its worst distance, so the tree prunes
// everything beyond the radius from the first node on (a k-NN search followed by a radius
// filter would visit far more nodes when few points are in range).
class NearestWithinRadius {
 public:
  using DistanceType = double;
  using IndexType = size_t;
  using CountType = size_t;

  NearestWithinRadius(size_t capacity, double squared_radius, size_t* indices, double* distances)
      : indices_(indices),
        distances_(distances),
        capacity_(capacity),
        squared_radius_(squared_radius) {}

  size_t size() const { return count_; }
  bool full() const { return count_ == capacity_; }
  double worstDist() const { return full() ? distances_[capacity_ - 1] : squared_radius_; }

  bool addPoint(double distance, size_t index) {
    if (distance >= worstDist()) return true;
    // Insertion sort into the kept prefix: k is small (<= a few dozen).
    size_t i = count_ < capacity_ ? count_ : capacity_ - 1;
    for (; i > 0 && distances_[i - 1] > distance; --i) {
      distances_[i] = distances_[i - 1];
      indices_[i] = indices_[i - 1];
    }
    distances_[i] = distance;
    indices_[i] = index;
    if (count_ < capacity_) ++count_;
    return true;
  }

 private:
  size_t* indices_;
  double* distances_;
  size_t capacity_;
  size_t count_ = 0;
  double squared_radius_;
};

}  // namespace

struct TargetIndex::KdTree {
  using Tree =
      nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointListAdaptor>,
                                          PointListAdaptor, 3, size_t>;
  explicit KdTree(const PointList* points)
      : adaptor{points}, tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(32)) {
    if (!points->empty()) tree.buildIndex();
  }
  PointListAdaptor adaptor;
  Tree tree;
};

TargetIndex::TargetIndex(PointList points)
    : points_(std::move(points)), tree_(std::make_unique<KdTree>(&points_)) {}

TargetIndex::~TargetIndex() = default;

size_t TargetIndex::nearestWithinRadius(const Point& query, int k, double radius, size_t* indices,
                                        double* squared_distances) const {
  if (points_.empty() || k <= 0 || !(radius > 0.0)) return 0;
  NearestWithinRadius result(static_cast<size_t>(k), radius * radius, indices, squared_distances);
  tree_->tree.findNeighbors(result, query.data(), nanoflann::SearchParams());
  return result.size();
}

}  // namespace pda_registration

#pragma once
// How far one estimate is from another, as the displacement it causes over the source: the
// centroid's displacement and the rotation times the source's RMS radius, one 6-vector. The
// runs' extrapolation and their rest test compare steps in it, so that a rotation and a
// translation weigh as what they do to the cloud.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

class PoseStep {
 public:
  using Vector = Eigen::Matrix<double, 6, 1>;

  PoseStep(const Point& centroid, double length) : centroid_(centroid), length_(length) {}
  /// Measured over this cloud's centroid and RMS radius (an empty cloud: the origin, 1).
  static PoseStep over(const PointList& cloud);

  /// (rotation angle x axis x length, displacement of the centroid) from `before` to `after`.
  Vector between(const Eigen::Isometry3d& before, const Eigen::Isometry3d& after) const;

  const Point& centroid() const { return centroid_; }

 private:
  Point centroid_;
  double length_;
};

/// How a step follows the one before (both non-zero, in one PoseStep metric): the cosine between
/// them and the ratio of their lengths. Runs near a rest converge linearly: successive steps
/// point the same way and shrink (the extrapolation and the tail read them so).
struct StepSuccession {
  /// Steps at least this close in direction (cosine) are taken as one linear sequence.
  static constexpr double kSameDirection = 0.9;
  double cosine = 0.0;
  double ratio = 0.0;  ///< |step| / |previous|
  bool sameDirection() const { return cosine >= kSameDirection; }
};
StepSuccession succession(const PoseStep::Vector& previous, const PoseStep::Vector& step);

}  // namespace pda_registration

#include "pda_registration/simulation/drift_distortion.hpp"

namespace pda_registration {
namespace simulation {

Point DriftDistortion::apply(const Point& point) const {
  const Eigen::Vector2d offset = point.head<2>() - centre;
  const double rho = offset.norm();
  const double growth = amount * rho / reference_radius;
  Point warped;
  warped.head<2>() = centre + (1.0 + growth) * offset;
  warped.z() = point.z() + growth * rho;
  return warped;
}

void applyDistortion(const DriftDistortion& distortion, PointList* points) {
  if (distortion.amount == 0.0) return;
  for (Point& point : *points) point = distortion.apply(point);
}

}  // namespace simulation
}  // namespace pda_registration

#pragma once
// Photogrammetry-like drift of a dense map: a smooth non-rigid warp that is zero at `centre` and
// grows with the horizontal distance rho from it,
//   scale: p_xy' = c + (1 + amount * rho / R) (p_xy - c)
//   bend:  z'    = z + amount * rho^2 / R
// with R = reference_radius (5 m). `amount` is the relative scale error at R, where a point
// moves amount * R outwards and amount * R up (amount 0.01: 5 cm and 5 cm at 5 m).

#include <Eigen/Core>

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {
namespace simulation {

struct DriftDistortion {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  ///< [m] horizontal centre of the warp
  double amount = 0.0;                               ///< relative scale error at reference_radius
  double reference_radius = 5.0;                     ///< [m]

  Point apply(const Point& point) const;
};

/// Warps every point in place; amount 0 leaves them untouched.
void applyDistortion(const DriftDistortion& distortion, PointList* points);

}  // namespace simulation
}  // namespace pda_registration

#pragma once
// A second start for a result that rests on a false minimum after a large correction. From 20 deg
// and 1 m off, the approach corrects rotation and translation together, and on a map with a
// repeated structure (an office walkway lined with desks) the source can slide along it while it
// turns and come to rest turned right but one repeat off. Such a rest fits half the points and not
// the other half: the Student-t's nu, estimated by EM, ends at its floor (all 20 converged
// failures of simulated RGB-D fragment pairs from 20 deg; their correct results ended at 1.5-3.2).
// Started again from the rotation it found, with the source's centroid where the seed put it, the
// same alignment reaches the right pose, and the better-supported of the two results is kept.

#include <Eigen/Geometry>

#include "pda_registration/core/point_list.hpp"
#include "pda_registration/core/registration_parameters.hpp"
#include "pda_registration/core/registration_result.hpp"

namespace pda_registration {

/// Where a second start would begin: the rotation `first` found, with `centroid` (of the source
/// points, source frame) where T_initial put it.
Eigen::Isometry3d secondStartPose(const Eigen::Isometry3d& T_found,
                                  const Eigen::Isometry3d& T_initial, const Point& centroid);

/// Whether `first`, converged from T_initial, warrants a second start: nu (estimated) ended at its
/// floor, and the first alignment moved the centroid further than its final candidate radius, so
/// that the second start is another hypothesis and not the basin the first one already searched.
bool secondStartWarranted(const RegistrationResult& first, const RegistrationParameters& p,
                          const Eigen::Isometry3d& T_initial, const Point& centroid,
                          double final_radius);

/// The first result's neighbourhood: where the source points lie, in root mean square, within
/// the first alignment's final candidate radius of where the first result put them. A second
/// start that enters it is in the basin the first one already searched (its last runs searched
/// that far around it), and is abandoned: the same rest, found again, is not worth a second settle
/// and refine. In root mean square, not for every point: a lidar scan's farthest return is 100 m
/// out where its points' RMS distance is 27 m, and a bound on the farthest point kept a second
/// start of a right VLP-16 result running for 11 more runs at 0.2-0.5 deg from it.
struct FirstResultBasin {
  Eigen::Isometry3d T_found = Eigen::Isometry3d::Identity();
  Point centroid = Point::Zero();  ///< of the source points (source frame)
  double source_rms_radius = 0.0;  ///< the RMS distance of the source points from the centroid
  double final_radius = 0.0;

  /// The source points' RMS displacement between T_found and T is below final_radius (bounded by
  /// the centroid's shift and the angle between them times source_rms_radius, in quadrature).
  bool contains(const Eigen::Isometry3d& T) const;
};

/// Whether the second start's result replaces the first's: converged, and a larger share of the
/// overlap fits it (the false rest's support was 0.44-0.54 where the right pose's was 0.63).
bool secondStartIsBetter(const RegistrationResult& first, const RegistrationResult& second);

}  // namespace pda_registration

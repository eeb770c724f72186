#pragma once
// The per-alignment source budget: a source of more than `max_points` points is thinned to
// `max_points` of them, so alignment time stays bounded however large the sparse map grows. Two
// ways (RegistrationParameters::spread_source_budget):
//
// - randomSubsample (the default): every finite point equally likely (input order kept, fixed
//   seed), so the objective stays the whole cloud's in expectation.
// - spatialSubsample: spread over the space the source covers. On the grid where about
//   `max_points` voxels are occupied every voxel keeps its points up to a common level, so the
//   densest voxels are thinned first. A lidar's points crowd with 1 / range^2 around the sensor,
//   and neighbouring residuals share their errors (the covariance's correlogram reads them
//   correlated over 0.3 m to metres), so a crowd of points on one car says little more than a
//   few: when the cars near the sensors were re-parked between the maps (a car park on another
//   day, pda_simulate --scene-changes), with every point weighed alike a few that moved alike
//   outvoted the poles, trees and buildings that did not, 28.8 cm off along the road on every
//   trial; spread over space, 1.2-1.3 mm. It is not the default because it costs elsewhere: the
//   sparse parts it favours are also where a sensor is noisiest or its map sampled most
//   coarsely (RGB-D fragments 1.5 -> 3.3 mm, two VLP-16 revolutions 20 m apart 1.2 -> 1.4 cm;
//   docs/algorithm.md, "The source budget").

#include <cstddef>

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

struct RegistrationParameters;  // registration_parameters.hpp: only referred to here

/// An unbiased subsample of `max_points` points (every finite point equally likely, input order
/// kept, fixed seed), or an empty list when `points` has no more than `max_points` points (use
/// the input as it is: no copy). Non-finite points are skipped. Also the approach stage's share
/// of a source.
PointList randomSubsample(const PointList& points, size_t max_points);

/// The same, for a caller that has counted the finite points already (countFinitePoints): a
/// 2M-point map is not read once more to count them again.
PointList randomSubsample(const PointList& points, size_t max_points, size_t finite_points);

/// `max_points` points spread over the space `points` covers (its densest voxels thinned first;
/// fixed seed, input order kept), or an empty list as randomSubsample. A NaN changes nothing but
/// itself: the same subsample as of the cloud without it.
PointList spatialSubsample(const PointList& points, size_t max_points);
PointList spatialSubsample(const PointList& points, size_t max_points, size_t finite_points);

/// The source as the runs align it, written to `source` (whose memory is reused): `input`'s
/// finite points (`finite_points` of them, counted by the caller), voxelised at
/// `source_voxel_size` when that is set, then at most `max_source_points` of them, subsampled as
/// `spread_source_budget` says. Returns whether the budget cut it.
bool prepareAlignedSource(const PointList& input, size_t finite_points,
                          const RegistrationParameters& parameters, PointList* source);

}  // namespace pda_registration

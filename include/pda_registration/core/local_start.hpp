#pragma once
// A local start: the alignment once more from the seed, with the outlier class (outlier_class.hpp)
// in every run, kept if it converges near the seed. Two RGB-D fragments that share a third of
// their scene fail the usual way from a seed 2-10 deg off: the two thirds of the source with no
// counterpart still find candidates within the 1-m radius (indoors no wall is a metre away), hold
// sigma at 0.14-0.18 m and pull the source along the walkway, either until the work bound ("not
// converged") or onto a rest one desk repeat along it, 2.7 m off, that fits the overlap as well as
// the truth does (converged, support 0.53 against the truth's 0.52) and, summed over the source,
// better: no score at the two rests tells them apart; only the seed's locality does. The outlier
// class gives the unshared points no say, and from a seed that close sigma falls to the noise
// (6 mm) within a few runs and stays at the truth (docs/benchmark.md, "RGB-D fragments that share
// less").
//
// Its reach is short: a true counterpart further than a few sigma looks like no counterpart, so
// from far off it converges, as readily, to a nearby false fit. Hence it runs only after a usual
// alignment that failed or that slid away from the seed: converged more than the search radius (in
// RMS over the source) from it, on a rest where nu, estimated, ended at its floor (half the points
// fit, half do not: second_start.hpp). It runs before the other direction and the wider search
// (which then still run where the first warranted them, see below), and its result is
// kept only if it moved the source, in root mean square, less than the search radius from the
// seed: a correction the candidates around the seed could see (and it stops as soon as it moves
// further: from 20 deg a lidar scan pair's local start wandered 2-7 m off for 12-58 runs, doubling
// the time of the right answer the first alignment had found). From 20 deg it found false fits
// 1.5-6.6 m away on the simulated office, a VLP-16 lattice and 1-cm fragments, which the bound
// rejects (the other direction or the wider search then found the truth, as before). A seed that
// far off leaves false fits within the bound too (an office with its chairs moved: 2.16 m off,
// support 0.11; the reversed room: 1.7 m off), so a local start kept after a first alignment
// that warranted the other direction or the wider search still meets their answers, and the one
// that fits more of the overlap at one yardstick stays (pda_registration.cpp).

#include <Eigen/Geometry>

#include "pda_registration/core/point_list.hpp"
#include "pda_registration/core/registration_parameters.hpp"
#include "pda_registration/core/registration_result.hpp"

namespace pda_registration {

/// Whether `first` warrants a local start, in the multi-run mode with sigma estimated: it did not
/// converge, for any reason but time; or it converged with nu (estimated) at its floor after
/// moving the source `moved_from_seed` (RMS, rmsDisplacement) at least the search radius.
bool localStartWarranted(const RegistrationResult& first, const RegistrationParameters& p,
                         double moved_from_seed);

/// The root-mean-square displacement of `source`'s points between T_a and T_b.
double rmsDisplacement(const PointList& source, const Eigen::Isometry3d& T_a,
                       const Eigen::Isometry3d& T_b);

/// Whether a local start at T is still near the seed: the source (as aligned) moved from it less
/// than the radius in root mean square. One that leaves stops; one that converges near it is kept.
bool localStartStaysNear(const PointList& source, const Eigen::Isometry3d& T,
                         const Eigen::Isometry3d& T_initial, const RegistrationParameters& p);

}  // namespace pda_registration

#include "pda_registration/core/competing_shift.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

namespace pda_registration {
namespace {

// At most this many probe points, taken at a fixed stride: a count of 100 errs by about 10, and
// the probe costs at most 128 x 49 searches.
constexpr size_t kMaxProbePoints = 128;
// At most this many shifts on either side; otherwise the step is half the inlier distance, so
// that a surface's window of fitting shifts (at least twice the inlier distance wide) holds at
// least four of them (two at the coarsest step, on a car park whose sigma is 1.3 cm).
constexpr int kMaxStepsPerSide = 24;
// Surfaces that face the probed direction: their residual changes at least half as fast as the
// shift (cos 60 deg).
constexpr double kMinFacing = 0.5;
// Fewer probe points than this leave the direction to the covariance alone.
constexpr size_t kMinProbePoints = 32;

// The most prominent peak beyond the estimate's on one side (`side` runs outward from the
// estimate, `own` the estimate's peak count), which ends at the first count below half of it: at
// each shift beyond, its rise above its key col and the estimate's own rise above that same col
// (prominence, not height: see the header). The col is the higher of the peak's two dips: the
// deepest count between it and the estimate (the saddle), and the deepest beyond it up to the
// next higher count or the probe's end (unless that stands as high as the estimate's own peak).
// A count that only climbs to the end of the reach, or a plateau of clutter that fits at every
// shift, has no dip beyond it and is no peak: on RGB-D fragments that share a third of the scene
// the probe's counts rose from 15 beside the estimate's 73 to 53 at 0.92 m, and against the
// saddle alone that read as a second pose (sigma 0.58 m against a 7-mm error).
struct SidePeak {
  double rise = 0.0;      ///< above the col
  double own_rise = 0.0;  ///< the estimate's, above the same col
  size_t step = 0;
  double relative() const { return own_rise > 0.0 ? rise / own_rise : 0.0; }
};
SidePeak mostProminentBeyond(const std::vector<size_t>& side, size_t own) {
  SidePeak best;
  size_t saddle = side[0];
  bool left_own_peak = false;
  for (size_t k = 1; k < side.size(); ++k) {
    saddle = std::min(saddle, side[k]);
    // Within the estimate's own peak a shallow dip and its rise are the count's noise.
    left_own_peak = left_own_peak || 2 * side[k] < own;
    if (!left_own_peak) continue;
    size_t beyond = side[k];
    for (size_t m = k + 1; m < side.size() && side[m] <= side[k]; ++m) {
      beyond = std::min(beyond, side[m]);
    }
    // Where even the dip beyond stands as high as the estimate's peak, the shifts out there fit
    // better throughout and the estimate is no peak above them: the dip between the two decides.
    const size_t higher_col = std::max(saddle, beyond);
    const size_t col = higher_col < own ? higher_col : saddle;
    const SidePeak here{static_cast<double>(side[k] - col),
                        static_cast<double>(own) - static_cast<double>(col), k};
    if (here.relative() > best.relative()) best = here;
  }
  return best;
}

// The estimate's own peak count: the largest while the counts stay at or above half of it, on
// both sides of the estimate (the estimate may sit a step off its peak).
size_t ownPeak(const std::vector<size_t>& ahead, const std::vector<size_t>& behind) {
  size_t peak = ahead[0];
  for (const std::vector<size_t>* side : {&ahead, &behind}) {
    for (size_t k = 1; k < side->size() && 2 * (*side)[k] >= peak; ++k) {
      peak = std::max(peak, (*side)[k]);
    }
  }
  return peak;
}

}  // namespace

CompetingShift findCompetingShift(const PointList& source, const PointList& normals,
                                  const Eigen::Isometry3d& T, const TargetIndex& index,
                                  const Eigen::Matrix3d& translation_covariance,
                                  const CompetingShiftSettings& settings) {
  CompetingShift none;
  if (!(settings.inlier_distance > 0.0) || !(settings.reach > 0.0) ||
      !(settings.search_radius > 0.0) || normals.size() != source.size() ||
      !translation_covariance.allFinite()) {
    return none;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(translation_covariance);
  const Eigen::Vector3d u = eigen.eigenvectors().col(2);  // the largest eigenvalue's
  std::vector<size_t> facing;
  for (size_t j = 0; j < source.size(); ++j) {
    if (std::abs(normals[j].dot(u)) > kMinFacing) {
      facing.push_back(j);
    }
  }
  none.probe_points = facing.size();
  if (facing.size() < kMinProbePoints) return none;
  const size_t stride = (facing.size() + kMaxProbePoints - 1) / kMaxProbePoints;

  const double step = std::max(0.5 * settings.inlier_distance, settings.reach / kMaxStepsPerSide);
  const int steps = static_cast<int>(std::floor(settings.reach / step));
  // counts[0]: shifts 0, +step, +2 step, ...; counts[1]: 0, -step, -2 step, ...
  std::vector<size_t> counts[2] = {std::vector<size_t>(steps + 1, 0),
                                   std::vector<size_t>(steps + 1, 0)};
  for (size_t f = 0; f < facing.size(); f += stride) {
    const size_t j = facing[f];
    const Point moved = T * source[j];
    const Eigen::Vector3d& n = normals[j];
    for (int side = 0; side < 2; ++side) {
      size_t hint = 0, hints = 0;
      for (int k = side; k <= steps; ++k) {  // the estimate itself counted once, on side 0
        const Point query = moved + (side == 0 ? k : -k) * step * u;
        size_t nearest = 0;
        double squared_distance = 0.0;
        if (index.nearestWithinRadius(query, 1, settings.search_radius, &nearest,
                                      &squared_distance, &hint, hints) == 0) {
          continue;
        }
        hint = nearest, hints = 1;
        if (std::abs(n.dot(query - index.points()[nearest])) < settings.inlier_distance) {
          ++counts[side][k];
        }
      }
    }
  }
  counts[1][0] = counts[0][0];
  const size_t own = ownPeak(counts[0], counts[1]);
  const SidePeak forward = mostProminentBeyond(counts[0], own);
  const SidePeak backward = mostProminentBeyond(counts[1], own);
  const bool forward_wins = forward.relative() >= backward.relative();
  const SidePeak& best = forward_wins ? forward : backward;
  CompetingShift result = none;
  // A peak at least half as prominent as the estimate's above the dip between them.
  if (!(best.relative() >= 0.5)) return result;
  result.estimate_support = best.own_rise;
  result.competitor_support = best.rise;
  result.shift = (forward_wins ? 1.0 : -1.0) * static_cast<double>(best.step) * step * u;
  result.share = best.rise / (best.rise + best.own_rise);
  return result;
}

Eigen::Matrix<double, 6, 6> withCompetingShift(const Eigen::Matrix<double, 6, 6>& covariance,
                                               const CompetingShift& competitor) {
  Eigen::Matrix<double, 6, 6> widened = covariance;
  if (competitor.found()) {
    widened.topLeftCorner<3, 3>() +=
        competitor.share * competitor.shift * competitor.shift.transpose();
  }
  return widened;
}

}  // namespace pda_registration

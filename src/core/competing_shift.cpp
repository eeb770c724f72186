#include "pda_registration/core/competing_shift.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

namespace pda_registration {
namespace {

// A competitor at least this prominent, relative to the estimate's peak above the same col.
constexpr double kMinRelativeProminence = 0.5;
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

// How many probe points fit within the inlier distance at each shift along u: ahead[k] at
// +k step, behind[k] at -k step (ahead[0] = behind[0]: the estimate itself).
struct FitProfile {
  std::vector<size_t> ahead, behind;
};

struct FitCounter {
  const PointList& source;
  const PointList& normals;
  const Eigen::Isometry3d& T;
  const TargetIndex& index;
  Eigen::Vector3d u;
  const CompetingShiftSettings& settings;
  double step;
  int steps;

  // Adds the counts of the facing points f with f % stride == 0, but not those already counted
  // at `counted_stride` (0: none).
  void add(const std::vector<size_t>& facing, size_t stride, size_t counted_stride,
           FitProfile* profile) const {
    for (size_t f = 0; f < facing.size(); f += stride) {
      if (counted_stride != 0 && f % counted_stride == 0) continue;
      const size_t j = facing[f];
      const Point moved = T * source[j];
      for (int side = 0; side < 2; ++side) {
        std::vector<size_t>& counts = side == 0 ? profile->ahead : profile->behind;
        size_t hint = 0, hints = 0;
        for (int k = side; k <= steps; ++k) {  // the estimate itself counted once, ahead
          const Point query = moved + (side == 0 ? k : -k) * step * u;
          size_t nearest = 0;
          double squared_distance = 0.0;
          if (index.nearestWithinRadius(query, 1, settings.search_radius, &nearest,
                                        &squared_distance, &hint, hints) == 0) {
            continue;
          }
          hint = nearest, hints = 1;
          if (std::abs(normals[j].dot(query - index.points()[nearest])) <
              settings.inlier_distance) {
            ++counts[k];
          }
        }
      }
    }
    profile->behind[0] = profile->ahead[0];
  }
};

// The most prominent peak beyond the estimate's, on either side.
struct Competitor {
  SidePeak peak;
  bool forward = true;
  size_t own = 0;  ///< the estimate's peak count
  // Whether the counts leave rise >= threshold x own rise within two standard errors of either
  // answer. Each count is taken as Poisson (a difference of two counts has the sum of their
  // variances; the counts share points, so this errs on the side of counting again).
  bool undecided() const {
    if (!(peak.rise > 0.0)) return false;  // no peak beyond the estimate's
    const double col = static_cast<double>(own) - peak.own_rise;
    const double margin = peak.rise - kMinRelativeProminence * peak.own_rise;
    const double rise_variance = (col + peak.rise) + col;
    const double own_rise_variance = static_cast<double>(own) + col;
    const double variance = rise_variance + std::pow(kMinRelativeProminence, 2) * own_rise_variance;
    return margin * margin < 4.0 * variance;
  }
};

Competitor strongestCompetitor(const FitProfile& profile) {
  Competitor best;
  best.own = ownPeak(profile.ahead, profile.behind);
  const SidePeak forward = mostProminentBeyond(profile.ahead, best.own);
  const SidePeak backward = mostProminentBeyond(profile.behind, best.own);
  best.forward = forward.relative() >= backward.relative();
  best.peak = best.forward ? forward : backward;
  return best;
}

}  // namespace

CompetingShift findCompetingShift(const PointList& source, const PointList& normals,
                                  const Eigen::Isometry3d& T, const TargetIndex& index,
                                  const Eigen::Matrix3d& translation_covariance,
                                  const CompetingShiftSettings& settings) {
  CompetingShift none;
  if (!(settings.inlier_distance > 0.0) || !(settings.reach > 0.0) ||
      !(settings.search_radius > 0.0) || settings.first_count_points == 0 ||
      settings.recount_points == 0 || normals.size() != source.size() ||
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
  const double step = std::max(0.5 * settings.inlier_distance, settings.reach / kMaxStepsPerSide);
  const int steps = static_cast<int>(std::floor(settings.reach / step));
  const FitCounter counter{source, normals, T, index, u, settings, step, steps};
  // A power of two, so that each recount at half the stride adds the points between.
  size_t stride = 1;
  while (stride * settings.first_count_points < facing.size()) stride *= 2;
  FitProfile profile{std::vector<size_t>(steps + 1, 0), std::vector<size_t>(steps + 1, 0)};
  counter.add(facing, stride, 0, &profile);
  Competitor best = strongestCompetitor(profile);
  while (best.undecided() && stride > 1 &&
         (facing.size() + stride / 2 - 1) / (stride / 2) <= settings.recount_points) {
    counter.add(facing, stride / 2, stride, &profile);
    stride /= 2;
    best = strongestCompetitor(profile);
  }
  CompetingShift result = none;
  result.relative_prominence = best.peak.relative();
  result.peak_shift = (best.forward ? 1.0 : -1.0) * static_cast<double>(best.peak.step) * step * u;
  if (!(best.peak.relative() >= kMinRelativeProminence)) return result;
  result.shift = result.peak_shift;
  result.estimate_support = best.peak.own_rise;
  result.competitor_support = best.peak.rise;
  result.share = best.peak.rise / (best.peak.rise + best.peak.own_rise);
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

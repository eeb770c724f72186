#include "pda_registration/core/scan_line_scale.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "pda_registration/core/surface_normals.hpp"

namespace pda_registration {
namespace {

constexpr int kFewest = 8;  // a neighbourhood's spread is judged from this many points on
constexpr int kFirst = 16;  // asked for first (most two-dimensional neighbourhoods need no more)
constexpr int kMost = 64;   // and no further: beyond, the point counts as on a line

}  // namespace

double scanLineScale(const TargetIndex& index, size_t samples) {
  const PointList& points = index.points();
  if (points.size() < static_cast<size_t>(kFewest) || samples == 0) return 0.0;
  size_t neighbours[kMost];
  double squared[kMost];
  std::vector<double> scales;
  scales.reserve(std::min(samples, points.size()));
  const size_t step = std::max<size_t>(1, points.size() / samples);
  for (size_t i = 0; i < points.size(); i += step) {
    // Most neighbourhoods of a map sampled in two directions are two-dimensional within a few
    // neighbours: ask for kFewest first, then kFirst, and for kMost only when those were not
    // enough. The k nearest are a prefix of the k' > k nearest (ties by index), so the answer is
    // the same.
    size_t found = index.nearestWithinRadius(
        points[i], kFewest, std::numeric_limits<double>::infinity(), neighbours, squared);
    if (found < static_cast<size_t>(kFewest)) continue;
    double scale = -1.0;
    // Moments relative to the sample itself, which is its own nearest neighbour.
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
    size_t m = 0;
    for (bool widened = false;;) {
      for (; m < found && scale < 0.0; ++m) {
        const Eigen::Vector3d offset = points[neighbours[m]] - points[i];
        sum += offset;
        outer += offset * offset.transpose();
        const double count = static_cast<double>(m + 1);
        if (m + 1 < static_cast<size_t>(kFewest)) continue;
        const Eigen::Vector3d mean = sum / count;
        eigen.computeDirect(outer / count - mean * mean.transpose(), Eigen::EigenvaluesOnly);
        const Eigen::Vector3d& variances = eigen.eigenvalues();  // ascending
        if (variances(2) > 0.0 &&
            variances(1) >= SurfaceNormalMap::kTwoDimensionalSpread * variances(2)) {
          scale = std::sqrt(squared[m]);
        }
      }
      if (scale >= 0.0 || widened) break;
      const int wider = found == static_cast<size_t>(kFewest) ? kFirst : kMost;
      const size_t asked = found;
      found = index.nearestWithinRadius(points[i], wider, std::numeric_limits<double>::infinity(),
                                        neighbours, squared);
      if (found == asked) break;  // the map has no more points
      widened = wider == kMost;
    }
    if (scale < 0.0) scale = std::sqrt(squared[found - 1]);
    scales.push_back(scale);
  }
  if (scales.empty()) return 0.0;
  const auto middle = scales.begin() + static_cast<long>(scales.size() / 2);
  std::nth_element(scales.begin(), middle, scales.end());
  return *middle;
}

}  // namespace pda_registration

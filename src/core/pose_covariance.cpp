#include "pda_registration/core/pose_covariance.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "pda_registration/core/map_scale_spread.hpp"
#include "pda_registration/core/noise_model.hpp"
#include "pda_registration/core/pose_jacobian.hpp"
#include "pda_registration/core/positive_definite.hpp"
#include "pda_registration/core/voxel_cell.hpp"

namespace pda_registration {
namespace {

// The finest grid of the score correlogram: the overlap's diagonal / 128 (a few centimetres on a
// room, decimetres on a car park; diagonal / 256 gave the same covariances at twice the cost).
// Each coarser level doubles the cell edge, up to kCoarsestEdge x the overlap's radius, where a
// cell's neighbourhood (3 cells wide) spans 3/8 of the overlap's diagonal. One level more (half
// the radius, 3/4 of the diagonal) paired nearly every cell with every other: the scores sum to
// zero at the optimum, so that level read the far pairs' cancelling as correlation (simulated
// offices: median error / sigma 0.72 in translation with it, 0.92 without; eight unseen office
// scenes 0.74 / 0.96). What the map's parts disagree on as wholes is the jackknife's.
constexpr int kFinestDivisions = 128;
constexpr double kCoarsestEdge = 0.25;
// The halves of a cut disagree beyond the covariance when their disagreement, read as the
// covariance it implies, exceeds it by more than the 95 % point of chi-square with six degrees of
// freedom in its worst direction (the squared Mahalanobis length of the six-vector by which the
// halves disagree): a 1-in-20 chance per cut if the covariance were right. The 95 % point of one
// degree of freedom (3.84) fired on white noise in 35 of 40 draws of a room.
constexpr double kHalvesSignificance = 12.59;

// Scores summed per grid cell, the cells in key order. The grid hangs on the overlap's corner, so
// coordinates are never negative and never reach 2^21 (at most kFinestDivisions per axis): key
// order is the lexicographic order of (x, y, z), and no two cells share a key.
struct CellScore {
  uint64_t key = 0;
  VoxelCell cell;
  Vector6d score = Vector6d::Zero();
};
using CellScores = std::vector<CellScore>;

// The scores summed per cell (each score in `cells[i]`). Sorted rather than hashed: the
// neighbour sums below then walk the cells in order, without a lookup per neighbour.
CellScores sumPerCell(const std::vector<VoxelCell>& cells, const std::vector<Vector6d>& scores) {
  std::vector<std::pair<uint64_t, uint32_t>> order(cells.size());
  for (size_t i = 0; i < cells.size(); ++i) {
    order[i] = {voxelCellKey(cells[i]), static_cast<uint32_t>(i)};
  }
  std::sort(order.begin(), order.end());
  CellScores summed;
  for (const auto& [key, i] : order) {
    if (summed.empty() || summed.back().key != key)
      summed.push_back({key, cells[i], Vector6d::Zero()});
    summed.back().score += scores[i];
  }
  return summed;
}

// The same scores summed over cells twice as large along each axis.
CellScores coarsen(const CellScores& fine) {
  std::vector<VoxelCell> parents(fine.size());
  std::vector<Vector6d> scores(fine.size());
  for (size_t i = 0; i < fine.size(); ++i) {
    parents[i] = parentCell(fine[i].cell);
    scores[i] = fine[i].score;
  }
  return sumPerCell(parents, scores);
}

// sum g_i g_j^T over the pairs of points whose cells touch (the 27 cells around a cell, itself
// included): a spatial HAC's middle term with a box kernel about 1.5 cells wide. Summed per cell,
// so it costs one pass over the cells, not a pass over the pairs of points. The neighbours of a
// cell lie in 9 rows (dx, dy) of up to 3 consecutive keys (z - 1 .. z + 1); each row has a cursor
// that only moves forward, because the rows' first keys grow with the cell's key.
Matrix6d neighbourScoreSum(const CellScores& cells) {
  Matrix6d sum = Matrix6d::Zero();
  size_t cursors[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  for (const CellScore& entry : cells) {
    const VoxelCell& c = entry.cell;
    Vector6d nearby = Vector6d::Zero();
    size_t* cursor = cursors;
    for (int64_t dx = -1; dx <= 1; ++dx) {
      for (int64_t dy = -1; dy <= 1; ++dy, ++cursor) {
        const VoxelCell first{c.x + dx, c.y + dy, std::max<int64_t>(c.z - 1, 0)};
        if (first.x < 0 || first.y < 0) continue;
        const uint64_t from = voxelCellKey(first);
        const uint64_t to = voxelCellKey({first.x, first.y, c.z + 1});
        while (*cursor < cells.size() && cells[*cursor].key < from) ++*cursor;
        for (size_t i = *cursor; i < cells.size() && cells[i].key <= to; ++i) {
          nearby += cells[i].score;
        }
      }
    }
    sum.noalias() += entry.score * nearby.transpose();
  }
  return 0.5 * (sum + sum.transpose());
}

// A covariance at least as large as both a and b: a + the positive part of (b - a), taken with
// rotations scaled by `length` so that metres and radians weigh alike.
Matrix6d upperBound(const Matrix6d& a, const Matrix6d& b, double length) {
  Vector6d scale;
  scale << 1.0, 1.0, 1.0, length, length, length;
  const Matrix6d difference = scale.asDiagonal() * (b - a) * scale.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eigen(0.5 * (difference + difference.transpose()));
  const Matrix6d positive = eigen.eigenvectors() *
                            eigen.eigenvalues().cwiseMax(0.0).asDiagonal() *
                            eigen.eigenvectors().transpose();
  const Vector6d unscale = scale.cwiseInverse();
  return a + unscale.asDiagonal() * positive * unscale.asDiagonal();
}

// [v]x: the matrix of the cross product v x (.).
Eigen::Matrix3d crossMatrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

// From increments about `pivot` to the same increments about `origin` (both in the target frame):
// a rotation w about the pivot is that rotation about the origin plus a shift w x (origin - pivot).
Matrix6d pivotToOrigin(const Eigen::Vector3d& pivot, const Eigen::Vector3d& origin) {
  Matrix6d change = Matrix6d::Identity();
  change.topRightCorner<3, 3>() = crossMatrix(pivot - origin);
  return change;
}

}  // namespace

bool computePoseCovariance(const WeightedCorrespondences& correspondences,
                           const Eigen::Isometry3d& T_target_source, double sigma_squared,
                           double nu, Eigen::Matrix<double, 6, 6>* covariance,
                           PoseCovarianceTerms* terms) {
  covariance->setZero();
  if (terms) *terms = PoseCovarianceTerms();
  if (correspondences.size() < 3 || !(sigma_squared > 0.0)) return false;
  // The moved points and the overlap's box, on which the cell grid and the octants hang.
  PointList moved(correspondences.size());
  Eigen::AlignedBox3d overlap;
  for (size_t i = 0; i < correspondences.size(); ++i) {
    moved[i] = T_target_source * correspondences.source[i];
    overlap.extend(moved[i]);
  }
  const double finest_edge = overlap.diagonal().norm() / kFinestDivisions;
  const Eigen::Vector3d centre = overlap.center();
  // Every term is taken with rotations about the overlap's centre and expressed about the
  // source origin (the message's convention) only at the end. About a far origin (a map
  // accumulated over a long drive) rotation and translation mix, and the upper bounds below,
  // taken with rotations weighed by the overlap's radius, would change with where that origin
  // lies: the same alignment 1 km from it read 1.5x more cautious.

  // The Hessian of the EM objective and every point's score (the gradient of its term) at the
  // optimum, summed per finest cell and per octant.
  // hessian: the complete-data information (every association and t-weight taken as known);
  // observed: the information the data actually hold about the pose (below).
  Matrix6d hessian = Matrix6d::Zero(), robust_hessian = Matrix6d::Zero();
  Matrix6d observed = Matrix6d::Zero();
  const bool have_moments = correspondences.second_moment.size() == correspondences.size();
  const double t_factor = std::isfinite(nu) ? 1.0 + 2.0 / (nu + 3.0) : 1.0;
  std::vector<VoxelCell> point_cells;
  std::vector<Vector6d> point_scores;
  point_cells.reserve(finest_edge > 0.0 ? correspondences.size() : 0);
  point_scores.reserve(point_cells.capacity());
  OctantPartition octants;
  for (size_t i = 0; i < correspondences.size(); ++i) {
    const PoseJacobian jacobian = poseJacobian(moved[i] - centre);
    const Eigen::Matrix3d shape =
        shapeInverse(correspondences.normal[i], correspondences.inverse_kappa[i]);
    const Eigen::Vector3d residual = correspondences.target_mean[i] - moved[i];
    const double weight = correspondences.weight[i];
    const Matrix6d point_hessian = weight * jacobian.transpose() * shape * jacobian;
    const Vector6d pull = jacobian.transpose() * shape * residual;
    const Vector6d score = weight * pull;
    hessian.noalias() += point_hessian;
    robust_hessian.noalias() += point_hessian;
    // Observed information (Louis 1982): the complete-data information less what the unknown
    // association and t-weight leave open, the posterior covariance of the candidates' pulls
    // u_i M^-1 r_i: (1 + 2 / (nu + 3)) sum_i P(a_i) u_i^2 r_i r_i^T - W^2 r r^T (r to the
    // weighted mean), the first factor for the t-weight's own spread. Where the target's samples
    // are as far apart as the noise (a lidar map of the scan's own sensor, the same lattice), a
    // source point's posterior spreads over several of them and the pose is known far less
    // well than the complete-data matrix says (64-beam lattice: 3.0x its sigma, now 1.1x).
    if (have_moments) {
      const Eigen::Matrix3d missing = t_factor * correspondences.second_moment[i] -
                                      weight * weight * residual * residual.transpose();
      const Eigen::Matrix<double, 3, 6> shaped = shape * jacobian;
      observed.noalias() += point_hessian - shaped.transpose() * missing * shaped / sigma_squared;
    }
    // The t-weight's own derivative: d(w r)/dr = w (I - 2 w / (nu + 3) M^-1 r r^T / sigma^2).
    if (std::isfinite(nu)) {
      const double t_weight =
          (nu + 3.0) / (nu + shapedSquaredNorm(residual, correspondences.normal[i],
                                               correspondences.inverse_kappa[i]) /
                                 sigma_squared);
      robust_hessian.noalias() -=
          2.0 * weight * t_weight / ((nu + 3.0) * sigma_squared) * pull * pull.transpose();
    }
    // The grid hangs on the overlap's corner: cells 0-128 per axis wherever the map lies.
    if (finest_edge > 0.0) {
      point_cells.push_back(voxelCellOf(moved[i] - overlap.min(), 1.0 / finest_edge));
      point_scores.push_back(score);
    }
    OctantSums& octant = octants[octantOf(moved[i], centre)];
    octant.hessian.noalias() += point_hessian;
    octant.score += score;
    ++octant.points;
  }
  Matrix6d hessian_inverse;
  if (!invertPositiveDefinite(hessian, &hessian_inverse)) return false;
  // The model term and the sandwich's bread: the observed information's inverse. Without the
  // candidates' second moments (or if it is not definite): the complete-data matrix, and as
  // bread the Student-t objective's Hessian with a point's candidates taken as one (an
  // M-estimator's), or the complete-data one if that is not definite either.
  Matrix6d observed_inverse, bread;
  const bool use_observed = have_moments && invertPositiveDefinite(observed, &observed_inverse);
  const Matrix6d model = sigma_squared * (use_observed ? observed_inverse : hessian_inverse);
  if (use_observed) {
    bread = observed_inverse;
  } else if (!invertPositiveDefinite(robust_hessian, &bread)) {
    bread = hessian_inverse;
  }

  // Structure term: a spatial HAC sandwich, H^-1 S(L) H^-1 with S(L) = sum g_i g_j^T over the
  // pairs of points closer than about L. Neighbouring residuals share the model's errors (a
  // surface sampled a little off, a warped wall, the target's own noise under several source
  // points), so they are not independent constraints. How far that correlation reaches is read
  // from the data: S(L) grows with L as long as the scores of points L apart pull the same way,
  // and falls back towards zero beyond (at the optimum the scores sum to zero). The term is the
  // level of a doubling ladder of L, from the finest grid to the overlap's size, that reaches
  // furthest. Each level estimates the same covariance with its own noise: their upper bound
  // (the positive parts of their differences, direction by direction) exceeds every one of them
  // and was too cautious wherever the levels scatter (scan pairs: error / sigma 0.70 -> 0.91).
  const double radius = 0.5 * overlap.diagonal().norm();
  CellScores cells = sumPerCell(point_cells, point_scores);
  Matrix6d widest = Matrix6d::Zero(), envelope = Matrix6d::Zero();
  size_t cell_count = 0;
  double cell_edge = 0.0, largest = 0.0;
  for (double edge = finest_edge; edge > 0.0 && edge <= kCoarsestEdge * radius; edge *= 2.0) {
    const Matrix6d level = bread * neighbourScoreSum(cells) * bread;
    envelope = upperBound(envelope, level, radius);
    // Metres and radians weighed as in the bounds.
    const double size = level.topLeftCorner<3, 3>().trace() +
                        radius * radius * level.bottomRightCorner<3, 3>().trace();
    if (size > largest) largest = size, widest = level, cell_count = cells.size(), cell_edge = edge;
    cells = coarsen(cells);
  }
  Matrix6d structure = widest;
  Matrix6d map_scale;
  if (radius > 0.0 && octantJackknife(octants, hessian, moved.size(), &map_scale)) {
    structure = upperBound(structure, map_scale, radius);
    envelope = upperBound(envelope, map_scale, radius);
  }
  // The two terms overlap: the structure term also holds the white noise the model term counts.
  // Their upper bound, not their sum (which counted that noise twice: 1.2-1.6x too cautious
  // wherever the residuals are independent, once the bread holds the observed information).
  Matrix6d bounded = upperBound(model, structure, radius);
  // The map cut in two (map_scale_spread.hpp): a warp or a bend over the whole map makes its
  // halves disagree as wholes, at a scale the correlogram's neighbourhoods do not reach and an
  // eighth left out barely moves. That is tested, not added: a cut is taken into the bound only
  // where its halves disagree beyond what every level of the ladder allows (kHalvesSignificance
  // against the levels' upper bound, a wide null: the cut fires on a warp, not on the levels'
  // scatter, and the warp polish it triggers does not move with the reported term). The halves of
  // a scan or a room also disagree by what cancels in the whole (a sensor's sampling seen from
  // opposite sides), and as one more term they made the simulated offices and scan pairs 1.1-1.4x
  // more cautious. Simulated RGB-D fragments warped by 1 %: error / sigma 3.5-3.9 -> 1.7.
  size_t cuts = 0;
  const Matrix6d null_spread = upperBound(model, envelope, radius);
  for (const Matrix6d& cut : halfSplitDisagreements(octants, hessian_inverse, overlap.sizes())) {
    if (largestExcess(cut, null_spread) > kHalvesSignificance) {
      bounded = upperBound(bounded, cut, radius);
      ++cuts;
    }
  }
  const Matrix6d to_origin = pivotToOrigin(centre, T_target_source.translation());
  *covariance = to_origin * bounded * to_origin.transpose();
  *covariance = 0.5 * (*covariance + covariance->transpose()).eval();  // exact symmetry
  if (terms) {
    terms->model = to_origin * model * to_origin.transpose();
    terms->structure = to_origin * structure * to_origin.transpose();
    terms->cells = cell_count;
    terms->cell_edge = cell_edge;
    terms->disagreeing_cuts = cuts;
  }
  return covariance->allFinite();
}

ExpectedError expectedError(const Eigen::Matrix<double, 6, 6>& covariance) {
  return {std::sqrt(std::max(0.0, covariance.topLeftCorner<3, 3>().trace())),
          std::sqrt(std::max(0.0, covariance.bottomRightCorner<3, 3>().trace()))};
}

Eigen::Matrix<double, 6, 6> invertedPoseCovariance(const Eigen::Isometry3d& T,
                                                   const Eigen::Matrix<double, 6, 6>& covariance) {
  // T^-1 = (R^T, -R^T t). With R <- exp(w) R, t <- t + v on T, the inverse moves by
  // w' = -R^T w and v' = -R^T v - R^T [t]x w (first order).
  const Eigen::Matrix3d Rt = T.linear().transpose();
  Matrix6d jacobian = Matrix6d::Zero();
  jacobian.topLeftCorner<3, 3>() = -Rt;
  jacobian.topRightCorner<3, 3>() = -Rt * crossMatrix(T.translation());
  jacobian.bottomRightCorner<3, 3>() = -Rt;
  return jacobian * covariance * jacobian.transpose();
}

}  // namespace pda_registration

#include "pda_registration/core/warm_start.hpp"

#include "pda_registration/core/nearest_rotation.hpp"

namespace pda_registration {

bool WarmStart::holds(const std::string& dense_frame, const std::string& sparse_frame) const {
  return have_ && dense_frame == dense_frame_ && sparse_frame == sparse_frame_;
}

Eigen::Isometry3d WarmStart::corrected(const Eigen::Isometry3d& T_dense_sparse_seed) const {
  return correction_ * T_dense_sparse_seed;
}

void WarmStart::remember(const Eigen::Isometry3d& T_dense_sparse_seed,
                         const Eigen::Isometry3d& T_dense_sparse_estimate,
                         const std::string& dense_frame, const std::string& sparse_frame) {
  Eigen::Isometry3d correction = T_dense_sparse_estimate * T_dense_sparse_seed.inverse();
  // Products of products drift off SO(3) in the last bits; keep the rotation a rotation.
  Eigen::Matrix3d rotation;
  if (!correction.matrix().allFinite() || !nearestRotation(correction.linear(), &rotation)) {
    forget();
    return;
  }
  correction.linear() = rotation;
  have_ = true;
  correction_ = correction;
  dense_frame_ = dense_frame;
  sparse_frame_ = sparse_frame;
}

void WarmStart::forget() {
  have_ = false;
  correction_ = Eigen::Isometry3d::Identity();
  dense_frame_.clear();
  sparse_frame_.clear();
}

bool alignFromWarmStart(
    const WarmStart& warm, bool use_warm, const Eigen::Isometry3d& T_dense_sparse_seed,
    const std::function<AttemptOutcome(const Eigen::Isometry3d& initial, bool warm)>& attempt) {
  if (!use_warm) {
    attempt(T_dense_sparse_seed, false);
    return false;
  }
  if (attempt(warm.corrected(T_dense_sparse_seed), true) != AttemptOutcome::kRejected) return false;
  attempt(T_dense_sparse_seed, false);
  return true;
}

}  // namespace pda_registration

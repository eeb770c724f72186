#include "pda_registration/core/alignment_gate.hpp"

#include <cmath>
#include <sstream>

#include "pda_registration/core/pose_covariance.hpp"

namespace pda_registration {

Verdict judgeAlignment(const RegistrationResult& result, const Eigen::Isometry3d& seed,
                       const AcceptanceThresholds& thresholds) {
  Verdict verdict;
  std::ostringstream reason;
  const double moved = (result.T_target_source.translation() - seed.translation()).norm();
  const double turned = std::abs(
      Eigen::AngleAxisd(result.T_target_source.linear() * seed.linear().transpose()).angle());
  if (!result.converged) {
    reason << "not converged: " << result.reason;
  } else if (result.inlier_fraction < thresholds.min_inlier_fraction) {
    reason << "inlier fraction " << result.inlier_fraction << " < "
           << thresholds.min_inlier_fraction;
  } else if (moved > thresholds.max_correction_translation) {
    reason << "correction of " << moved << " m from the seed exceeds max_correction_translation "
           << thresholds.max_correction_translation;
  } else if (turned > thresholds.max_correction_rotation) {
    reason << "correction of " << turned * 180.0 / M_PI
           << " deg from the seed exceeds max_correction_rotation "
           << thresholds.max_correction_rotation * 180.0 / M_PI;
  } else if (const ExpectedError expected = expectedError(result.covariance);
             thresholds.max_expected_translation > 0.0 &&
             expected.translation > thresholds.max_expected_translation) {
    reason << "expected error " << expected.translation << " m (1 sigma of its covariance) "
           << "exceeds max_expected_error " << thresholds.max_expected_translation;
  } else if (thresholds.max_expected_rotation > 0.0 &&
             expected.rotation > thresholds.max_expected_rotation) {
    reason << "expected error " << expected.rotation * 180.0 / M_PI
           << " deg (1 sigma of its covariance) exceeds max_expected_error_deg "
           << thresholds.max_expected_rotation * 180.0 / M_PI;
  } else {
    verdict.accepted = true;
    return verdict;
  }
  verdict.reason = reason.str();
  return verdict;
}

}  // namespace pda_registration

#pragma once
// Decides whether an alignment may replace the last good estimate in a running system: it must
// have converged, matched enough of the source, stayed within a plausible correction of its
// seed, and (when asked) expect no larger an error than the stack can use. A wild transform on
// tf costs a robot more than a missed update.

#include <Eigen/Geometry>
#include <string>

#include "pda_registration/core/registration_result.hpp"

namespace pda_registration {

struct AcceptanceThresholds {
  double min_inlier_fraction = 0.3;         ///< of the used source points
  double max_correction_translation = 1.0;  ///< [length] from the seed
  double max_correction_rotation = 0.35;    ///< [rad] from the seed (about 20 degrees)
  /// The error the result's own covariance expects (1 sigma, pose_covariance.hpp's
  /// expectedError): larger is rejected. 0 = no limit (the default: what a stack can use is
  /// the stack's to say).
  double max_expected_translation = 0.0;  ///< [length]
  double max_expected_rotation = 0.0;     ///< [rad]
};

struct Verdict {
  bool accepted = false;
  std::string reason;  ///< why it was rejected (empty when accepted)
};

Verdict judgeAlignment(const RegistrationResult& result, const Eigen::Isometry3d& seed,
                       const AcceptanceThresholds& thresholds);

}  // namespace pda_registration

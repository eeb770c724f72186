#pragma once
// Runs PDA or one of PCL's methods on the same inputs with one call, so pda_align and
// pda_benchmark compare methods the same way (every method's time includes its own target
// indexing, since PCL's does).

#include <Eigen/Geometry>
#include <string>

#include "pda_registration/core/alignment_trace.hpp"
#include "pda_registration/core/point_list.hpp"
#include "pda_registration/core/registration_parameters.hpp"
#include "pda_registration/core/registration_result.hpp"
#include "pda_registration/tools/pcl_baselines.hpp"

namespace pda_registration {

struct MethodSettings {
  RegistrationParameters pda;
  BaselineParameters baseline;
};

/// Method names: "pda", "icp", "gicp", "ndt".
bool isKnownMethod(const std::string& method);

/// A method's outcome in one shape. For PCL methods the PDA-only fields stay at their defaults
/// and `pda_fields` is false.
struct MethodOutcome {
  std::string method;
  bool pda_fields = false;
  RegistrationResult result;  ///< T, converged, time_ms (+ runs, sigma, ... for PDA)
  double fitness = 0.0;       ///< PCL fitness score (PCL methods only)
};

/// `trace` (PDA only): receives the alignment's runs and attempts (alignment_trace.hpp).
MethodOutcome runMethod(const std::string& method, const PointList& target, const PointList& source,
                        const Eigen::Isometry3d& T_target_source_initial,
                        const MethodSettings& settings, const AlignmentTrace& trace = {});

}  // namespace pda_registration

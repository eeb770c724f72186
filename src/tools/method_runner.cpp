#include "pda_registration/tools/method_runner.hpp"

#include <algorithm>
#include <chrono>

#include "pda_registration/core/pda_registration.hpp"

namespace pda_registration {

bool isKnownMethod(const std::string& method) {
  BaselineMethod unused;
  return method == "pda" || parseBaselineMethod(method, &unused);
}

MethodOutcome runMethod(const std::string& method, const PointList& target, const PointList& source,
                        const Eigen::Isometry3d& T_target_source_initial,
                        const MethodSettings& settings, const AlignmentTrace& trace) {
  MethodOutcome outcome;
  outcome.method = method;
  BaselineMethod baseline;
  if (parseBaselineMethod(method, &baseline)) {
    const BaselineResult b =
        runBaseline(baseline, target, source, T_target_source_initial, settings.baseline);
    outcome.result.T_target_source = b.T_target_source;
    outcome.result.converged = b.converged;
    outcome.result.reason = b.converged ? "" : "PCL reports no convergence";
    outcome.result.time_ms = b.time_ms;
    outcome.fitness = b.fitness;
    return outcome;
  }
  outcome.pda_fields = true;
  const auto start = std::chrono::steady_clock::now();
  PdaRegistration registration(settings.pda);
  registration.setTrace(trace);
  registration.setTarget(target);
  outcome.result = registration.align(source, T_target_source_initial);
  outcome.result.time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return outcome;
}

}  // namespace pda_registration

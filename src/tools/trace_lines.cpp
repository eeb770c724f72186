#include "pda_registration/tools/trace_lines.hpp"

#include <cmath>

#include "pda_registration/tools/json_line.hpp"

namespace pda_registration {

AlignmentTrace jsonLinesTrace(std::ostream* out,
                              std::function<double(const Eigen::Isometry3d&)> error_from_truth) {
  AlignmentTrace trace;
  trace.run = [out](const RunRecord& r) {
    JsonLine line;
    line.add("trace", "run").add("attempt", r.attempt).add("run", r.run).add("stage", r.stage);
    line.add("points", r.points).add("radius", r.radius).add("sigma", r.sigma).add("nu", r.nu);
    line.add("step_m", r.step_translation).add("step_deg", r.step_rotation * 180.0 / M_PI);
    line.add("em_iterations", r.em_iterations);
    if (r.replayed) line.add("replayed", true);
    *out << line.str() << '\n';
  };
  trace.attempt = [out, error_from_truth](const AttemptRecord& a) {
    JsonLine line;
    line.add("trace", "attempt").add("attempt", a.attempt).add("converged", a.converged);
    line.add("adopted", a.adopted).add("reason", a.reason).add("runs", a.runs);
    line.add("sigma", a.sigma).add("time_ms", a.time_ms);
    if (error_from_truth) line.add("mean_distance", error_from_truth(a.T_target_source));
    line.add("T", a.T_target_source);
    *out << line.str() << '\n';
  };
  return trace;
}

}  // namespace pda_registration

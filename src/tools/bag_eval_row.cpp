#include "pda_registration/tools/bag_eval_row.hpp"

#include <Eigen/Geometry>
#include <iomanip>
#include <sstream>

namespace pda_registration {
namespace {

// RFC 4180: a field with a comma, quote or line break is quoted, inner quotes doubled.
std::string csvText(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace

std::string csvHeader(bool ground_truth) {
  std::string header = "set";
  for (const std::string& flag : gridFlagNames()) header += "," + flag;
  header +=
      ",message,stamp,seed,x,y,z,qx,qy,qz,qw,converged,reason,sigma,inlier_fraction,runs,"
      "em_iterations,time_ms";
  if (ground_truth) header += ",eq22_m,rot_err_deg,trans_err_m,seed_eq22_m";
  return header + "\n";
}

std::string csvLine(const ParameterSet& set, const EvaluationRow& row, bool ground_truth) {
  const RegistrationResult& r = row.result;
  const Eigen::Vector3d t = r.T_target_source.translation();
  const Eigen::Quaterniond q(r.T_target_source.rotation());
  std::ostringstream line;
  line << std::setprecision(9) << set.id;
  for (const std::string& value : set.values) line << ',' << value;
  line << ',' << row.message << ',' << std::fixed << std::setprecision(6) << row.stamp
       << std::defaultfloat << std::setprecision(9) << ',' << row.seed << ',' << t.x() << ','
       << t.y() << ',' << t.z() << ',' << q.x() << ',' << q.y() << ',' << q.z() << ',' << q.w()
       << ',' << (r.converged ? 1 : 0) << ',' << csvText(r.reason) << ',' << r.sigma << ','
       << r.inlier_fraction << ',' << r.runs << ',' << r.em_iterations << ',' << r.time_ms;
  if (ground_truth) {
    line << ',' << row.error.mean_distance << ',' << row.error.rotation_deg << ','
         << row.error.translation << ',' << row.seed_error.mean_distance;
  }
  line << '\n';
  return line.str();
}

}  // namespace pda_registration

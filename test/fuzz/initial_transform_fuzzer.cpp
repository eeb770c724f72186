// initialTransformFromList: the nodelet's ~initial_transform, a list of numbers from the
// parameter server (XmlRpc doubles: any bit pattern, NaN and Inf included). The input is the
// list, 8 bytes per number (6, 7 and 16 numbers are the accepted lengths). Accepted ⇒ a finite
// rigid transform with the translation and rotation given; refused ⇒ a one-line reason.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "fuzz_invariant.hpp"
#include "pda_registration/ros/initial_transform.hpp"

using namespace pda_registration;

namespace {

/// The rotation of quaternion (w, x, y, z) = values 6, 3, 4, 5, computed after scaling by the
/// largest component so that no magnitude in the list can overflow or underflow the result.
Eigen::Matrix3d quaternionRotation(const std::vector<double>& v) {
  Eigen::Vector4d q(v[6], v[3], v[4], v[5]);
  q /= q.cwiseAbs().maxCoeff();
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<double> values(std::min<size_t>(size / sizeof(double), 20));
  if (!values.empty()) std::memcpy(values.data(), data, values.size() * sizeof(double));
  Eigen::Isometry3d T;
  std::string error;
  if (!initialTransformFromList(values, &T, &error)) {
    fuzzing::require(fuzzing::isOneLineMessage(error), "refusal is a one-line reason", error);
    return 0;
  }
  fuzzing::requireRigid(T);
  const Eigen::Matrix3d R = T.linear();
  const bool matrix = values.size() == 16;
  const Eigen::Vector3d given = matrix ? Eigen::Vector3d(values[3], values[7], values[11])
                                       : Eigen::Vector3d(values[0], values[1], values[2]);
  fuzzing::require(T.translation() == given, "translation is the one given");
  if (values.size() == 7) {
    fuzzing::require((R - quaternionRotation(values)).norm() < 1e-9,
                     "rotation is the quaternion given, whatever its scale");
  }
  return 0;
}

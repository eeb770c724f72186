#include "test_support/simulated_cases.hpp"

#include <gtest/gtest.h>

#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/perturbation.hpp"

namespace pda_registration {
namespace testing_support {

using namespace simulation;

MapSimulationOptions smallOfficeOptions(uint64_t seed) {
  MapSimulationOptions options;
  options.seed = seed;
  options.kinect_frames = 3;
  options.velodyne_revolutions = 1;
  return options;
}

MapSimulationOptions rgbdFragmentOptions(uint64_t seed, double distortion) {
  MapSimulationOptions options;
  options.seed = seed;
  options.sparse_sensor = SparseSensor::kKinectFragment;
  options.distortion = distortion;
  return options;
}

MapSimulationOptions lowOverlapFragmentOptions(uint64_t seed) {
  MapSimulationOptions options = rgbdFragmentOptions(seed);
  options.fragment_length = 0.4;
  return options;
}

MapSimulationOptions carParkOptions(DenseSensor dense_sensor, bool same_pose) {
  MapSimulationOptions options;
  options.seed = 3;
  options.scene = SceneKind::kOutdoor;
  options.dense_sensor = dense_sensor;
  options.same_pose = same_pose;
  options.dense_voxel_size = 0.0;
  return options;
}

MapSimulationOptions scanPairOptions(DenseSensor dense_sensor, uint64_t seed,
                                     const Eigen::Vector3d& dense_offset) {
  MapSimulationOptions options = carParkOptions(dense_sensor, false);
  options.seed = seed;
  options.dense_revolutions = 1;
  options.velodyne_revolutions = 1;
  options.dense_offset_set = true;
  options.dense_offset = dense_offset;
  options.scan_frame = true;
  return options;
}

const SimulatedMaps& latticeMaps() {
  static const SimulatedMaps maps = simulateMaps(carParkOptions(DenseSensor::kLidar64, true));
  return maps;
}

double alignedError(const SimulatedMaps& maps, const RegistrationParameters& parameters,
                    double degrees, double metres, uint64_t seed, RegistrationResult* out) {
  PdaRegistration registration(parameters);
  EXPECT_TRUE(registration.setTarget(maps.dense));
  const Eigen::Isometry3d initial =
      maps.T_target_source * randomPerturbation(degrees, metres, seed);
  *out = registration.align(maps.sparse, initial);
  return poseError(maps.sparse, out->T_target_source, maps.T_target_source).mean_distance;
}

}  // namespace testing_support
}  // namespace pda_registration

// The ROS layer's pure parts, without a roscore: PointCloud2 conversion of good and broken
// messages, the ~initial_transform list, association markers, the newest-input mailbox,
// covariance propagation through inversion, and the idle-core count that caps the alignment's
// threads. (The gate and the warm start: alignment_decisions_test.)
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "pda_registration/core/pose_covariance.hpp"
#include "pda_registration/core/pose_jacobian.hpp"
#include "pda_registration/ros/alignment_status.hpp"
#include "pda_registration/ros/association_markers.hpp"
#include "pda_registration/ros/idle_cores.hpp"
#include "pda_registration/ros/initial_transform.hpp"
#include "pda_registration/ros/latest_input_queue.hpp"
#include "pda_registration/ros/live_parameters.hpp"
#include "pda_registration/ros/point_cloud_conversion.hpp"

namespace pda_registration {
namespace {

PointList somePoints(size_t n) {
  PointList points;
  for (size_t i = 0; i < n; ++i) points.emplace_back(0.1 * i, -0.2 * i, 1.0 + 0.01 * i);
  return points;
}

sensor_msgs::PointCloud2 cloudOf(const PointList& points) {
  std_msgs::Header header;
  header.frame_id = "map";
  return toPointCloud2(points, header);
}

TEST(PointCloudConversion, RoundTripsFloat32) {
  const PointList points = somePoints(50);
  const CloudConversion back = fromPointCloud2(cloudOf(points));
  ASSERT_TRUE(back.ok()) << back.error;
  ASSERT_EQ(back.points.size(), 50u);
  EXPECT_LT((back.points[49] - points[49]).norm(), 1e-6);
}

TEST(PointCloudConversion, ReadsFloat64OrganisedCloudsWithPaddingAndDropsNaN) {
  sensor_msgs::PointCloud2 m;
  m.height = 2;
  m.width = 3;
  m.point_step = 32;                         // x y z as doubles plus 8 bytes of something else
  m.row_step = m.point_step * m.width + 16;  // padded rows
  const char* names[3] = {"x", "y", "z"};
  for (uint32_t i = 0; i < 3; ++i) {
    sensor_msgs::PointField f;
    f.name = names[i];
    f.offset = 8 * i;
    f.datatype = sensor_msgs::PointField::FLOAT64;
    f.count = 1;
    m.fields.push_back(f);
  }
  m.data.assign(m.row_step * m.height, 0);
  for (uint32_t r = 0; r < 2; ++r) {
    for (uint32_t c = 0; c < 3; ++c) {
      const double xyz[3] = {double(r), double(c),
                             (r == 1 && c == 2) ? std::numeric_limits<double>::quiet_NaN() : 5.0};
      std::memcpy(&m.data[r * m.row_step + c * m.point_step], xyz, sizeof xyz);
    }
  }
  const CloudConversion out = fromPointCloud2(m);
  ASSERT_TRUE(out.ok()) << out.error;
  EXPECT_EQ(out.points.size(), 5u);
  EXPECT_EQ(out.non_finite, 1u);
  EXPECT_EQ(out.points[4], Point(1.0, 1.0, 5.0));
}

TEST(PointCloudConversion, RefusesBrokenMessagesWithAReason) {
  const sensor_msgs::PointCloud2 good = cloudOf(somePoints(10));
  struct Case {
    std::function<void(sensor_msgs::PointCloud2*)> break_it;
    std::string reason;
  };
  const std::vector<Case> cases = {
      {[](sensor_msgs::PointCloud2* m) { m->width = 0; }, "empty cloud"},
      {[](sensor_msgs::PointCloud2* m) { m->data.resize(m->data.size() - 1); }, "data holds"},
      {[](sensor_msgs::PointCloud2* m) { m->row_step = 1; }, "shorter than width x point_step"},
      {[](sensor_msgs::PointCloud2* m) { m->width = 1000000; }, "shorter than width x point_step"},
      {[](sensor_msgs::PointCloud2* m) { m->height = 1000; }, "data holds"},
      {[](sensor_msgs::PointCloud2* m) { m->fields[1].name = "q"; }, "no 'y' field"},
      {[](sensor_msgs::PointCloud2* m) { m->fields[2].datatype = sensor_msgs::PointField::INT8; },
       "not FLOAT32"},
      {[](sensor_msgs::PointCloud2* m) { m->fields[2].offset = 100; }, "outside point_step"},
      {[](sensor_msgs::PointCloud2* m) { m->point_step = 0; }, "outside point_step"},
      {[](sensor_msgs::PointCloud2* m) { m->is_bigendian = !m->is_bigendian; }, "byte order"},
      {[](sensor_msgs::PointCloud2* m) {
         const float nan = std::numeric_limits<float>::quiet_NaN();
         for (size_t i = 0; i + 4 <= m->data.size(); i += 4) std::memcpy(&m->data[i], &nan, 4);
       },
       "are NaN or Inf"},
  };
  for (const Case& c : cases) {
    sensor_msgs::PointCloud2 broken = good;
    c.break_it(&broken);
    const CloudConversion out = fromPointCloud2(broken);
    EXPECT_FALSE(out.ok());
    EXPECT_NE(out.error.find(c.reason), std::string::npos) << out.error;
  }
}

// Found by the point_cloud2 fuzzer (test/fuzz/regressions/point_cloud2/): for huge layouts the
// size in the error wrapped around 2^64 and named a wrong number of bytes.
TEST(PointCloudConversion, HugeLayoutsAreRefusedWithTheirTrueSize) {
  sensor_msgs::PointCloud2 m = cloudOf(somePoints(4));
  m.width = m.height = 0xFFFFFFFFu;
  m.row_step = 0xFFFFFFFFu;
  CloudConversion out = fromPointCloud2(m);
  EXPECT_EQ(out.error, "row_step 4294967295 is shorter than width x point_step = 51539607540");
  m.width = 1;
  m.row_step = 12;
  out = fromPointCloud2(m);
  EXPECT_EQ(out.error, "data holds 48 bytes but height x row_step needs 51539607540");
}

TEST(InitialTransform, ReadsSixSevenOrSixteenNumbersAndRefusesTheRest) {
  Eigen::Isometry3d T;
  std::string error;
  ASSERT_TRUE(initialTransformFromList({1, 2, 3, 0, 0, M_PI / 2}, &T, &error)) << error;
  EXPECT_TRUE(T.linear().isApprox(
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix()));
  EXPECT_EQ(T.translation(), Eigen::Vector3d(1, 2, 3));
  ASSERT_TRUE(initialTransformFromList({1, 2, 3, 0, 0, 1, 1}, &T, &error)) << error;
  EXPECT_TRUE(T.linear().isApprox(
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix()));
  ASSERT_TRUE(
      initialTransformFromList({0, -1, 0, 4, 1, 0, 0, 5, 0, 0, 1, 6, 0, 0, 0, 1}, &T, &error))
      << error;
  EXPECT_EQ(T.translation(), Eigen::Vector3d(4, 5, 6));
  EXPECT_FALSE(initialTransformFromList({1, 2, 3, 4, 5}, &T, &error));
  EXPECT_NE(error.find("got 5"), std::string::npos) << error;
  EXPECT_FALSE(initialTransformFromList({0, 0, 0, 0, 0, 0, 0}, &T, &error));
  EXPECT_NE(error.find("zero quaternion"), std::string::npos) << error;
  EXPECT_FALSE(initialTransformFromList({0, 0, 0, 0, 0, std::nan("")}, &T, &error));
  EXPECT_NE(error.find("NaN or Inf"), std::string::npos) << error;
}

// Found by the initial_transform fuzzer (regressions/initial_transform/): huge finite entries made
// the orthonormality error Inf - Inf = NaN, which passed "> 1e-3", and the transform came out NaN.
TEST(InitialTransform, HugeEntriesAreNotARotation) {
  Eigen::Isometry3d T;
  std::string error;
  EXPECT_FALSE(initialTransformFromList({2.7e154, -3.4e221, 0, 0, -3.4e221, -1.7e308, -1.2e217, 0,
                                         -3.4e221, 0, -1.7e308, 0, 0, 0, 0, 1},
                                        &T, &error));
  EXPECT_NE(error.find("not a rotation"), std::string::npos) << error;
}

// Found by the initial_transform fuzzer (test/fuzz/regressions/initial_transform/): a quaternion
// with components beyond ~1e154 overflowed its norm to Inf and was read as the identity; the
// second one's norm exceeds even DBL_MAX.
TEST(InitialTransform, HugeQuaternionIsStillItsRotation) {
  Eigen::Isometry3d T;
  std::string error;
  ASSERT_TRUE(initialTransformFromList({0, 0, 0, -1.1e217, 0, 0, 0}, &T, &error)) << error;
  EXPECT_TRUE(T.linear().isApprox(Eigen::Vector3d(1, -1, -1).asDiagonal().toDenseMatrix()))
      << T.linear();
  ASSERT_TRUE(initialTransformFromList({1, 2, 0.5, 0, 0, -3.6e307, -1.76e308}, &T, &error))
      << error;
  const Eigen::Quaterniond same_direction(-1.76, 0, 0, -0.36);
  EXPECT_TRUE(T.linear().isApprox(same_direction.normalized().toRotationMatrix())) << T.linear();
}

Associations threePointsWithCandidates() {
  Associations a;
  a.offsets.push_back(0);
  for (int i = 0; i < 3; ++i) {
    a.source_points.emplace_back(i, 0, 0);
    for (int c = 0; c < 4; ++c) {
      a.candidates.emplace_back(i, 0.1 * c, 0);
      a.posterior.push_back(c == 0 ? 0.7 : 0.1);
    }
    a.offsets.push_back(a.candidates.size());
  }
  return a;
}

TEST(AssociationMarkers, AlphaIsTheWeightAndTheCapKeepsWholePoints) {
  std_msgs::Header header;
  header.frame_id = "map";
  const visualization_msgs::MarkerArray all =
      associationMarkers(threePointsWithCandidates(), header, 100, 0.01);
  ASSERT_EQ(all.markers.size(), 1u);
  const visualization_msgs::Marker& lines = all.markers[0];
  EXPECT_EQ(lines.type, visualization_msgs::Marker::LINE_LIST);
  ASSERT_EQ(lines.points.size(), 24u);
  ASSERT_EQ(lines.colors.size(), 24u);
  double first_point_alpha = 0.0;
  for (size_t i = 0; i < 8; i += 2) first_point_alpha += lines.colors[i].a;
  EXPECT_NEAR(first_point_alpha, 1.0, 1e-6);
  EXPECT_FLOAT_EQ(lines.colors[0].r, 0.7f);

  // A cap of 8 lines keeps a uniform subsample of whole source points (every second point).
  const auto capped = associationMarkers(threePointsWithCandidates(), header, 8, 0.01);
  EXPECT_LE(capped.markers[0].points.size() / 2, 8u);
  EXPECT_EQ(capped.markers[0].points.size() % 8, 0u);
  EXPECT_EQ(associationMarkers(threePointsWithCandidates(), header, 0, 0.01).markers[0].action,
            visualization_msgs::Marker::DELETE);
}

TEST(LatestInputQueue, NewerInputReplacesPendingAndStopWakesTheWorker) {
  LatestInputQueue<int, int> queue;
  EXPECT_FALSE(queue.putSparse(1));
  EXPECT_TRUE(queue.putSparse(2));  // 1 was still pending: dropped
  EXPECT_FALSE(queue.putDense(10));
  int dense = 0, sparse = 0;
  bool has_dense = false, has_sparse = false;
  ASSERT_TRUE(queue.waitAndTake(&dense, &has_dense, &sparse, &has_sparse));
  EXPECT_TRUE(has_dense && has_sparse);
  EXPECT_EQ(dense, 10);
  EXPECT_EQ(sparse, 2);

  std::thread worker(
      [&] { EXPECT_FALSE(queue.waitAndTake(&dense, &has_dense, &sparse, &has_sparse)); });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  queue.stop();
  worker.join();
}

// The inverse's covariance matches a finite-difference propagation through T -> T^-1.
TEST(InvertedPoseCovariance, MatchesNumericPropagation) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(3.0, -1.0, 2.0);
  Matrix6d numeric_jacobian;
  const double h = 1e-6;
  for (int i = 0; i < 6; ++i) {
    Vector6d delta = Vector6d::Zero();
    delta(i) = h;
    const Eigen::Isometry3d moved_inverse = applyIncrement(T, delta).inverse();
    const Eigen::Isometry3d inverse = T.inverse();
    // Express the change of the inverse in the same increment convention.
    Vector6d change;
    change.head<3>() = moved_inverse.translation() - inverse.translation();
    const Eigen::AngleAxisd w(moved_inverse.linear() * inverse.linear().transpose());
    change.tail<3>() = w.angle() * w.axis();
    numeric_jacobian.col(i) = change / h;
  }
  Matrix6d covariance = Matrix6d::Identity();
  covariance(0, 3) = covariance(3, 0) = 0.2;
  covariance(4, 4) = 0.5;
  const Matrix6d expected = numeric_jacobian * covariance * numeric_jacobian.transpose();
  EXPECT_TRUE(invertedPoseCovariance(T, covariance).isApprox(expected, 1e-4));
  // Inverting twice gives the original back.
  EXPECT_TRUE(invertedPoseCovariance(T.inverse(), invertedPoseCovariance(T, covariance))
                  .isApprox(covariance, 1e-9));
}

TEST(IdleCores, AnotherProcessKeepingACoreBusyLeavesOneFewer) {
  const double cores = static_cast<double>(sysconf(_SC_NPROCESSORS_ONLN));
  IdleCores idle;
  EXPECT_EQ(idle.sample(), cores);  // no full window yet: every core
  EXPECT_EQ(idle.threadsFor(1), 1);
  EXPECT_EQ(idle.threadsFor(0), 1);
  // A child process spinning for the whole window is another process's work: at least ~one core
  // fewer is idle, whatever else the machine runs. (This process's own threads never count.)
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    volatile uint64_t spin = 0;
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(2500);
    while (std::chrono::steady_clock::now() < end) spin = spin + 1;
    _exit(0);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  idle.sample(0.0);  // starts the window with the child running
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  const double during = idle.sample(1.0);
  kill(child, SIGKILL);
  waitpid(child, nullptr, 0);
  EXPECT_GE(during, 0.0);
  EXPECT_LE(during, cores - 0.8);
  EXPECT_LE(idle.threadsFor(static_cast<int>(cores), 1e9),
            std::max(1, static_cast<int>(cores) - 1));
}

// One default parameter set: the nodelet's dynamic_reconfigure defaults map onto the core's (and
// so the tools') registration defaults, except the thread count (the tools default to one thread
// for comparable timings, the nodelet to two) and the crop bounds, which follow the gate.
TEST(LiveParameters, TheNodeletsDefaultsAreTheCoresAndTheTools) {
  const RegistrationParameters nodelet =
      liveParametersFrom(PdaRegistrationConfig::__getDefault__()).registration;
  const RegistrationParameters core;
  EXPECT_EQ(nodelet.k, core.k);
  EXPECT_EQ(nodelet.radius, core.radius);
  EXPECT_EQ(nodelet.min_radius, core.min_radius);
  EXPECT_EQ(nodelet.nu, core.nu);
  EXPECT_EQ(nodelet.nu_mode, core.nu_mode);
  EXPECT_EQ(nodelet.sigma_mode, core.sigma_mode);
  EXPECT_EQ(nodelet.fixed_sigma, core.fixed_sigma);
  EXPECT_EQ(nodelet.surface_anisotropy, core.surface_anisotropy);
  EXPECT_EQ(nodelet.sampling_scale, core.sampling_scale);
  EXPECT_EQ(nodelet.normal_voxel_size, core.normal_voxel_size);
  EXPECT_EQ(nodelet.max_runs, core.max_runs);
  EXPECT_EQ(nodelet.max_em_iterations, core.max_em_iterations);
  EXPECT_EQ(nodelet.coarse_stride, core.coarse_stride);
  EXPECT_EQ(nodelet.translation_epsilon, core.translation_epsilon);
  EXPECT_EQ(nodelet.rotation_epsilon, core.rotation_epsilon);
  EXPECT_EQ(nodelet.solver, core.solver);
  EXPECT_EQ(nodelet.solver_max_iterations, core.solver_max_iterations);
  EXPECT_EQ(nodelet.source_voxel_size, core.source_voxel_size);
  EXPECT_EQ(nodelet.target_voxel_size, core.target_voxel_size);
  EXPECT_EQ(nodelet.crop_above_points, core.crop_above_points);
  EXPECT_EQ(nodelet.min_correspondences, core.min_correspondences);
  EXPECT_EQ(nodelet.min_support_fraction, core.min_support_fraction);
  EXPECT_EQ(nodelet.max_source_points, core.max_source_points);
  EXPECT_EQ(nodelet.spread_source_budget, core.spread_source_budget);
  EXPECT_EQ(nodelet.threads, 2);
  EXPECT_EQ(core.threads, 1);
  PdaRegistrationConfig spread = PdaRegistrationConfig::__getDefault__();
  spread.spread_source_budget = true;
  EXPECT_TRUE(liveParametersFrom(spread).registration.spread_source_budget);
}

// The diagnostics say how far a competing pose lies (core/competing_shift.hpp), in cm, beside the
// expected error that includes it.
TEST(AlignmentStatus, DiagnosticsShowTheCompetingPose) {
  AlignmentStatus status;
  status.update([](AlignmentStatusValues& s) {
    s.have_result = true;
    s.last_result.converged = true;
    s.last_result.competing_shift = 0.25;
    s.expected_error.translation = 0.155;
  });
  diagnostic_updater::DiagnosticStatusWrapper wrapper;
  status.fill(wrapper, 1);
  std::map<std::string, std::string> values;
  for (const diagnostic_msgs::KeyValue& kv : wrapper.values) values[kv.key] = kv.value;
  ASSERT_EQ(values.count("competing pose [cm]"), 1u);
  EXPECT_NEAR(std::stod(values["competing pose [cm]"]), 25.0, 1e-9);
  EXPECT_NEAR(std::stod(values["expected error [cm]"]), 15.5, 1e-9);
}

}  // namespace
}  // namespace pda_registration

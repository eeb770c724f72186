// The least-squares polish over a warped overlap (warp_polish.hpp): when it is warranted, and what
// it does end to end on the benchmark's warped RGB-D fragment pair against its rigid twin.
#include "pda_registration/core/warp_polish.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "test_support/simulated_cases.hpp"

namespace pda_registration {
namespace {

RegistrationResult convergedWithDisagreeingHalves() {
  RegistrationResult result;
  result.converged = true;
  result.disagreeing_halves = 1;
  return result;
}

TEST(WarpPolish, WarrantedOnlyForAConvergedResultWhoseHalvesDisagree) {
  const RegistrationParameters p;
  EXPECT_TRUE(warpPolishWarranted(convergedWithDisagreeingHalves(), p, 3.0));

  RegistrationResult agreeing = convergedWithDisagreeingHalves();
  agreeing.disagreeing_halves = 0;
  EXPECT_FALSE(warpPolishWarranted(agreeing, p, 3.0));

  RegistrationResult failed = convergedWithDisagreeingHalves();
  failed.converged = false;
  EXPECT_FALSE(warpPolishWarranted(failed, p, 3.0));

  // Already Gaussian, or nu at its floor (the second start's sign of a false rest).
  EXPECT_FALSE(warpPolishWarranted(convergedWithDisagreeingHalves(), p,
                                   std::numeric_limits<double>::infinity()));
  EXPECT_FALSE(warpPolishWarranted(convergedWithDisagreeingHalves(), p, 1.0));

  RegistrationParameters single_run;
  single_run.max_runs = 1;  // the paper's single-run mode stays the paper's
  EXPECT_FALSE(warpPolishWarranted(convergedWithDisagreeingHalves(), single_run, 3.0));
}

// 6 sigma of the polish's own Gaussian, floored by the shorter of min_radius and the target's
// surface scale (min_radius alone when that is unknown), capped by the radius; a fixed radius stays
// fixed.
TEST(WarpPolish, RadiusIsSixSigmaFlooredByTheSurfaceScale) {
  RegistrationParameters p;
  p.radius = 1.0;
  p.min_radius = 0.25;
  const double surface = 0.15;
  EXPECT_NEAR(polishRadius(p, 0.039 * 0.039, surface), 0.234, 1e-9);  // below min_radius
  EXPECT_NEAR(polishRadius(p, 0.003 * 0.003, surface), 0.15, 1e-9);   // a lattice: the surface
  EXPECT_NEAR(polishRadius(p, 0.003 * 0.003, 0.0), 0.25, 1e-9);       // no scale: min_radius
  EXPECT_NEAR(polishRadius(p, 0.003 * 0.003, 0.5), 0.25, 1e-9);  // never above the refine floor
  EXPECT_NEAR(polishRadius(p, 0.1 * 0.1, surface), 0.6, 1e-9);
  EXPECT_NEAR(polishRadius(p, 0.5 * 0.5, surface), 1.0, 1e-9);  // the radius caps it
  p.min_radius = 1.5;                                           // the user fixed the radius
  EXPECT_NEAR(polishRadius(p, 0.039 * 0.039, surface), 1.0, 1e-9);
}

// The benchmark's pair (pda_simulate --seed 2 --sparse-sensor kinect, and with --distortion
// 0.01): aligned from 5 deg / 0.25 m, the error is eq. 22 from the ground truth (for the warped
// pair the warp's least-squares rigid fit over the overlap).
RegistrationResult alignFragments(double distortion, double* error, int layout = 2) {
  const simulation::SimulatedMaps maps =
      simulation::simulateMaps(testing_support::rgbdFragmentOptions(layout, distortion));
  RegistrationResult result;
  *error = testing_support::alignedError(maps, RegistrationParameters(), 5.0, 0.25, 1, &result);
  return result;
}

// Without the polish the t-weights fit the part of the warped overlap that fits best: 7.6 cm from
// the fit (PCL GICP 6.4-6.8 cm); polished 6.7 cm with the normals read at the moved points, 5.2
// cm at the candidates (normal_lookup_test.cpp) with the refine runs' 0.25-m floor, 4.9 cm within
// 6 sigma (polishRadius): inside the benchmark's 5-cm success line.
TEST(WarpPolish, WarpedRgbdFragmentsEndNearerTheirLeastSquaresFit) {
  double error = 0.0;
  const RegistrationResult result = alignFragments(0.01, &error);
  std::printf("warped fragments: %.4f m from the fit, nu %g, %d runs\n", error, result.nu,
              result.runs);
  ASSERT_TRUE(result.converged) << result.reason;
  EXPECT_TRUE(result.warp_polished);
  EXPECT_TRUE(std::isinf(result.nu));
  EXPECT_LT(error, 0.050);
}

// A second layout warped by half as much (held out of the benchmark): 2.79 cm from its fit with
// the 0.25-m floor, 1.94 cm with polishRadius (at sigma 1.9 cm the 0.15-m normal voxel is the
// floor; 1.81 cm at 6 sigma alone), PCL GICP on 0.1 m voxels 8.31 cm.
TEST(WarpPolish, HalfAsWarpedSecondLayoutEndsWithinTwoCentimetres) {
  double error = 0.0;
  const RegistrationResult result = alignFragments(0.005, &error, 3);
  std::printf("layout 3 warped by 0.5 %%: %.4f m from the fit, sigma %.4f m\n", error,
              result.sigma);
  ASSERT_TRUE(result.converged) << result.reason;
  EXPECT_TRUE(result.warp_polished);
  EXPECT_LT(error, 0.023);
}

// The same pair without the warp: the halves agree, the t's result stands.
TEST(WarpPolish, RigidRgbdFragmentsAreNotPolished) {
  double error = 0.0;
  const RegistrationResult result = alignFragments(0.0, &error);
  ASSERT_TRUE(result.converged) << result.reason;
  EXPECT_FALSE(result.warp_polished);
  EXPECT_EQ(result.disagreeing_halves, 0u);
  EXPECT_TRUE(std::isfinite(result.nu));
  EXPECT_LT(error, 0.005);
}

}  // namespace
}  // namespace pda_registration

#pragma once
// PCL's ICP, GICP and NDT behind one call, on the same inputs as PDA, so the tools can compare
// them in one process. All PCL registration templates are instantiated in pcl_baselines.cpp only.

#include <Eigen/Geometry>
#include <string>

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

enum class BaselineMethod { kIcp, kGicp, kNdt };

bool parseBaselineMethod(const std::string& text, BaselineMethod* method);
const char* toString(BaselineMethod method);

struct BaselineParameters {
  double max_correspondence_distance = 1.0;  ///< [m] ICP and GICP (PDA's radius)
  int max_iterations = 100;
  double transformation_epsilon = 1e-8;      ///< PCL's (squared-translation) threshold
  double ndt_resolution = 1.0;               ///< [m] NDT voxel size
  double ndt_step_size = 0.1;                ///< [m] NDT More-Thuente max step
  double ndt_transformation_epsilon = 1e-6;  ///< PCL tutorial's 0.01 stops NDT far from the optimum
  double source_voxel_size = 0.0;            ///< [m] 0 = full clouds
  double target_voxel_size = 0.0;
};

struct BaselineResult {
  Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();
  bool converged = false;
  double fitness = 0.0;  ///< PCL's fitness score (mean squared distance of correspondences)
  double time_ms = 0.0;  ///< setInputTarget + setInputSource + align (all index building included)
};

/// Runs one PCL method. Non-finite points are dropped first. Never throws.
BaselineResult runBaseline(BaselineMethod method, const PointList& target, const PointList& source,
                           const Eigen::Isometry3d& T_target_source_initial,
                           const BaselineParameters& parameters);

}  // namespace pda_registration

#include "pda_registration/tools/pcl_baselines.hpp"

#include <pcl/console/print.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/gicp.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/ndt.h>

#include <chrono>

#include "pda_registration/core/point_filter.hpp"

namespace pda_registration {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

Cloud::Ptr toPcl(const PointList& points, double voxel_size) {
  PointList finite = points;
  removeNonFinitePoints(&finite);
  finite = voxelDownsample(finite, voxel_size);
  Cloud::Ptr cloud(new Cloud);
  cloud->reserve(finite.size());
  for (const Point& p : finite) {
    cloud->push_back(pcl::PointXYZ(static_cast<float>(p.x()), static_cast<float>(p.y()),
                                   static_cast<float>(p.z())));
  }
  return cloud;
}

template <class Registration>
BaselineResult alignWith(Registration* registration, const Cloud::Ptr& target,
                         const Cloud::Ptr& source, const Eigen::Isometry3d& initial) {
  BaselineResult result;
  result.T_target_source = initial;
  const auto start = std::chrono::steady_clock::now();
  registration->setInputTarget(target);
  registration->setInputSource(source);
  Cloud aligned;
  registration->align(aligned, initial.matrix().cast<float>());
  result.time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  result.converged = registration->hasConverged();
  result.T_target_source.matrix() = registration->getFinalTransformation().template cast<double>();
  result.fitness = registration->getFitnessScore();
  return result;
}

}  // namespace

bool parseBaselineMethod(const std::string& text, BaselineMethod* method) {
  if (text == "icp")
    *method = BaselineMethod::kIcp;
  else if (text == "gicp")
    *method = BaselineMethod::kGicp;
  else if (text == "ndt")
    *method = BaselineMethod::kNdt;
  else
    return false;
  return true;
}

const char* toString(BaselineMethod method) {
  switch (method) {
    case BaselineMethod::kIcp:
      return "icp";
    case BaselineMethod::kGicp:
      return "gicp";
    case BaselineMethod::kNdt:
      return "ndt";
  }
  return "unknown";
}

BaselineResult runBaseline(BaselineMethod method, const PointList& target_points,
                           const PointList& source_points,
                           const Eigen::Isometry3d& T_target_source_initial,
                           const BaselineParameters& p) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  BaselineResult failed;
  failed.T_target_source = T_target_source_initial;
  try {
    const Cloud::Ptr target = toPcl(target_points, p.target_voxel_size);
    const Cloud::Ptr source = toPcl(source_points, p.source_voxel_size);
    if (target->size() < 3 || source->size() < 3) return failed;
    switch (method) {
      case BaselineMethod::kIcp: {
        pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> icp;
        icp.setMaxCorrespondenceDistance(p.max_correspondence_distance);
        icp.setMaximumIterations(p.max_iterations);
        icp.setTransformationEpsilon(p.transformation_epsilon);
        return alignWith(&icp, target, source, T_target_source_initial);
      }
      case BaselineMethod::kGicp: {
        pcl::GeneralizedIterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> gicp;
        gicp.setMaxCorrespondenceDistance(p.max_correspondence_distance);
        gicp.setMaximumIterations(p.max_iterations);
        gicp.setTransformationEpsilon(p.transformation_epsilon);
        return alignWith(&gicp, target, source, T_target_source_initial);
      }
      case BaselineMethod::kNdt: {
        pcl::NormalDistributionsTransform<pcl::PointXYZ, pcl::PointXYZ> ndt;
        ndt.setResolution(static_cast<float>(p.ndt_resolution));
        ndt.setStepSize(p.ndt_step_size);
        ndt.setMaximumIterations(p.max_iterations);
        ndt.setTransformationEpsilon(p.ndt_transformation_epsilon);
        return alignWith(&ndt, target, source, T_target_source_initial);
      }
    }
  } catch (const std::exception&) {
    return failed;
  }
  return failed;
}

}  // namespace pda_registration

#pragma once
// A registration case on disk, the layout of ../shared/data/<case>/ and of pda_simulate's output:
// target.pcd|ply (dense), source.pcd|ply (sparse), T_target_source.txt (4x4 row-major,
// p_target = T * p_source).

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

struct CaseFolder {
  PointList target, source;
  Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();
};

/// Loads all three files (each cloud as .pcd, else .ply); false with a one-line reason.
bool loadCaseFolder(const std::string& directory, CaseFolder* loaded, std::string* error);

/// Every sub-folder of `data` that holds a T_target_source.txt, in name order (empty when none or
/// when `data` cannot be read).
std::vector<std::string> listCaseFolders(const std::string& data);

}  // namespace pda_registration

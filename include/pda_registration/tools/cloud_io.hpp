#pragma once
// Reading point clouds from PCD and PLY files into the core's point list.

#include <string>

#include "pda_registration/core/point_list.hpp"

namespace pda_registration {

/// Loads x, y, z of every point (NaNs kept: the core drops and counts them). The format is taken
/// from the extension (.pcd or .ply). On failure returns false with a one-line reason.
bool loadPointCloudFile(const std::string& path, PointList* points, std::string* error);

/// Writes a binary PCD of the points (used for aligned clouds and simulated maps).
bool savePointCloudFile(const std::string& path, const PointList& points, std::string* error);

}  // namespace pda_registration

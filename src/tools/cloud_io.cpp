#include "pda_registration/tools/cloud_io.hpp"

#include <pcl/PCLPointCloud2.h>
#include <pcl/common/io.h>
#include <pcl/console/print.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cctype>
#include <fstream>

#include "pda_registration/tools/pcd_header.hpp"

namespace pda_registration {
namespace {

std::string lowerCaseExtension(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos) return "";
  std::string extension = path.substr(dot + 1);
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

bool hasField(const pcl::PCLPointCloud2& cloud, const std::string& name) {
  return std::any_of(cloud.fields.begin(), cloud.fields.end(),
                     [&name](const pcl::PCLPointField& f) { return f.name == name; });
}

}  // namespace

bool loadPointCloudFile(const std::string& path, PointList* points, std::string* error) {
  // PCL prints its own diagnostics to stderr; the caller reports one clear line instead.
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  if (!std::ifstream(path).good()) {
    *error = "cannot open '" + path + "'";
    return false;
  }
  const std::string extension = lowerCaseExtension(path);
  pcl::PCLPointCloud2 blob;
  int status = -1;
  try {
    if (extension == "pcd") {
      std::string header_error;
      if (!checkPcdHeader(path, &header_error)) {
        *error = "'" + path + "': not a readable pcd point cloud (" + header_error + ")";
        return false;
      }
      status = pcl::io::loadPCDFile(path, blob);
    } else if (extension == "ply") {
      status = pcl::io::loadPLYFile(path, blob);
    } else {
      *error = "'" + path + "': unknown cloud format (expected .pcd or .ply)";
      return false;
    }
  } catch (const std::exception& e) {
    *error = "'" + path + "': " + e.what();
    return false;
  }
  if (status < 0) {
    *error = "'" + path + "': not a readable " + extension + " point cloud";
    return false;
  }
  if (!hasField(blob, "x") || !hasField(blob, "y") || !hasField(blob, "z")) {
    *error = "'" + path + "': the cloud has no x, y, z fields";
    return false;
  }
  if (blob.data.size() < static_cast<size_t>(blob.width) * blob.height * blob.point_step) {
    *error = "'" + path + "': the point data is shorter than its header says";
    return false;
  }
  pcl::PointCloud<pcl::PointXYZ> cloud;
  pcl::fromPCLPointCloud2(blob, cloud);
  points->clear();
  points->reserve(cloud.size());
  for (const pcl::PointXYZ& p : cloud.points) points->emplace_back(p.x, p.y, p.z);
  return true;
}

bool savePointCloudFile(const std::string& path, const PointList& points, std::string* error) {
  pcl::PointCloud<pcl::PointXYZ> cloud;
  cloud.reserve(points.size());
  for (const Point& p : points) {
    cloud.push_back(pcl::PointXYZ(static_cast<float>(p.x()), static_cast<float>(p.y()),
                                  static_cast<float>(p.z())));
  }
  if (cloud.empty() || pcl::io::savePCDFileBinary(path, cloud) < 0) {
    *error = cloud.empty() ? "refusing to write an empty cloud to '" + path + "'"
                           : "cannot write '" + path + "'";
    return false;
  }
  return true;
}

}  // namespace pda_registration

#include "pda_registration/tools/case_folder.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "pda_registration/core/transform_io.hpp"
#include "pda_registration/tools/cloud_io.hpp"

namespace pda_registration {
namespace {

// stem.pcd when it exists, else stem.ply.
bool loadCloud(const std::string& stem, PointList* points, std::string* error) {
  const std::string pcd = stem + ".pcd", ply = stem + ".ply";
  if (!std::ifstream(pcd).good() && !std::ifstream(ply).good()) {
    *error = "neither '" + pcd + "' nor '" + ply + "' can be opened";
    return false;
  }
  return loadPointCloudFile(std::ifstream(pcd).good() ? pcd : ply, points, error);
}

}  // namespace

bool loadCaseFolder(const std::string& directory, CaseFolder* loaded, std::string* error) {
  const std::string base = directory + "/";
  return loadCloud(base + "target", &loaded->target, error) &&
         loadCloud(base + "source", &loaded->source, error) &&
         readTransformFile(base + "T_target_source.txt", &loaded->T_target_source, error);
}

std::vector<std::string> listCaseFolders(const std::string& data) {
  std::vector<std::string> cases;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(data, error)) {
    if (std::filesystem::exists(entry.path() / "T_target_source.txt")) {
      cases.push_back(entry.path().filename().string());
    }
  }
  std::sort(cases.begin(), cases.end());
  return cases;
}

}  // namespace pda_registration

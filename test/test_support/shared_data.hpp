#pragma once
// Access to the real clouds in ../shared/data (read in place, never copied). PDA_DATA_DIR in the
// environment overrides the directory configured at build time.

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "pda_registration/core/point_list.hpp"
#include "pda_registration/tools/case_folder.hpp"

namespace pda_registration {
namespace testing_support {

struct SharedCase : CaseFolder {
  std::string name;
};

std::string sharedDataDirectory();
/// The case names the tests expect to find (every case of the shared data README).
std::vector<std::string> sharedCaseNames();
/// Loads target.pcd, source.pcd and T_target_source.txt; false with a reason on failure.
bool loadSharedCase(const std::string& name, SharedCase* shared_case, std::string* error);

}  // namespace testing_support
}  // namespace pda_registration

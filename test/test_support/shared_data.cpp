#include "test_support/shared_data.hpp"

#include <cstdlib>

#include "pda_registration/core/transform_io.hpp"
#include "pda_registration/tools/cloud_io.hpp"

namespace pda_registration {
namespace testing_support {

std::string sharedDataDirectory() {
  const char* from_environment = std::getenv("PDA_DATA_DIR");
  return from_environment && *from_environment ? from_environment : PDA_DATA_DIR;
}

std::vector<std::string> sharedCaseNames() {
  return {"campus_hdl32", "factory_p64", "kinect_pairwise", "room_scan"};
}

bool loadSharedCase(const std::string& name, SharedCase* c, std::string* error) {
  const std::string directory = sharedDataDirectory() + "/" + name + "/";
  c->name = name;
  return loadPointCloudFile(directory + "target.pcd", &c->target, error) &&
         loadPointCloudFile(directory + "source.pcd", &c->source, error) &&
         readTransformFile(directory + "T_target_source.txt", &c->T_target_source, error);
}

}  // namespace testing_support
}  // namespace pda_registration

#include "test_support/shared_data.hpp"

#include <cstdlib>

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
  c->name = name;
  return loadCaseFolder(sharedDataDirectory() + "/" + name, c, error);
}

}  // namespace testing_support
}  // namespace pda_registration

#pragma once
// Live parameters to change, gathered into one dynamic_reconfigure request that
// NodeletHarness::reconfigure sends.

#include <dynamic_reconfigure/Config.h>

#include <string>

namespace pda_registration {
namespace testing_support {

/// A dynamic_reconfigure request built up one parameter at a time:
/// harness.reconfigure(ParameterChange().set("k", 3).set("solver", "ceres")).
class ParameterChange {
 public:
  ParameterChange& set(const std::string& name, bool value);
  ParameterChange& set(const std::string& name, int value);
  ParameterChange& set(const std::string& name, double value);
  ParameterChange& set(const std::string& name, const std::string& value);
  ParameterChange& set(const std::string& name, const char* value) {
    return set(name, std::string(value));
  }
  const dynamic_reconfigure::Config& config() const { return config_; }

 private:
  dynamic_reconfigure::Config config_;
};

}  // namespace testing_support
}  // namespace pda_registration

#include "parameter_change.hpp"

namespace pda_registration {
namespace testing_support {

namespace {
template <class Parameter, class Value>
void addParameter(std::vector<Parameter>* list, const std::string& name, const Value& value) {
  Parameter parameter;
  parameter.name = name;
  parameter.value = value;
  list->push_back(parameter);
}
}  // namespace

ParameterChange& ParameterChange::set(const std::string& name, bool value) {
  addParameter(&config_.bools, name, value);
  return *this;
}

ParameterChange& ParameterChange::set(const std::string& name, int value) {
  addParameter(&config_.ints, name, value);
  return *this;
}

ParameterChange& ParameterChange::set(const std::string& name, double value) {
  addParameter(&config_.doubles, name, value);
  return *this;
}

ParameterChange& ParameterChange::set(const std::string& name, const std::string& value) {
  addParameter(&config_.strs, name, value);
  return *this;
}

}  // namespace testing_support
}  // namespace pda_registration

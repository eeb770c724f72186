#include "test_support/traced_alignment.hpp"

#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/perturbation.hpp"

namespace pda_registration {
namespace testing_support {

TracedAlignment alignTraced(const simulation::SimulatedMaps& maps, double degrees, double metres,
                            uint64_t seed, const RegistrationParameters& parameters) {
  TracedAlignment traced;
  PdaRegistration registration(parameters);
  AlignmentTrace trace;
  trace.run = [&traced](const RunRecord& r) {
    if (std::string(r.attempt) == "first") traced.first_runs.push_back(r);
    traced.runs.push_back(r);
  };
  trace.attempt = [&traced](const AttemptRecord& a) { traced.attempts.push_back(a); };
  registration.setTrace(trace);
  EXPECT_TRUE(registration.setTarget(maps.dense));
  traced.result = registration.align(
      maps.sparse, maps.T_target_source * randomPerturbation(degrees, metres, seed));
  return traced;
}

const AttemptRecord* attemptNamed(const TracedAlignment& traced, const std::string& name) {
  for (const AttemptRecord& a : traced.attempts) {
    if (name == a.attempt) return &a;
  }
  return nullptr;
}

::testing::AssertionResult ranAndWas(const TracedAlignment& traced, const std::string& name,
                                     bool adopted) {
  const AttemptRecord* a = attemptNamed(traced, name);
  if (a == nullptr) return ::testing::AssertionFailure() << "no " << name << " ran";
  if (a->adopted != adopted) {
    const char* outcome = a->adopted ? "adopted" : "dropped";
    return ::testing::AssertionFailure() << "the " << name << " was " << outcome << ": "
                                         << a->reason;
  }
  return ::testing::AssertionSuccess();
}

}  // namespace testing_support
}  // namespace pda_registration

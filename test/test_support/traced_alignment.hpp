#pragma once
// One alignment of simulated maps with its trace kept (alignment_trace.hpp): which attempts ran,
// which one align() adopted, and the first attempt's runs. Shared by the tests of the attempts
// after the first (second starts, the near search).

#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "pda_registration/core/alignment_trace.hpp"
#include "pda_registration/core/registration_parameters.hpp"
#include "pda_registration/core/registration_result.hpp"
#include "pda_registration/simulation/map_simulation.hpp"

namespace pda_registration {
namespace testing_support {

struct TracedAlignment {
  std::vector<RunRecord> first_runs;  ///< the runs of the attempt named "first"
  std::vector<RunRecord> runs;        ///< every attempt's runs, in order
  std::vector<AttemptRecord> attempts;
  RegistrationResult result;
};

/// Aligns maps.sparse to maps.dense from the ground truth perturbed by `degrees` / `metres`
/// (seeded), tracing it.
TracedAlignment alignTraced(const simulation::SimulatedMaps& maps, double degrees, double metres,
                            uint64_t seed,
                            const RegistrationParameters& parameters = RegistrationParameters());

/// The first attempt named `name`, or null.
const AttemptRecord* attemptNamed(const TracedAlignment& traced, const std::string& name);

/// Whether an attempt named `name` ran and align() adopted it (`adopted`) or dropped it.
::testing::AssertionResult ranAndWas(const TracedAlignment& traced, const std::string& name,
                                     bool adopted);

}  // namespace testing_support
}  // namespace pda_registration

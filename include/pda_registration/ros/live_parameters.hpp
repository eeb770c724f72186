#pragma once
// The run-time tunable parameters: one dynamic_reconfigure config mapped onto the core's
// structs. Applied by the worker at the start of each alignment.

#include <pda_registration/PdaRegistrationConfig.h>

#include "pda_registration/core/alignment_gate.hpp"
#include "pda_registration/core/registration_parameters.hpp"

namespace pda_registration {

struct LiveParameters {
  RegistrationParameters registration;
  AcceptanceThresholds acceptance;
  double min_interval = 0.0;  ///< [s]
  size_t max_markers = 20000;
  /// Index a dense map much finer than the sparse clouds as its representative subset at their
  /// sample spacing (core/representative_subset.hpp).
  bool dense_subset = true;
  /// Start each alignment from the seed corrected by the last accepted correction
  /// (core/warm_start.hpp), unless the node's own tf edge is part of the seed.
  bool warm_start = true;
  /// The part of the sparse clouds' period an alignment may take (ros/rate_budget.hpp); 0: the
  /// budget is max_source_points.
  double alignment_share = 0.5;
  /// A warm alignment still moving after this many periods of the sparse clouds is abandoned
  /// (not published); 0: no limit. Alignments from the seed are never cut, nor the one after five
  /// cut in a row.
  double deadline_periods = 1.0;
};

LiveParameters liveParametersFrom(const PdaRegistrationConfig& config);

}  // namespace pda_registration

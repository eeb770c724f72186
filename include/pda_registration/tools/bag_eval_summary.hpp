#pragma once
// pda_bag_eval's summary: one line per parameter set, ranked best first. With ground truth by
// success rate (eq. 22 below a threshold), then median eq. 22; without it by converged fraction,
// then median inlier fraction, then median time.

#include <string>
#include <vector>

#include "pda_registration/tools/bag_eval_row.hpp"
#include "pda_registration/tools/bag_parameter_grid.hpp"

namespace pda_registration {

struct SetSummary {
  ParameterSet set;
  size_t messages = 0;
  size_t converged = 0;
  size_t successes = 0;  ///< eq. 22 below the threshold (ground truth only)
  double median_eq22 = 0.0, max_eq22 = 0.0;
  double median_rotation_deg = 0.0, median_translation = 0.0;
  double median_inlier_fraction = 0.0, median_sigma = 0.0, median_runs = 0.0;
  double median_time_ms = 0.0;
};

/// Summaries of every set over its rows, best first (ties keep the set order).
std::vector<SetSummary> rankSets(const std::vector<ParameterSet>& sets,
                                 const std::vector<EvaluationRow>& rows, bool ground_truth,
                                 double success_threshold);

/// The ranked summaries as a markdown table (header included), newline-terminated.
std::string summaryTable(const std::vector<SetSummary>& ranked, bool ground_truth,
                         double success_threshold);

}  // namespace pda_registration

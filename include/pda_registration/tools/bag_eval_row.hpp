#pragma once
// One outcome of pda_bag_eval, a parameter set on one sparse map message, and its CSV form.

#include <string>

#include "pda_registration/core/error_metrics.hpp"
#include "pda_registration/core/registration_result.hpp"
#include "pda_registration/tools/bag_parameter_grid.hpp"

namespace pda_registration {

struct EvaluationRow {
  int set_id = 0;
  int message = 0;     ///< 1-based index among the bag's sparse map messages
  double stamp = 0.0;  ///< [s] the sparse map's stamp
  std::string seed;    ///< "at_stamp" or "latest": which tf gave the initial guess
  RegistrationResult result;
  bool has_ground_truth = false;
  PoseError error;       ///< the estimate against the ground truth
  PoseError seed_error;  ///< the seed against the ground truth
};

/// The column names, newline-terminated; the error columns only with ground truth.
std::string csvHeader(bool ground_truth);
/// One row in the header's columns, newline-terminated; text fields quoted when needed.
std::string csvLine(const ParameterSet& set, const EvaluationRow& row, bool ground_truth);

}  // namespace pda_registration

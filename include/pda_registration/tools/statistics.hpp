#pragma once
// Order statistics for the tools' reports.

#include <vector>

namespace pda_registration {

/// Median (mean of the middle two for an even count); 0 for no values.
double median(std::vector<double> values);
/// Nearest-rank percentile, q in [0, 1]; 0 for no values.
double percentile(std::vector<double> values, double q);

}  // namespace pda_registration

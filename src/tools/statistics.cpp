#include "pda_registration/tools/statistics.hpp"

#include <algorithm>

namespace pda_registration {

double median(std::vector<double> values) {
  const size_t n = values.size();
  if (n == 0) return 0.0;
  std::sort(values.begin(), values.end());
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const double clamped = std::min(std::max(q, 0.0), 1.0);
  return values[static_cast<size_t>(clamped * static_cast<double>(values.size() - 1) + 0.5)];
}

}  // namespace pda_registration

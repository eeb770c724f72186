#include "pda_registration/tools/bag_eval_summary.hpp"

#include <algorithm>
#include <iomanip>
#include <map>
#include <sstream>

#include "pda_registration/tools/statistics.hpp"

namespace pda_registration {
namespace {

// a/b > c/d without division (every count is a whole number of messages).
bool largerFraction(size_t a, size_t b, size_t c, size_t d) { return a * d > c * b; }
bool sameFraction(size_t a, size_t b, size_t c, size_t d) { return a * d == c * b; }

bool betterWithGroundTruth(const SetSummary& a, const SetSummary& b) {
  if (!sameFraction(a.successes, a.messages, b.successes, b.messages)) {
    return largerFraction(a.successes, a.messages, b.successes, b.messages);
  }
  if (a.median_eq22 != b.median_eq22) return a.median_eq22 < b.median_eq22;
  return a.median_time_ms < b.median_time_ms;
}

bool betterWithoutGroundTruth(const SetSummary& a, const SetSummary& b) {
  if (!sameFraction(a.converged, a.messages, b.converged, b.messages)) {
    return largerFraction(a.converged, a.messages, b.converged, b.messages);
  }
  if (a.median_inlier_fraction != b.median_inlier_fraction) {
    return a.median_inlier_fraction > b.median_inlier_fraction;
  }
  return a.median_time_ms < b.median_time_ms;
}

}  // namespace

std::vector<SetSummary> rankSets(const std::vector<ParameterSet>& sets,
                                 const std::vector<EvaluationRow>& rows, bool ground_truth,
                                 double success_threshold) {
  std::map<int, std::vector<const EvaluationRow*>> rows_by_set;
  for (const EvaluationRow& row : rows) rows_by_set[row.set_id].push_back(&row);

  std::vector<SetSummary> summaries;
  for (const ParameterSet& set : sets) {
    SetSummary s;
    s.set = set;
    std::vector<double> eq22, rotation, translation, inliers, sigma, runs, time;
    for (const EvaluationRow* row : rows_by_set[set.id]) {
      const RegistrationResult& r = row->result;
      ++s.messages;
      s.converged += r.converged ? 1 : 0;
      inliers.push_back(r.inlier_fraction);
      sigma.push_back(r.sigma);
      runs.push_back(r.runs);
      time.push_back(r.time_ms);
      if (ground_truth) {
        s.successes += row->error.mean_distance < success_threshold ? 1 : 0;
        eq22.push_back(row->error.mean_distance);
        rotation.push_back(row->error.rotation_deg);
        translation.push_back(row->error.translation);
      }
    }
    s.median_eq22 = median(eq22);
    s.max_eq22 = eq22.empty() ? 0.0 : *std::max_element(eq22.begin(), eq22.end());
    s.median_rotation_deg = median(rotation);
    s.median_translation = median(translation);
    s.median_inlier_fraction = median(inliers);
    s.median_sigma = median(sigma);
    s.median_runs = median(runs);
    s.median_time_ms = median(time);
    summaries.push_back(s);
  }
  std::stable_sort(summaries.begin(), summaries.end(),
                   ground_truth ? betterWithGroundTruth : betterWithoutGroundTruth);
  return summaries;
}

std::string summaryTable(const std::vector<SetSummary>& ranked, bool ground_truth,
                         double success_threshold) {
  std::ostringstream table;
  table << "| rank | set";
  for (const std::string& flag : gridFlagNames()) table << " | " << flag;
  if (ground_truth) {
    table << " | success (eq.22 < " << success_threshold
          << " m) | median eq.22 [m] | max eq.22 [m] | median rot [deg] | median trans [m]";
  }
  table << " | converged | median inliers | median sigma [m] | median runs | median time [ms] |\n";
  const size_t columns = 2 + gridFlagNames().size() + (ground_truth ? 5 : 0) + 5;
  table << '|';
  for (size_t c = 0; c < columns; ++c) table << "---:|";
  table << '\n';

  int rank = 0;
  for (const SetSummary& s : ranked) {
    table << "| " << ++rank << " | " << s.set.id;
    for (const std::string& value : s.set.values) table << " | " << value;
    table << std::fixed;
    if (ground_truth) {
      table << " | " << s.successes << "/" << s.messages << " | " << std::setprecision(4)
            << s.median_eq22 << " | " << s.max_eq22 << " | " << std::setprecision(3)
            << s.median_rotation_deg << " | " << std::setprecision(4) << s.median_translation;
    }
    table << " | " << s.converged << "/" << s.messages << " | " << std::setprecision(3)
          << s.median_inlier_fraction << " | " << std::setprecision(4) << s.median_sigma << " | "
          << std::setprecision(1) << s.median_runs << " | " << s.median_time_ms << " |\n";
    table << std::defaultfloat;
  }
  return table.str();
}

}  // namespace pda_registration

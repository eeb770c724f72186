#include "pda_registration/tools/bag_eval_summary.hpp"

#include <algorithm>
#include <iomanip>
#include <map>
#include <sstream>

#include "pda_registration/tools/settings_flags.hpp"
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

std::string gridDescription(const CommandLine& cl, const std::vector<ParameterSet>& sets) {
  std::ostringstream text;
  text << sets.size() << " parameter set" << (sets.size() == 1 ? "" : "s") << ":";
  for (size_t a = 0; a < gridFlagNames().size(); ++a) {
    std::vector<std::string> values;
    for (const ParameterSet& set : sets) {
      if (std::find(values.begin(), values.end(), set.values[a]) == values.end()) {
        values.push_back(set.values[a]);
      }
    }
    text << " --" << gridFlagNames()[a] << ' ';
    for (size_t i = 0; i < values.size(); ++i) text << (i ? "," : "") << values[i];
  }
  // The other registration flags the user changed, so the summary says what was run.
  for (const std::string& flag : settingsFlagNames()) {
    const bool grid =
        std::find(gridFlagNames().begin(), gridFlagNames().end(), flag) != gridFlagNames().end();
    if (!grid && cl.has(flag)) text << " --" << flag << ' ' << cl.text(flag);
  }
  return text.str();
}

std::string summaryMarkdown(const BagEvalOptions& options, const BagMaps& bag,
                            const BagTransforms& transforms, const CommandLine& cl,
                            const std::vector<ParameterSet>& sets,
                            const std::vector<EvaluationRow>& rows, const RunCounts& counts) {
  const bool ground_truth = transforms.hasGroundTruth();
  std::ostringstream md;
  md << "## pda_bag_eval: " << options.bag_path << "\n\n";
  md << "- maps: " << options.topics.sparse << " (" << bag.messageCount(options.topics.sparse)
     << " messages, " << counts.evaluated << " evaluated, " << counts.skipped.size()
     << " skipped) onto " << options.topics.dense << " (" << bag.messageCount(options.topics.dense)
     << " messages, " << counts.targets_indexed << " indexed in " << std::fixed
     << std::setprecision(0) << counts.index_ms << " ms)\n";
  md << "- seed: tf (" << counts.seeds_at_stamp << " at the sparse map's stamp, "
     << counts.seeds_latest << " latest before it)";
  if (ground_truth) {
    md << ", median seed eq. 22 " << std::setprecision(4) << median(counts.seed_eq22) << " m";
  }
  md << std::defaultfloat << "\n";
  if (ground_truth) {
    md << "- ground truth: " << options.ground_truth_topic << "; ranked by success (eq. 22 < "
       << options.success_threshold << " m), then median eq. 22\n";
  } else {
    md << "- ground truth: none"
       << (options.ground_truth_topic.empty()
               ? std::string(" (ignored)")
               : " (no topic '" + options.ground_truth_topic + "' in the bag)")
       << "; ranked by converged fraction, then median inlier fraction, then median time\n";
  }
  md << "- " << gridDescription(cl, sets) << "\n\n";
  md << summaryTable(rankSets(sets, rows, ground_truth, options.success_threshold), ground_truth,
                     options.success_threshold);
  if (!counts.skipped.empty()) {
    md << "\nSkipped:\n";
    for (const std::string& skipped : counts.skipped) md << "- " << skipped << "\n";
  }
  return md.str();
}

}  // namespace pda_registration

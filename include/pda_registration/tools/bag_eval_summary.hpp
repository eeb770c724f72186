#pragma once
// pda_bag_eval's summary: a preamble saying what was run (bag, topics, seeds, ground truth, grid),
// then one line per parameter set, ranked best first. With ground truth by success rate (eq. 22
// below a threshold), then median eq. 22; without it by converged fraction, then median inlier
// fraction, then median time.

#include <limits>
#include <string>
#include <vector>

#include "pda_registration/tools/bag_eval_row.hpp"
#include "pda_registration/tools/bag_maps.hpp"
#include "pda_registration/tools/bag_parameter_grid.hpp"
#include "pda_registration/tools/bag_transforms.hpp"
#include "pda_registration/tools/command_line.hpp"

namespace pda_registration {

/// What pda_bag_eval was asked to do, from its flags.
struct BagEvalOptions {
  std::string bag_path;
  MapTopics topics;
  std::string ground_truth_topic = "/ground_truth";
  bool ground_truth_topic_given = false;
  double success_threshold = 0.05;
  int max_messages = std::numeric_limits<int>::max();
  std::string csv_path, summary_path;
};

/// What the run did besides the rows, for the summary's preamble.
struct RunCounts {
  size_t evaluated = 0, seeds_at_stamp = 0, seeds_latest = 0, targets_indexed = 0;
  double index_ms = 0.0;
  std::vector<double> seed_eq22;
  std::vector<std::string> skipped;  ///< "message N (t = ...): why"
};

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

/// "N parameter sets: --k 1,5 --nu 5,inf ...", with the other registration flags the user set.
std::string gridDescription(const CommandLine& cl, const std::vector<ParameterSet>& sets);

/// The whole summary as markdown: the preamble, the ranked table and the skipped messages.
std::string summaryMarkdown(const BagEvalOptions& options, const BagMaps& bag,
                            const BagTransforms& transforms, const CommandLine& cl,
                            const std::vector<ParameterSet>& sets,
                            const std::vector<EvaluationRow>& rows, const RunCounts& counts);

}  // namespace pda_registration

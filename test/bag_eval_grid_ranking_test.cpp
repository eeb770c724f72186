// pda_bag_eval's parameter grid and its ranking of the sets, on their own (no bag): every
// combination of the grid's flags, first flag slowest; the ranking with and without ground truth.
// The tool run on bags: bag_eval_test.cpp.
#include <gtest/gtest.h>

#include <limits>
#include <set>
#include <string>
#include <vector>

#include "pda_registration/tools/bag_eval_summary.hpp"
#include "pda_registration/tools/bag_parameter_grid.hpp"
#include "pda_registration/tools/command_line.hpp"
#include "pda_registration/tools/settings_flags.hpp"
#include "test_support/bag_eval_output.hpp"

namespace pda_registration {
namespace {

using testing_support::summaryRows;

std::vector<ParameterSet> gridFrom(std::vector<const char*> arguments, std::string* error) {
  arguments.insert(arguments.begin(), "pda_bag_eval");
  std::set<std::string> flags = settingsFlagNames();
  CommandLine cl(flags, {});
  std::vector<ParameterSet> sets;
  if (!cl.parse(static_cast<int>(arguments.size()), arguments.data()) ||
      !readParameterGrid(&cl, &sets)) {
    *error = cl.error();
  }
  return sets;
}

TEST(ParameterGrid, ExpandsEveryCombinationFirstFlagSlowest) {
  std::string error;
  const auto sets =
      gridFrom({"--k", "1,5", "--nu", "5,inf", "--radius", "0.5,0.50", "--runs", "7"}, &error);
  ASSERT_TRUE(error.empty()) << error;
  ASSERT_EQ(sets.size(), 4u);  // the duplicate radius counts once
  const std::vector<std::pair<int, double>> expected = {
      {1, 5.0},
      {1, std::numeric_limits<double>::infinity()},
      {5, 5.0},
      {5, std::numeric_limits<double>::infinity()}};
  for (size_t i = 0; i < sets.size(); ++i) {
    EXPECT_EQ(sets[i].id, static_cast<int>(i) + 1);
    EXPECT_EQ(sets[i].parameters.k, expected[i].first);
    EXPECT_EQ(sets[i].parameters.nu, expected[i].second);
    EXPECT_EQ(sets[i].parameters.radius, 0.5);
    EXPECT_EQ(sets[i].parameters.max_runs, 7);  // a single-value flag applies to every set
    EXPECT_EQ(sets[i].values.size(), gridFlagNames().size());
  }
  EXPECT_EQ(sets[1].values[1], "inf");

  const auto defaults = gridFrom({}, &error);
  ASSERT_EQ(defaults.size(), 1u);
  EXPECT_EQ(defaults[0].parameters.k, RegistrationParameters().k);

  gridFrom({"--k", "1,x"}, &error);
  EXPECT_NE(error.find("--k: 'x'"), std::string::npos) << error;
}

EvaluationRow row(int set_id, double eq22, bool converged, double inliers, double time_ms) {
  EvaluationRow r;
  r.set_id = set_id;
  r.has_ground_truth = true;
  r.error.mean_distance = eq22;
  r.result.converged = converged;
  r.result.inlier_fraction = inliers;
  r.result.time_ms = time_ms;
  return r;
}

TEST(SummaryRanking, SuccessThenMedianErrorOrConvergedThenInliersThenTime) {
  std::vector<ParameterSet> sets(4);
  for (int i = 0; i < 4; ++i) {
    sets[i].id = i + 1;
    sets[i].values = {std::to_string(i + 1), "5", "1", "1000"};
  }
  const std::vector<EvaluationRow> rows = {
      row(1, 0.010, true, 0.9, 10),  row(1, 0.200, true, 0.9, 10),   // 1/2 successes
      row(2, 0.030, false, 0.5, 10), row(2, 0.040, false, 0.5, 10),  // 2/2, median 0.035
      row(3, 0.020, true, 0.6, 50),  row(3, 0.045, true, 0.6, 50),   // 2/2, median 0.0325
      row(4, 0.500, true, 0.6, 20),  row(4, 0.600, true, 0.6, 20)};  // 0/2
  std::vector<int> order;
  for (const SetSummary& s : rankSets(sets, rows, true, 0.05)) order.push_back(s.set.id);
  EXPECT_EQ(order, (std::vector<int>{3, 2, 1, 4}));

  // Without ground truth: converged 2/2 first (1, 3, 4), by inliers (1), then time (4 before 3).
  order.clear();
  const auto ranked = rankSets(sets, rows, false, 0.05);
  for (const SetSummary& s : ranked) order.push_back(s.set.id);
  EXPECT_EQ(order, (std::vector<int>{1, 4, 3, 2}));
  EXPECT_EQ(summaryRows(summaryTable(ranked, false, 0.05)).size(), 4u);
}

}  // namespace
}  // namespace pda_registration

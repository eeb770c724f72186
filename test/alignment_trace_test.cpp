// The alignment trace (alignment_trace.hpp) on a real case: it changes no answer, its runs add up
// to the result's, and its attempts end on the one align() answered with.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "pda_registration/core/pda_registration.hpp"
#include "pda_registration/core/perturbation.hpp"
#include "test_support/shared_data.hpp"

namespace pda_registration {
namespace {

using testing_support::loadSharedCase;
using testing_support::SharedCase;

struct Traced {
  std::vector<RunRecord> runs;
  std::vector<AttemptRecord> attempts;
  RegistrationResult result;
};

Traced alignTraced(const PointList& target, const PointList& source,
                   const Eigen::Isometry3d& initial) {
  Traced traced;
  PdaRegistration registration((RegistrationParameters()));
  AlignmentTrace trace;
  trace.run = [&traced](const RunRecord& r) { traced.runs.push_back(r); };
  trace.attempt = [&traced](const AttemptRecord& a) { traced.attempts.push_back(a); };
  registration.setTrace(trace);
  EXPECT_TRUE(registration.setTarget(target));
  traced.result = registration.align(source, initial);
  return traced;
}

RegistrationResult alignUntraced(const PointList& target, const PointList& source,
                                 const Eigen::Isometry3d& initial) {
  PdaRegistration registration((RegistrationParameters()));
  EXPECT_TRUE(registration.setTarget(target));
  return registration.align(source, initial);
}

int stageOrder(const std::string& stage) {
  if (stage == "approach") return 0;
  if (stage == "settle") return 1;
  if (stage == "refine") return 2;
  return -1;
}

// The runs of one attempt: numbered from 1, stages in order, the refine radius never wider.
void expectWellFormedRuns(std::vector<RunRecord>::const_iterator begin,
                          std::vector<RunRecord>::const_iterator end, double radius) {
  ASSERT_TRUE(begin != end) << "an attempt without runs";
  const std::string attempt = begin->attempt;
  int expected_run = 1;
  int last_stage = 0;
  for (auto r = begin; r != end; ++r) {
    EXPECT_EQ(std::string(r->attempt), attempt);
    EXPECT_EQ(r->run, expected_run++) << attempt;
    const int stage = stageOrder(r->stage);
    EXPECT_GE(stage, last_stage) << attempt << " run " << r->run << ": " << r->stage;
    last_stage = stage;
    EXPECT_GT(r->points, 0u);
    EXPECT_GT(r->sigma, 0.0);
    EXPECT_GT(r->em_iterations, 0);
    EXPECT_LE(r->radius, radius + 1e-12);
    EXPECT_GE(r->step_translation, 0.0);
  }
}

TEST(AlignmentTrace, ChangesNothingAndItsRunsAddUpToTheResult) {
  SharedCase c;
  std::string error;
  ASSERT_TRUE(loadSharedCase("room_scan", &c, &error)) << error;
  const Eigen::Isometry3d initial = c.T_target_source * randomPerturbation(5.0, 0.25, 1);
  const Traced traced = alignTraced(c.target, c.source, initial);
  const RegistrationResult untraced = alignUntraced(c.target, c.source, initial);
  const RegistrationResult& r = traced.result;
  ASSERT_TRUE(r.converged) << r.reason;
  EXPECT_TRUE(r.T_target_source.matrix() == untraced.T_target_source.matrix());
  EXPECT_EQ(r.runs, untraced.runs);

  // Room_scan in its usual direction: one attempt, adopted, and every run is its.
  ASSERT_EQ(traced.attempts.size(), 1u);
  const AttemptRecord& first = traced.attempts.front();
  EXPECT_EQ(std::string(first.attempt), "first");
  EXPECT_TRUE(first.adopted);
  EXPECT_TRUE(first.converged);
  EXPECT_EQ(first.runs, r.runs);
  EXPECT_DOUBLE_EQ(first.sigma, r.sigma);
  ASSERT_EQ(traced.runs.size(), static_cast<size_t>(r.runs));
  expectWellFormedRuns(traced.runs.begin(), traced.runs.end(), RegistrationParameters().radius);
  int em_iterations = 0;
  for (const RunRecord& run : traced.runs) em_iterations += run.em_iterations;
  EXPECT_EQ(em_iterations, r.em_iterations);
  EXPECT_EQ(std::string(traced.runs.front().stage), "approach");
  EXPECT_LT(traced.runs.front().points, r.source_points_used);  // the approach subset
  EXPECT_EQ(std::string(traced.runs.back().stage), "refine");
  EXPECT_EQ(traced.runs.back().points, r.source_points_used);
  EXPECT_DOUBLE_EQ(traced.runs.back().sigma, r.sigma);
}

// The dense room as the source of its 16-row scan: the usual direction does not come to a fit,
// and align() tries further attempts. Each one is noted once, in order, after its own runs, and
// the answer is the last one adopted.
TEST(AlignmentTrace, NotesEveryAttemptAndAnswersWithTheLastAdopted) {
  SharedCase c;
  std::string error;
  ASSERT_TRUE(loadSharedCase("room_scan", &c, &error)) << error;
  const Eigen::Isometry3d truth = c.T_target_source.inverse();
  const Eigen::Isometry3d initial = truth * randomPerturbation(5.0, 0.25, 1);
  const Traced traced = alignTraced(c.source, c.target, initial);
  const RegistrationResult untraced = alignUntraced(c.source, c.target, initial);
  const RegistrationResult& r = traced.result;
  EXPECT_TRUE(r.T_target_source.matrix() == untraced.T_target_source.matrix());

  ASSERT_GE(traced.attempts.size(), 2u) << "room_scan reversed needed one attempt only";
  EXPECT_EQ(std::string(traced.attempts.front().attempt), "first");
  EXPECT_TRUE(traced.attempts.front().adopted);  // the answer until a later attempt replaces it
  EXPECT_FALSE(traced.attempts.front().converged);
  EXPECT_FALSE(traced.attempts.front().reason.empty());
  const AttemptRecord* answer = nullptr;
  std::set<std::string> seen;
  double last_time = 0.0;
  size_t next_run = 0;
  for (const AttemptRecord& a : traced.attempts) {
    EXPECT_TRUE(seen.insert(a.attempt).second || std::string(a.attempt) == "second start")
        << a.attempt << " noted twice";
    EXPECT_GE(a.time_ms, last_time);
    last_time = a.time_ms;
    EXPECT_EQ(a.converged, a.reason.empty()) << a.attempt << ": " << a.reason;
    // This attempt's runs come next in the run records, as many as it reports.
    const size_t first_run = next_run;
    while (next_run < traced.runs.size() &&
           std::string(traced.runs[next_run].attempt) == a.attempt &&
           (next_run == first_run || traced.runs[next_run].run > 1)) {
      ++next_run;
    }
    EXPECT_EQ(static_cast<int>(next_run - first_run), a.runs) << a.attempt;
    expectWellFormedRuns(traced.runs.begin() + static_cast<long>(first_run),
                         traced.runs.begin() + static_cast<long>(next_run),
                         RegistrationParameters().radius);
    if (a.adopted) answer = &a;
  }
  EXPECT_EQ(next_run, traced.runs.size()) << "runs outside any attempt";
  ASSERT_NE(answer, nullptr);
  EXPECT_EQ(answer->converged, r.converged);
  EXPECT_EQ(answer->runs, r.runs);
  EXPECT_TRUE(answer->T_target_source.isApprox(r.T_target_source, 1e-12));
  EXPECT_EQ(r.roles_swapped, std::string(answer->attempt) == "other direction");
  EXPECT_EQ(r.local_start, std::string(answer->attempt) == "local start");
  EXPECT_TRUE(r.converged) << r.reason;
}

}  // namespace
}  // namespace pda_registration

#include "pda_registration/core/pda_registration.hpp"

// The second starts (second_start.hpp), and after them a turned start (turned_start.hpp), as
// align() runs them: at the end of the first attempt, or earlier, once the first's refine runs
// leave nu at its floor, the mark of a false rest. On the RGB-D fragment pair of seed 5 from
// 20 deg the first attempt then still ran 10-12 refine runs (110-130 ms of a 560-700 ms
// alignment) into the rest the second start replaced.

#include <cmath>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "pda_registration/core/em_run.hpp"
#include "pda_registration/core/final_statistics.hpp"
#include "pda_registration/core/nested_alignment.hpp"
#include "pda_registration/core/turned_start.hpp"

namespace pda_registration {
namespace {

// The first result's basin (second_start.hpp) around T_found, from the points it ran on.
FirstResultBasin basinAround(const PointList& used, const Eigen::Isometry3d& T_found,
                             double final_radius) {
  FirstResultBasin basin;
  basin.T_found = T_found;
  basin.final_radius = final_radius;
  for (const Point& point : used) basin.centroid += point;
  basin.centroid /= static_cast<double>(used.size());
  for (const Point& point : used) basin.source_rms_radius += (point - basin.centroid).squaredNorm();
  basin.source_rms_radius = std::sqrt(basin.source_rms_radius / static_cast<double>(used.size()));
  return basin;
}

// Swaps two workspaces while it lives (a null `live`: nothing), so that an attempt run in between
// leaves the paused one's memory, candidate sets and search state as they were.
class WorkspaceSwap {
 public:
  WorkspaceSwap(RegistrationWorkspace* live, RegistrationWorkspace* spare)
      : live_(live), spare_(spare) {
    if (live_) std::swap(*live_, *spare_);
  }
  WorkspaceSwap(const WorkspaceSwap&) = delete;
  WorkspaceSwap& operator=(const WorkspaceSwap&) = delete;
  ~WorkspaceSwap() {
    if (live_) std::swap(*live_, *spare_);
  }

 private:
  RegistrationWorkspace* live_;
  RegistrationWorkspace* spare_;
};

}  // namespace

bool PdaRegistration::fitsMoreOfTheOverlap(const RegistrationResult& second,
                                           const Eigen::Isometry3d& T_first, double sigma_first,
                                           const TargetIndex& index) const {
  if (!second.converged || second.out_of_time) return false;
  const PointList& used = workspace_.source;
  const double yardstick = commonYardstick(parameters_, sigma_first, second.sigma);
  const auto supportAt = [&](const Eigen::Isometry3d& T) {
    return supportFractionAt(index, used, T, yardstick, parameters_.radius, parameters_.threads);
  };
  return secondStartIsBetter(second, supportAt(second.T_target_source), supportAt(T_first));
}

std::optional<Eigen::Isometry3d> PdaRegistration::turnedStart(
    const Eigen::Isometry3d& T_initial) const {
  const std::shared_ptr<const TargetIndex> index = target_map_.index();
  if (!index || workspace_.source.empty()) return std::nullopt;
  // Every 4th of the points the first attempt ran on: the test is a ranking, not a fit.
  PointList sample;
  for (size_t i = 0; i < workspace_.source.size(); i += 4) sample.push_back(workspace_.source[i]);
  const auto share = [&](const Eigen::Isometry3d& T) {
    return shareWithinReach(*index, sample, T, parameters_.radius, parameters_.threads);
  };
  std::array<Eigen::Isometry3d, kTurnDegrees.size()> turns;
  std::array<double, kTurnDegrees.size()> shares{};
  for (size_t i = 0; i < turns.size(); ++i) {
    turns[i] = turnedAboutSensor(T_initial, kTurnDegrees[i]);
    shares[i] = share(turns[i]);
  }
  const int chosen = turnToTry(shares, share(T_initial));
  if (chosen < 0) return std::nullopt;
  return turns[static_cast<size_t>(chosen)];
}

void PdaRegistration::runSecondStarts(
    const PointList& source, const Eigen::Isometry3d& T_initial,
    std::chrono::steady_clock::time_point started, const FirstResultBasin& basin,
    bool want_associations, bool in_spare_workspace,
    const std::function<bool(RegistrationResult*, Associations*)>& keep) {
  const Eigen::Isometry3d* tried = nullptr;
  const auto found_rotation = secondStartPoses(basin.T_found, T_initial, basin.centroid);
  std::vector<Eigen::Isometry3d> starts(found_rotation.begin(), found_rotation.end());
  const size_t found_rotation_starts = starts.size();
  if (const auto turned = turnedStart(T_initial)) starts.push_back(*turned);
  for (size_t i = 0; i < starts.size(); ++i) {
    const Eigen::Isometry3d& start = starts[i];
    // A start in the first result's basin would only find it again; one near the start just
    // tried is the same hypothesis.
    if (basin.contains(start) || (tried && basin.near(*tried, start))) continue;
    tried = &start;
    const NestedAlignment nested(&parameters_, started);
    const AttemptLabel label(
        &attempt_, attemptName(i < found_rotation_starts ? "second start" : "turned start"));
    if (!nested.timeLeft()) return;
    Associations second_associations;
    AttemptOptions options;
    options.abandon_in = &basin;
    if (i >= found_rotation_starts) options.fit_within_runs = kTurnedStartFitRuns;
    RegistrationResult second;
    {
      const WorkspaceSwap swap(in_spare_workspace ? &workspace_ : nullptr, &spare_workspace_);
      second = alignUnchecked(source, start, want_associations ? &second_associations : nullptr,
                              options);
    }
    if (keep(&second, &second_associations)) return;
  }
}

void PdaRegistration::trySecondStart(const PointList& source, const Eigen::Isometry3d& T_initial,
                                     std::chrono::steady_clock::time_point started,
                                     RegistrationResult* result, Associations* associations) {
  const PointList& used = workspace_.source;  // the points the first alignment ran on
  if (used.empty()) return;
  const FirstResultBasin basin = basinAround(
      used, result->T_target_source, refineRadius(parameters_, result->sigma * result->sigma));
  if (!secondStartWarranted(*result, parameters_, T_initial, basin.centroid, basin.final_radius)) {
    return;
  }
  runSecondStarts(source, T_initial, started, basin, associations != nullptr,
                  /*in_spare_workspace=*/false,
                  [&](RegistrationResult* second, Associations* second_associations) {
                    const bool better = fitsMoreOfTheOverlap(
                        *second, result->T_target_source, result->sigma, *target_map_.index());
                    traceAttempt(*second, better, started);
                    adoptNested(better, second, second_associations, result, associations);
                    return better;
                  });
}

bool PdaRegistration::secondStartsAtNuFloor(const PointList& source,
                                            const Eigen::Isometry3d& T_initial,
                                            std::chrono::steady_clock::time_point started,
                                            const EmState& first, const TargetIndex& first_index,
                                            bool want_associations, EarlySecondStarts* early) {
  const PointList& used = workspace_.source;  // the points the first attempt runs on
  if (used.empty() || early->tried) return false;
  // The test a converged first result meets (second_start.hpp), with the radius its next run
  // would search.
  RegistrationResult as_it_stands;
  as_it_stands.converged = true;
  as_it_stands.nu = first.nu;
  as_it_stands.T_target_source = first.T;
  const FirstResultBasin basin =
      basinAround(used, first.T, refineRadius(parameters_, first.sigma_squared));
  if (!secondStartWarranted(as_it_stands, parameters_, T_initial, basin.centroid,
                            basin.final_radius)) {
    return false;
  }
  early->tried = true;
  runSecondStarts(
      source, T_initial, started, basin, want_associations, /*in_spare_workspace=*/true,
      [&](RegistrationResult* second, Associations* second_associations) {
        if (!second->converged || second->out_of_time) {
          traceAttempt(*second, false, started);
          early->dropped_index_ms += second->target_index_ms;
          return false;
        }
        // The first's residuals are still wide here: the second's yardstick measures both.
        if (fitsMoreOfTheOverlap(*second, first.T, std::sqrt(first.sigma_squared), first_index)) {
          traceAttempt(*second, true, started);
          early->adopted = true;
          early->adopted_result = std::move(*second);
          early->adopted_associations = std::move(*second_associations);
          return true;
        }
        early->pending.push_back(std::move(*second));
        early->pending_associations.push_back(std::move(*second_associations));
        return false;
      });
  return early->adopted;
}

void PdaRegistration::settleEarlySecondStarts(const Eigen::Isometry3d& T_initial,
                                              std::chrono::steady_clock::time_point started,
                                              EarlySecondStarts* early, RegistrationResult* result,
                                              Associations* associations) {
  result->target_index_ms += early->dropped_index_ms;
  const PointList& used = workspace_.source;
  const std::shared_ptr<const TargetIndex> index = target_map_.index();
  bool warranted = false;
  if (!used.empty() && index) {
    const FirstResultBasin basin = basinAround(
        used, result->T_target_source, refineRadius(parameters_, result->sigma * result->sigma));
    warranted =
        secondStartWarranted(*result, parameters_, T_initial, basin.centroid, basin.final_radius);
  }
  bool adopted = false;
  for (size_t i = 0; i < early->pending.size(); ++i) {
    const bool better =
        !adopted && warranted &&
        fitsMoreOfTheOverlap(early->pending[i], result->T_target_source, result->sigma, *index);
    {
      // Noted once decided: its runs came before the first attempt's last ones.
      const AttemptLabel label(&attempt_, attemptName("second start"));
      traceAttempt(early->pending[i], better, started);
    }
    adoptNested(better, &early->pending[i], &early->pending_associations[i], result,
                associations);
    adopted = adopted || better;
  }
}

}  // namespace pda_registration

#include "pda_registration/core/pda_registration.hpp"

// The near search (near_search.hpp) as align() runs it: after the usual alignment and its
// fallbacks, where their answer is questionable or a kept local start, all of them once more from
// the seed.

#include <cstring>
#include <utility>
#include <vector>

#include "pda_registration/core/local_start.hpp"
#include "pda_registration/core/near_search.hpp"
#include "pda_registration/core/nested_alignment.hpp"

namespace pda_registration {

void PdaRegistration::tryNearSearch(const PointList& source, const Eigen::Isometry3d& T_initial,
                                    std::chrono::steady_clock::time_point started,
                                    RegistrationResult* result, Associations* associations) {
  if (!nearSearchWarranted(*result, questionable(*result, T_initial))) return;
  const bool usual_converged = result->converged;
  const NestedAlignment nested(&parameters_, started);
  // A converged result stands when there is no time to question it; a failed one says why.
  if (usual_converged ? !nested.timeLeft() : !nested.timeLeftOrNote("a near search", result)) {
    return;
  }
  // The usual answer's points and target, for the comparison (the near search re-aligns the same
  // source, so they are the ones it runs on too).
  const std::shared_ptr<const TargetIndex> usual_index = target_map_.index();
  Associations near_associations;
  std::vector<AttemptRecord> near_attempts;  // noted once it is known whether the answer is kept
  RegistrationResult near;
  UsualAnswer usual;
  usual.T_target_source = result->T_target_source;
  usual.sigma = result->sigma;
  {
    const AttemptLabel label(&attempt_, "near search");
    in_near_search_ = true;
    near_rejoined_ = false;
    deferred_attempts_ = trace_.attempt ? &near_attempts : nullptr;
    near = alignWithFallbacks(source, T_initial, started,
                              associations ? &near_associations : nullptr, /*near_search=*/true,
                              nearSearchCanRejoin(*result) ? &usual : nullptr);
    in_near_search_ = false;
    deferred_attempts_ = nullptr;
  }
  if (near_rejoined_) {
    // Back at the usual answer: it stands, confirmed (near_search.hpp).
    near_rejoined_ = false;
    for (AttemptRecord& record : near_attempts) {
      record.adopted = false;
      trace_.attempt(record);
    }
    return;
  }
  near.near_search = true;
  const bool near_questionable = questionable(near, T_initial);
  const bool near_fits_more =
      usual_converged && usual_index &&
      fitsMoreOfTheOverlap(near, result->T_target_source, result->sigma, *usual_index);
  const bool keep = nearAnswerReplaces(usual_converged, near, near_questionable, near_fits_more);
  const bool cut = near.out_of_time;
  for (AttemptRecord& record : near_attempts) {
    record.adopted = record.adopted && keep;
    trace_.attempt(record);
  }
  adoptNested(keep, &near, &near_associations, result, associations);
  if (!usual_converged) nested.noteIfCut("a near search", keep, cut, result);
}

bool PdaRegistration::questionable(const RegistrationResult& answer,
                                   const Eigen::Isometry3d& T_initial) const {
  const double moved = rmsDisplacement(workspace_.source, answer.T_target_source, T_initial);
  return localStartWarranted(answer, parameters_, moved);
}

const char* PdaRegistration::attemptName(const char* usual) const {
  if (!in_near_search_) return usual;
  if (std::strcmp(usual, "second start") == 0) return "near search: second start";
  if (std::strcmp(usual, "turned start") == 0) return "near search: turned start";
  if (std::strcmp(usual, "local start") == 0) return "near search: local start";
  if (std::strcmp(usual, "other direction") == 0) return "near search: other direction";
  if (std::strcmp(usual, "wider search") == 0) return "near search: wider search";
  return usual;
}

}  // namespace pda_registration

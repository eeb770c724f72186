#pragma once
// What the attempts align() runs after (or during) the first one share: the user's time limit,
// the trace's label, and how a nested result replaces the first's. Internal to the engine
// (pda_registration.cpp, second_start_attempts.cpp).

#include <chrono>

#include "pda_registration/core/associations.hpp"
#include "pda_registration/core/registration_parameters.hpp"
#include "pda_registration/core/registration_result.hpp"

namespace pda_registration {

/// An alignment that align() runs after the first one (a second start, a wider search): it gets
/// what is left of the user's time limit, and the user's parameters come back however it ends
/// (align() catches what alignUnchecked throws).
class NestedAlignment {
 public:
  NestedAlignment(RegistrationParameters* live, std::chrono::steady_clock::time_point started);
  NestedAlignment(const NestedAlignment&) = delete;
  NestedAlignment& operator=(const NestedAlignment&) = delete;
  ~NestedAlignment() { *live_ = user_; }
  /// False when the user's time limit is already spent: the nested alignment is not run.
  bool timeLeft() const { return time_left_; }
  /// timeLeft(); when false, `result` notes that `nested` was cut by the time limit.
  bool timeLeftOrNote(const char* nested, RegistrationResult* result) const;
  /// Notes on `result` that `nested` was cut by the time limit, when it was and was not kept.
  void noteIfCut(const char* nested, bool kept, bool cut, RegistrationResult* result) const;

 private:
  RegistrationParameters* live_;
  const RegistrationParameters user_;
  bool time_left_ = true;
};

/// Names the attempt that align() runs while it lives (the trace's label), then restores the last.
class AttemptLabel {
 public:
  AttemptLabel(const char** live, const char* name) : live_(live), before_(*live) { *live = name; }
  AttemptLabel(const AttemptLabel&) = delete;
  AttemptLabel& operator=(const AttemptLabel&) = delete;
  ~AttemptLabel() { *live_ = before_; }

 private:
  const char** live_;
  const char* before_;
};

/// What a nested alignment leaves: its result (and associations) replace the first's when `keep`;
/// either way the answer counts the indexing both did in this call.
void adoptNested(bool keep, RegistrationResult* nested, Associations* nested_associations,
                 RegistrationResult* result, Associations* associations);

}  // namespace pda_registration

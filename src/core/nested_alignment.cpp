#include "pda_registration/core/nested_alignment.hpp"

#include <sstream>
#include <utility>

namespace pda_registration {
namespace {

// A failed result whose nested alignment (the other direction, a wider search) was cut by the
// user's time limit, or found none of it left, is the deadline's verdict, not the data's: it
// says so, and a caller with a deadline (the nodelet's warm attempts) does not retry it from
// the seed as if the data had rejected it.
void noteCutByTheTimeLimit(const char* nested, double time_limit_ms, RegistrationResult* result) {
  result->out_of_time = true;
  std::ostringstream reason;
  reason << result->reason << "; " << nested << " was cut by the time limit of " << time_limit_ms
         << " ms";
  result->reason = reason.str();
}

}  // namespace

NestedAlignment::NestedAlignment(RegistrationParameters* live,
                                 std::chrono::steady_clock::time_point started)
    : live_(live), user_(*live) {
  if (!(user_.time_limit_ms > 0.0)) return;  // no limit
  live_->time_limit_ms =
      user_.time_limit_ms -
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
  time_left_ = live_->time_limit_ms > 0.0;
}

bool NestedAlignment::timeLeftOrNote(const char* nested, RegistrationResult* result) const {
  if (!time_left_) noteCutByTheTimeLimit(nested, user_.time_limit_ms, result);
  return time_left_;
}

void NestedAlignment::noteIfCut(const char* nested, bool kept, bool cut,
                                RegistrationResult* result) const {
  if (!kept && cut) noteCutByTheTimeLimit(nested, user_.time_limit_ms, result);
}

void adoptNested(bool keep, RegistrationResult* nested, Associations* nested_associations,
                 RegistrationResult* result, Associations* associations) {
  if (!keep) {
    result->target_index_ms += nested->target_index_ms;
    return;
  }
  nested->target_index_ms += result->target_index_ms;
  *result = std::move(*nested);
  if (associations) *associations = std::move(*nested_associations);
}

}  // namespace pda_registration

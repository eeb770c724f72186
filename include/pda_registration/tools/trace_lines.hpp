#pragma once
// pda_align --trace: an alignment's runs and attempts (alignment_trace.hpp) as JSON lines, one per
// record, so that a user can see where the runs went (which stage, at what sigma, how far each
// moved) and why each attempt was or was not kept.

#include <ostream>

#include "pda_registration/core/alignment_trace.hpp"

namespace pda_registration {

/// A trace that writes each record to `out` as one JSON line ({"trace":"run",...} or
/// {"trace":"attempt",...}); `out` must outlive it.
AlignmentTrace jsonLinesTrace(std::ostream* out);

}  // namespace pda_registration

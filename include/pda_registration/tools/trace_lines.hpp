#pragma once
// pda_align --trace: an alignment's runs and attempts (alignment_trace.hpp) as JSON lines, one per
// record, so that a user can see where the runs went (which stage, at what sigma, how far each
// moved) and why each attempt was or was not kept.

#include <functional>
#include <ostream>

#include "pda_registration/core/alignment_trace.hpp"

namespace pda_registration {

/// A trace that writes each record to `out` as one JSON line ({"trace":"run",...} or
/// {"trace":"attempt",...}); `out` must outlive it. Each attempt's line carries its estimate "T";
/// with `error_from_truth` (pda_align --ground-truth) also its eq. 22 "mean_distance", so a user
/// sees which attempt found the truth and which was kept.
AlignmentTrace jsonLinesTrace(
    std::ostream* out,
    std::function<double(const Eigen::Isometry3d&)> error_from_truth = nullptr);

}  // namespace pda_registration

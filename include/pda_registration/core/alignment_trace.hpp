#pragma once
// What an alignment did, run by run and attempt by attempt, for a user who asks why it took 80
// runs or why it answered what it did (`pda_align --trace`). One align() is one or more
// attempts: the first, then, where its result calls for them, a second start, a local start, the
// other direction and a wider search, and where their answer is questionable all of them again
// as a near search ("near search", "near search: second start", ...: near_search.hpp; its
// attempts are noted once it is decided whether its answer stays; pda_registration.hpp). Each
// attempt is a sequence of runs (approach, settle, refine: docs/algorithm.md). A second start
// may run while the first attempt pauses at nu's floor: its runs then come between the first's,
// and the first attempt is noted after its own last run. Reading the trace changes nothing: an
// alignment traced answers exactly what it answers untraced.

#include <cstddef>
#include <functional>
#include <string>

#include <Eigen/Geometry>

namespace pda_registration {

/// One run: the candidate sets recomputed, then EM on them.
struct RunRecord {
  const char* attempt = "";  ///< "first", "second start", "local start", "other direction", ...
  int run = 0;               ///< 1-based within the attempt
  const char* stage = "";    ///< "approach", "settle" or "refine"
  size_t points = 0;         ///< source points aligned in this run (the approach: a subset)
  double radius = 0.0;       ///< candidate search radius [length]
  double sigma = 0.0;        ///< sigma after the run's EM [length]
  double nu = 0.0;           ///< Student-t degrees of freedom after the run's EM
  double step_translation = 0.0;  ///< how far the run moved the pose [length]
  double step_rotation = 0.0;     ///< [rad]
  int em_iterations = 0;          ///< this run's E/M iterations
  /// A near search's run taken over from the usual first attempt, which ran it to the digit
  /// (opening_runs.hpp): not run again.
  bool replayed = false;
};

/// One attempt, when it has ended: what it concluded and whether align() adopted it as its answer
/// (a later attempt may still replace it).
struct AttemptRecord {
  const char* attempt = "";
  bool converged = false;
  bool adopted = false;
  std::string reason;  ///< why it did not converge (empty when it did)
  int runs = 0;  ///< its runs as listed; a least-squares polish over a warp adds its own, unlisted
  double sigma = 0.0;
  double time_ms = 0.0;  ///< since align() began
  /// its estimate, p_target = T * p_source, in align()'s frames (the other direction's inverted)
  Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();
};

/// Receivers, each optional; called on align()'s own thread, in order.
struct AlignmentTrace {
  std::function<void(const RunRecord&)> run;
  std::function<void(const AttemptRecord&)> attempt;
};

}  // namespace pda_registration

#pragma once
// Memory an alignment reuses from run to run, EM iteration to EM iteration, and alignment to
// alignment: the candidate sets, the E-step's correspondences and noise shapes, the M-step's
// terms. Allocated afresh each time, these megabytes come back from the system as new pages, and
// the page faults cost as much as the arithmetic (measured: ~25 % of an alignment of an HDL-32
// scan, half of a dense Kinect pair's). Only the memory is shared: every call overwrites what
// it reads, so results do not depend on what ran before.

#include "pda_registration/core/association_weights.hpp"
#include "pda_registration/core/candidate_sets.hpp"
#include "pda_registration/core/gauss_newton_solver.hpp"
#include "pda_registration/core/noise_shapes.hpp"

namespace pda_registration {

struct RegistrationWorkspace {
  PointList source;         ///< the finite (voxelised) source points
  PointList coarse_source;  ///< every coarse_stride-th of them
  CandidateSearchBuffers search;
  CandidateSets candidates;
  PointList normals;           ///< target normal at each moved source point (one run)
  std::vector<double> spread;  ///< candidates' sampling spread (one run)
  NoiseShapes shapes;
  EStepBuffers e_step;
  WeightedCorrespondences correspondences;
  GaussNewtonBuffers gauss_newton;
};

}  // namespace pda_registration

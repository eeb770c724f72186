#pragma once
// Memory an alignment reuses from run to run, EM iteration to EM iteration, and alignment to
// alignment: the source points, the candidate sets, the E-step's correspondences and noise
// shapes. Allocated afresh each time, these megabytes come back from the system as new pages, and
// page faults are slow (on campus_hdl32: ~1650 faults per alignment before, ~290 with this, and
// the alignment 15-20 % faster; 10 % on kinect_pairwise). Only the memory is shared: every call
// overwrites what it reads, so results do not depend on what ran before.

#include "pda_registration/core/association_weights.hpp"
#include "pda_registration/core/candidate_sets.hpp"
#include "pda_registration/core/noise_shapes.hpp"
#include "pda_registration/core/surface_normals.hpp"

namespace pda_registration {

struct RegistrationWorkspace {
  PointList source;         ///< the finite (voxelised) source points
  PointList coarse_source;  ///< every coarse_stride-th of them
  CandidateSearchBuffers search;
  CandidateSets candidates;
  PointList normals;           ///< each source point's target normal (final statistics;
                               ///< a run keeps its own in shapes.normal)
  std::vector<double> spread;  ///< candidates' sampling spread (one run)
  /// Each source point's last normal lookup, slot by slot (valid only for the voxel and map
  /// version it names, so any source may reuse the slots).
  std::vector<SurfaceNormalMap::Memo> normal_memos;
  NoiseShapes shapes;
  EStepBuffers e_step;
  WeightedCorrespondences correspondences;
};

}  // namespace pda_registration

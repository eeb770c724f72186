#pragma once
// A "no counterpart" class beside the Student-t mixture, as in CPD: each source point is either
// one of the t's members over its candidates (prior 1 - w) or an outlier, uniform across the
// search radius (prior w), w estimated by EM. It answers a limit of the t alone: with the
// weights (nu + 3) / (nu + m) and sigma the weighted mean squared residual across the surface, a
// point with no counterpart adds about (nu + 3) sigma^2 to the sigma update however far off it is,
// so once more than about 1 / (nu + 3) of the points with candidates have none (an eighth at
// nu = 5), sigma cannot shrink below their residuals. Two RGB-D fragments that share a third of
// their scene (docs/benchmark.md, "RGB-D fragments that share less") keep sigma at 0.14-0.18 m
// from the ground truth itself, and the unshared points pull the source 2.6 m along the walkway.
//
// The outlier class is only as wide as the search, so the along-surface part of a point's noise
// shape (the target's sampling, kappa sigma^2) is left out of both densities: only the residual
// across the surface (or the whole residual where no normal is known) decides whether a point has
// a counterpart. The same reason it rejects far points takes away the reach: a true counterpart
// half a metre away looks like no counterpart at all, so it is used only for a start near the
// seed (local_start.hpp), never for the approach from far off.

namespace pda_registration {

/// The class for one E-step: off (odds 0) or the prior odds of an outlier times its density.
struct OutlierClass {
  double odds = 0.0;          ///< w / (1 - w) / (2 radius): 0 = no outlier class
  double log_constant = 0.0;  ///< the t's normalisation across the surface (nu's part)

  bool on() const { return odds > 0.0; }
};

/// The class for outlier share `share` (clamped to [1e-3, 0.999]), search radius `radius` and
/// degrees of freedom `nu` (+inf: the Gaussian).
OutlierClass outlierClassFor(double share, double radius, double nu);

/// gamma_j, the posterior probability that a source point has a counterpart: its best candidate's
/// Mahalanobis distance m (in its noise shape), the log of its across-surface variance, and the
/// sum of its candidates' densities relative to the best's over their count (the association
/// prior is uniform over the candidates).
double inlierResponsibility(const OutlierClass& outliers, double nu, double best_mahalanobis,
                            double log_across_variance, double relative_density_mean);

}  // namespace pda_registration

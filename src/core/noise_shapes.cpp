#include "pda_registration/core/noise_shapes.hpp"

#include <algorithm>

namespace pda_registration {

std::vector<double> candidateSpread(const CandidateSets& candidates, int threads) {
  const size_t n = candidates.sourceCount();
  std::vector<double> spread(n, 0.0);
#pragma omp parallel for schedule(static) num_threads(std::max(threads, 1))
  for (long long j = 0; j < static_cast<long long>(n); ++j) {
    const size_t begin = candidates.offsets[j], end = candidates.offsets[j + 1];
    if (end - begin < 2) continue;
    Point centroid = Point::Zero();
    for (size_t c = begin; c < end; ++c) centroid += candidates.points[c];
    centroid /= static_cast<double>(end - begin);
    double sum = 0.0;
    for (size_t c = begin; c < end; ++c) sum += (candidates.points[c] - centroid).squaredNorm();
    spread[j] = sum / static_cast<double>(end - begin);
  }
  return spread;
}

double targetThickness(const CandidateSets& candidates, const PointList& normals) {
  std::vector<double> variances;
  for (size_t j = 0; j < candidates.sourceCount() && j < normals.size(); ++j) {
    const size_t begin = candidates.offsets[j], end = candidates.offsets[j + 1];
    if (end - begin < 3 || !(normals[j].squaredNorm() > 0.0)) continue;
    double sum = 0.0, squares = 0.0;
    for (size_t c = begin; c < end; ++c) {
      const double height = normals[j].dot(candidates.points[c] - candidates.points[begin]);
      sum += height;
      squares += height * height;
    }
    const double count = static_cast<double>(end - begin);
    variances.push_back(std::max(0.0, (squares - sum * sum / count) / (count - 1.0)));
  }
  if (variances.size() < 10) return 0.0;
  const auto middle = variances.begin() + static_cast<long>(variances.size() / 2);
  std::nth_element(variances.begin(), middle, variances.end());
  return *middle;
}

bool usesSamplingModel(const RegistrationParameters& p) {
  return p.surface_anisotropy > 1.0 && p.sampling_scale > 0.0;
}

void makeNoiseShapes(const PointList& normals, const std::vector<double>& spread,
                     double sigma_squared, const RegistrationParameters& p, NoiseShapes* out) {
  NoiseShapes& shapes = *out;
  shapes.sampling = false;
  if (!(p.surface_anisotropy > 1.0)) {  // the paper's isotropic model
    shapes.normal.clear();
    shapes.inverse_kappa.clear();
    return;
  }
  // A run's EM loop keeps its normals in the shapes themselves: no copy per iteration.
  if (&normals != &shapes.normal) shapes.normal = normals;
  shapes.inverse_kappa.assign(shapes.normal.size(), 1.0);
  if (!usesSamplingModel(p)) {
    for (size_t j = 0; j < shapes.normal.size(); ++j) {
      if (shapes.normal[j].squaredNorm() > 0.0)
        shapes.inverse_kappa[j] = 1.0 / p.surface_anisotropy;
    }
    return;
  }
  shapes.sampling = true;
  // Along the surface: the larger of the constant kappa's sigma^2 kappa and sigma^2 + s_j^2.
  // Without a normal: sigma^2 + s_j^2 in every direction.
  const double constant_inverse_kappa = 1.0 / p.surface_anisotropy;
  for (size_t j = 0; j < shapes.normal.size() && j < spread.size(); ++j) {
    const double total = sigma_squared + p.sampling_scale * spread[j];
    const double sampling_inverse_kappa = total > 0.0 ? sigma_squared / total : 1.0;
    shapes.inverse_kappa[j] = shapes.normal[j].squaredNorm() > 0.0
                                  ? std::min(constant_inverse_kappa, sampling_inverse_kappa)
                                  : sampling_inverse_kappa;
  }
}

}  // namespace pda_registration

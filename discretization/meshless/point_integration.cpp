#include "discretization/meshless/point_integration.h"

#include "core/check.h"

namespace kerf {

PointIntegration::PointIntegration(ShapeTable shapes, std::vector<double> weights, Index node_count)
    : shapes_(std::move(shapes)), weights_(std::move(weights)) {
  KERF_CHECK(static_cast<Index>(weights_.size()) == shapes_.point_count(), "integration weights: ", weights_.size(),
             " for ", shapes_.point_count(), " points");
  const auto& nb = shapes_.neighbours;
  const Index slots = static_cast<Index>(nb.index.size());
  slot_point_.resize(slots);
  for (Index p = 0; p < nb.size(); ++p)
    for (Index s = nb.start[p]; s < nb.start[p + 1]; ++s) slot_point_[s] = p;
  // Transpose of the neighbour lists by counting sort: slots of a node in point order.
  users_.start.assign(node_count + 1, 0);
  for (Index K : nb.index) ++users_.start[K + 1];
  for (Index K = 0; K < node_count; ++K) users_.start[K + 1] += users_.start[K];
  users_.index.resize(slots);
  std::vector<Index> next(users_.start.begin(), users_.start.end() - 1);
  for (Index s = 0; s < slots; ++s) users_.index[next[nb.index[s]]++] = s;
}

void PointIntegration::gather(std::span<const Mat3> stress, std::span<const Vec3> slot_force, Vector& f) const {
  const int dim = shapes_.dimension;
  const Index N = users_.size();
  f.resize(dim * N);
  const double* g = shapes_.gradient.data();
  const bool pairs = !slot_force.empty();
#pragma omp parallel for schedule(static)
  for (Index K = 0; K < N; ++K) {
    Vec3 acc = Vec3::Zero();
    for (Index s : users_.of(K)) {
      const Mat3& Q = stress[slot_point_[s]];
      const double* gs = g + dim * s;
      if (dim == 3)
        acc += Q * Vec3(gs[0], gs[1], gs[2]);
      else
        acc += Q * Vec3(gs[0], gs[1], 0.0);
      if (pairs) acc += slot_force[s];
    }
    for (int i = 0; i < dim; ++i) f[dim * K + i] = acc[i];
  }
}

void PointIntegration::add_material_block(Index p, const Mat9& dPdF, double scale,
                                          std::vector<double>& block) const {
  const int dim = shapes_.dimension;
  const Index n = static_cast<Index>(neighbours(p).size()), size = n * dim;
  const double* g = shapes_.gradients_of(p);
  for (Index b = 0; b < n; ++b)
    for (int k = 0; k < dim; ++k) {
      // T(i, j) = sum_l dP(i,j)/dF(k,l) g_b(l)
      Mat3 T = Mat3::Zero();
      for (int l = 0; l < dim; ++l)
        for (int j = 0; j < dim; ++j)
          for (int i = 0; i < dim; ++i) T(i, j) += dPdF(i + 3 * j, k + 3 * l) * g[dim * b + l];
      for (Index a = 0; a < n; ++a)
        for (int i = 0; i < dim; ++i) {
          double s = 0.0;
          for (int j = 0; j < dim; ++j) s += T(i, j) * g[dim * a + j];
          block[(dim * a + i) * size + dim * b + k] += scale * s;
        }
    }
}

void PointIntegration::neighbour_dofs(Index p, std::vector<Index>& dofs) const {
  const int dim = shapes_.dimension;
  dofs.clear();
  for (Index K : neighbours(p))
    for (int i = 0; i < dim; ++i) dofs.push_back(dim * K + i);
}

}  // namespace kerf

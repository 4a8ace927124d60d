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
  users_ = transpose_slots(nb, node_count);
}

void PointIntegration::gather(std::span<const Mat3> stress, Vector& f) const {
  const int dim = shapes_.dimension;
  const Index N = users_.size();
  f.resize(dim * N);
  const double* g = shapes_.gradient.data();
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
    }
    for (int i = 0; i < dim; ++i) f[dim * K + i] = acc[i];
  }
}

void add_material_block(const ShapeTable& table, Index point, const Mat9& dPdF, double scale,
                        std::vector<double>& block) {
  const int dim = table.dimension;
  const Index n = static_cast<Index>(table.neighbours.of(point).size()), size = n * dim;
  const double* g = table.gradients_of(point);
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

void assemble_material_blocks(const ShapeTable& table, std::span<const double> weights, const MaterialLaw& law,
                              const Vector& u, const BlockSink& sink, const BlockExtra& extra) {
#pragma omp parallel
  {
    std::vector<double> block;
    std::vector<Index> dofs;
    Mat3 P;
    Mat9 dPdF;
#pragma omp for schedule(dynamic, 16)
    for (Index p = 0; p < table.point_count(); ++p) {
      neighbour_dofs(table, p, dofs);
      block.assign(dofs.size() * dofs.size(), 0.0);
      law.stress_and_tangent(deformation_gradient(table, p, u), P, dPdF);
      add_material_block(table, p, dPdF, weights[p], block);
      if (extra) extra(p, block);
#pragma omp critical(kerf_meshless_sink)
      sink(dofs, block);
    }
  }
}

}  // namespace kerf

#include "discretization/meshless/point_integration.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <limits>

#include "core/check.h"

namespace kerf {

PointIntegration::PointIntegration(ShapeTable shapes, std::vector<double> weights, std::span<const Vec3> nodes)
    : shapes_(std::move(shapes)), weights_(std::move(weights)), schedule_(schedule_points(shapes_, nodes)) {
  const Index node_count = static_cast<Index>(nodes.size());
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
      // A hyperelastic tangent has major symmetry, so K is symmetric: the
      // blocks a <= b are computed and mirrored.
      for (Index a = 0; a <= b; ++a)
        for (int i = 0; i < dim; ++i) {
          double s = 0.0;
          for (int j = 0; j < dim; ++j) s += T(i, j) * g[dim * a + j];
          block[(dim * a + i) * size + dim * b + k] += scale * s;
          if (a < b) block[(dim * b + k) * size + dim * a + i] += scale * s;
        }
    }
}

PointSchedule schedule_points(const ShapeTable& table, std::span<const Vec3> nodes) {
  const Index P = table.point_count();
  std::vector<Vec3> centre(P, Vec3::Zero());
  double reach = 0.0;  // the largest distance from a point's centroid to one of its neighbours
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
  for (Index p = 0; p < P; ++p) {
    auto near = table.neighbours.of(p);
    for (Index J : near) centre[p] += nodes[J];
    if (!near.empty()) centre[p] /= static_cast<double>(near.size());
    for (Index J : near) reach = std::max(reach, (nodes[J] - centre[p]).norm());
    low = low.cwiseMin(centre[p]), high = high.cwiseMax(centre[p]);
  }
  // Two points sharing a node have centroids within 2 reach: cubes of that width
  // (a hair more for round-off), same-colour cubes a cube apart.
  const double width = 2.0 * reach * (1.0 + 1e-9) + 1e-300;
  std::array<Index, 3> count{1, 1, 1};
  for (int a = 0; a < table.dimension; ++a)
    count[a] = std::max<Index>(1, static_cast<Index>(std::floor((high[a] - low[a]) / width)) + 1);
  std::vector<std::vector<Index>> cubes(static_cast<std::size_t>(count[0]) * count[1] * count[2]);
  for (Index p = 0; p < P; ++p) {
    std::array<Index, 3> at{0, 0, 0};
    for (int a = 0; a < table.dimension; ++a)
      at[a] = std::min(count[a] - 1, static_cast<Index>((centre[p][a] - low[a]) / width));
    cubes[at[0] + count[0] * (at[1] + count[1] * at[2])].push_back(p);
  }
  PointSchedule schedule;
  schedule.colours.resize(table.dimension == 3 ? 8 : 4);
  for (Index k = 0; k < count[2]; ++k)
    for (Index j = 0; j < count[1]; ++j)
      for (Index i = 0; i < count[0]; ++i) {
        auto& cube = cubes[i + count[0] * (j + count[1] * k)];
        if (!cube.empty()) schedule.colours[(i % 2) + 2 * (j % 2) + 4 * (k % 2)].push_back(std::move(cube));
      }
  return schedule;
}

void assemble_material_blocks(const ShapeTable& table, const PointSchedule& schedule, std::span<const double> weights,
                              const MaterialLaw& law, const Vector& u, const BlockSink& sink,
                              const BlockExtra& extra) {
  std::exception_ptr failure;  // an exception must not leave an OpenMP region
#pragma omp parallel
  {
    std::vector<double> block;
    std::vector<Index> dofs;
    Mat3 P;
    Mat9 dPdF;
    for (const auto& colour : schedule.colours) {
#pragma omp for schedule(dynamic, 1)
      for (std::size_t c = 0; c < colour.size(); ++c) {
        try {
          for (Index p : colour[c]) {
            neighbour_dofs(table, p, dofs);
            block.assign(dofs.size() * dofs.size(), 0.0);
            law.stress_and_tangent(deformation_gradient(table, p, u), P, dPdF);
            add_material_block(table, p, dPdF, weights[p], block);
            if (extra) extra(p, block);
            sink(dofs, block);  // no other thread writes these dofs now: this colour's cubes share no node
          }
        } catch (...) {
#pragma omp critical(kerf_meshless_failure)
          if (!failure) failure = std::current_exception();
        }
      }
    }
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace kerf

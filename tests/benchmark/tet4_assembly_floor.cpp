#include "tet4_assembly_floor.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace kerf::bench {

Tet4AssemblyFloor::Tet4AssemblyFloor(const Mesh& mesh, const SparseMatrix& K, double lambda, double mu, int threads)
    : lambda_(lambda), mu_(mu) {
  const CellSchedule schedule = schedule_cells(mesh, threads);
  phases_ = schedule.phases;
  const Index* outer = K.outerIndexPtr();
  const Index* inner = K.innerIndexPtr();
  cells_.reserve(schedule.cells.size());
  for (Index c : schedule.cells) {
    Cell cell;
    auto nodes = mesh.cell(c);
    Eigen::Matrix3d J;  // columns: edges from corner 0
    for (int k = 0; k < 3; ++k) J.col(k) = mesh.nodes[nodes[k + 1]] - mesh.nodes[nodes[0]];
    const Eigen::Matrix3d Jinv = J.inverse();
    cell.volume = std::abs(J.determinant()) / 6.0;
    for (int a = 0; a < 4; ++a) {
      cell.node[a] = nodes[a];
      // grad N_a = J^-T grad_xi N_a, grad_xi N_0 = (-1, -1, -1), N_k = xi_k
      Eigen::Vector3d reference = a == 0 ? Eigen::Vector3d(-1, -1, -1) : Eigen::Vector3d::Unit(a - 1);
      Eigen::Vector3d g = Jinv.transpose() * reference;
      for (int l = 0; l < 3; ++l) cell.gradient[3 * a + l] = g[l];
    }
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        const Index row = 3 * nodes[a];
        const Index* at = std::lower_bound(inner + outer[row], inner + outer[row + 1], 3 * nodes[b]);
        cell.offset[4 * a + b] = static_cast<Index>(at - (inner + outer[row]));
      }
    cells_.push_back(cell);
  }
}

void Tet4AssemblyFloor::assemble(const double* u, SparseMatrix& K, double* f) const {
  const Index* outer = K.outerIndexPtr();
  double* values = K.valuePtr();
  const Index rows = static_cast<Index>(K.rows());
#pragma omp parallel
  {
#pragma omp for schedule(static)
    for (Index r = 0; r < rows; ++r) {
      std::fill(values + outer[r], values + outer[r + 1], 0.0);
      f[r] = 0.0;
    }
    for (const auto& phase : phases_) {
#pragma omp for schedule(static, 1)
      for (std::size_t range = 0; range < phase.size(); ++range)
        for (Index slot = phase[range].first; slot < phase[range].second; ++slot) {
          const Cell& cell = cells_[slot];
          const double* g = cell.gradient.data();
          for (int a = 0; a < 4; ++a) {
            const Index row = 3 * cell.node[a];
            double fa[3] = {};
            for (int b = 0; b < 4; ++b) {
              const double* ga = g + 3 * a;
              const double* gb = g + 3 * b;
              const double dot = ga[0] * gb[0] + ga[1] * gb[1] + ga[2] * gb[2];
              const double* ub = u + 3 * cell.node[b];
              for (int i = 0; i < 3; ++i) {
                double* out = values + outer[row + i] + cell.offset[4 * a + b];
                for (int k = 0; k < 3; ++k) {
                  const double kik =
                      cell.volume * (lambda_ * ga[i] * gb[k] + mu_ * ga[k] * gb[i] + (i == k ? mu_ * dot : 0.0));
                  out[k] += kik;
                  fa[i] += kik * ub[k];
                }
              }
            }
            for (int i = 0; i < 3; ++i) f[row + i] += fa[i];
          }
        }
    }
  }
}

}  // namespace kerf::bench

#include "discretization/meshless/natural_stabilization.h"

#include <omp.h>

#include <algorithm>
#include <numeric>

#include "core/parallel_failure.h"
#include "geometry/mesh.h"

namespace kerf {
namespace {

/// The strain gradient of node L's term along i: sym(sum_J u_J h_J^T), h_J =
/// column i of psi_J's Hessian (dim x dim, column-major reads of a symmetric matrix).
template <int Dim>
void strain_derivative(const double* hessians, std::span<const Index> near, const Vector& u, int i,
                       double eps[Dim][Dim]) {
  double g[Dim][Dim] = {};
  for (std::size_t k = 0; k < near.size(); ++k) {
    const double* h = hessians + Dim * Dim * k + Dim * i;
    const double* uJ = &u[Dim * near[k]];
    for (int a = 0; a < Dim; ++a)
      for (int b = 0; b < Dim; ++b) g[a][b] += uJ[a] * h[b];
  }
  for (int a = 0; a < Dim; ++a)
    for (int b = 0; b < Dim; ++b) eps[a][b] = 0.5 * (g[a][b] + g[b][a]);
}

/// sigma = lambda tr(eps) I + 2 mu eps, scaled by `scale`, in place.
template <int Dim>
void stress_in_place(const Lame& lame, double scale, double eps[Dim][Dim]) {
  double trace = 0.0;
  for (int a = 0; a < Dim; ++a) trace += eps[a][a];
  for (int a = 0; a < Dim; ++a)
    for (int b = 0; b < Dim; ++b) eps[a][b] = scale * (2.0 * lame.mu * eps[a][b] + (a == b ? lame.lambda * trace : 0.0));
}

template <int Dim>
void add_forces_of(const ShapeTable& table, const std::vector<double>& hessian, const std::vector<Vec3>& moment,
                   const Lame& lame, std::pair<Index, Index> points, const Vector& u, double* f) {
  for (Index L = points.first; L < points.second; ++L) {
    auto near = table.neighbours.of(L);
    const double* H = hessian.data() + Dim * Dim * table.neighbours.start[L];
    for (int i = 0; i < Dim; ++i) {
      double s[Dim][Dim];
      strain_derivative<Dim>(H, near, u, i, s);
      stress_in_place<Dim>(lame, moment[L][i], s);
      for (std::size_t k = 0; k < near.size(); ++k) {
        const double* h = H + Dim * Dim * k + Dim * i;
        double* fJ = f + Dim * near[k];
        for (int a = 0; a < Dim; ++a)
          for (int b = 0; b < Dim; ++b) fJ[a] += s[a][b] * h[b];
      }
    }
  }
}

template <int Dim>
double energy_of(const ShapeTable& table, const std::vector<double>& hessian, const std::vector<Vec3>& moment,
                 const Lame& lame, std::pair<Index, Index> points, const Vector& u) {
  double energy = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : energy)
  for (Index L = points.first; L < points.second; ++L) {
    auto near = table.neighbours.of(L);
    const double* H = hessian.data() + Dim * Dim * table.neighbours.start[L];
    for (int i = 0; i < Dim; ++i) {
      double eps[Dim][Dim], s[Dim][Dim];
      strain_derivative<Dim>(H, near, u, i, eps);
      std::copy(&eps[0][0], &eps[0][0] + Dim * Dim, &s[0][0]);
      stress_in_place<Dim>(lame, moment[L][i], s);  // 2D: plane strain, eps_zz = 0 adds nothing
      for (int a = 0; a < Dim; ++a)
        for (int b = 0; b < Dim; ++b) energy += 0.5 * s[a][b] * eps[a][b];
    }
  }
  return energy;
}

}  // namespace

NaturalStabilization::NaturalStabilization(const NodeSet& nodes, MlsBasis basis, const ShapeTable& at_nodes,
                                           const EnrichmentRule* enrichment, const Lame& lame,
                                           std::vector<Vec3> moments)
    : dim_(nodes.dimension), lame_(lame), moment_(std::move(moments)) {
  hessian_.assign(static_cast<std::size_t>(dim_) * dim_ * at_nodes.neighbours.index.size(), 0.0);
  std::vector<Index> rows(nodes.size());
  std::iota(rows.begin(), rows.end(), Index{0});
  refresh(nodes, basis, at_nodes, rows, enrichment);
}

void NaturalStabilization::refresh(const NodeSet& nodes, MlsBasis basis, const ShapeTable& at_nodes,
                                   std::span<const Index> rows, const EnrichmentRule* enrichment) {
  const int dim = dim_;
  for_each_with_scratch<PointShapes>(static_cast<Index>(rows.size()), [&](Index r, PointShapes& scratch) {
    const Index L = rows[r];
    auto near = at_nodes.neighbours.of(L);
    double* H = hessian_.data() + static_cast<std::size_t>(dim) * dim * at_nodes.neighbours.start[L];
    scratch.look_up_factors(nodes.positions[L], near, enrichment);
    const bool ok = scratch.evaluate_looked_up(nodes, basis, nodes.positions[L], near, true);
    for (std::size_t k = 0; k < near.size(); ++k)
      for (int a = 0; a < dim; ++a)
        for (int b = 0; b < dim; ++b) H[dim * dim * k + dim * a + b] = ok ? scratch.shape.hessian[k](a, b) : 0.0;
  });
}

void NaturalStabilization::add_forces(const ShapeTable& at_nodes, std::pair<Index, Index> points, const Vector& u,
                                      Vector& f) const {
  const Index dofs = f.size();
  // Sized here, not inside the region: an allocation failure must not be thrown in it.
  thread_forces_.resize(static_cast<std::size_t>(omp_get_max_threads()) * dofs);
#pragma omp parallel
  {
    const int thread = omp_get_thread_num(), threads = omp_get_num_threads();
    double* mine = thread_forces_.data() + static_cast<std::size_t>(thread) * dofs;
    std::fill(mine, mine + dofs, 0.0);
    // An even share of the points to each thread: the sum's order depends on the thread count only.
    const Index n = points.second - points.first;
    const std::pair<Index, Index> part{points.first + n * thread / threads, points.first + n * (thread + 1) / threads};
    if (dim_ == 3)
      add_forces_of<3>(at_nodes, hessian_, moment_, lame_, part, u, mine);
    else
      add_forces_of<2>(at_nodes, hessian_, moment_, lame_, part, u, mine);
#pragma omp barrier
#pragma omp for schedule(static)
    for (Index d = 0; d < dofs; ++d) {
      double sum = 0.0;
      for (int t = 0; t < threads; ++t) sum += thread_forces_[static_cast<std::size_t>(t) * dofs + d];
      f[d] += sum;
    }
  }
}

double NaturalStabilization::energy(const ShapeTable& at_nodes, std::pair<Index, Index> points,
                                    const Vector& u) const {
  return dim_ == 3 ? energy_of<3>(at_nodes, hessian_, moment_, lame_, points, u)
                   : energy_of<2>(at_nodes, hessian_, moment_, lame_, points, u);
}

void NaturalStabilization::add_block(const ShapeTable& at_nodes, Index L, std::vector<double>& block) const {
  const int dim = dim_;
  auto near = at_nodes.neighbours.of(L);
  const Index n = static_cast<Index>(near.size()), size = n * dim;
  const double* H = hessian_.data() + static_cast<std::size_t>(dim) * dim * at_nodes.neighbours.start[L];
  // M_i (lambda h_J h_K^T + mu (h_J . h_K) I + mu h_K h_J^T), h_J = column i of psi_J's Hessian.
  for (int i = 0; i < dim; ++i) {
    const double m = moment_[L][i];
    for (Index J = 0; J < n; ++J) {
      const double* hJ = H + dim * dim * J + dim * i;
      for (Index K = 0; K < n; ++K) {
        const double* hK = H + dim * dim * K + dim * i;
        double dot = 0.0;
        for (int b = 0; b < dim; ++b) dot += hJ[b] * hK[b];
        for (int a = 0; a < dim; ++a)
          for (int c = 0; c < dim; ++c)
            block[(dim * J + a) * size + dim * K + c] +=
                m * (lame_.lambda * hJ[a] * hK[c] + lame_.mu * hJ[c] * hK[a] + (a == c ? lame_.mu * dot : 0.0));
      }
    }
  }
}

}  // namespace kerf

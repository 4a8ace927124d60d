#include "discretization/meshless/integration_constraint.h"

#include <cmath>

#include "core/check.h"
#include "core/gmres.h"
#include "discretization/meshless/point_sums.h"

namespace kerf {

void add_boundary_terms(const ShapeTable& at_boundary, const BoundaryQuadrature& quadrature, std::vector<double>& terms) {
  const int dim = at_boundary.dimension;
  KERF_CHECK(at_boundary.point_count() == quadrature.size(), "internal: boundary table and quadrature differ");
  for (Index q = 0; q < at_boundary.point_count(); ++q) {
    auto near = at_boundary.neighbours.of(q);
    const double* psi = at_boundary.values_of(q);
    const Vec3& n = quadrature.weighted_normal[q];
    for (std::size_t k = 0; k < near.size(); ++k)
      for (int i = 0; i < dim; ++i) terms[dim * near[k] + i] += psi[k] * n[i];
  }
}

VolumeTerms volume_terms(const ShapeTable& points, std::span<const double> weights, Index node_count,
                         std::span<const double> offsets) {
  const int dim = points.dimension;
  // Per node, packed: the gradient sum (dim), the magnitude, the value sum.
  const int width = dim + 2;
  std::vector<double> packed(width * node_count, 0.0);
  add_over_points(points.point_count(), packed, [&](Index p, double* sums) {
    auto near = points.neighbours.of(p);
    const double* g = points.gradients_of(p);
    const double* psi = points.values_of(p);
    const double* o = offsets.empty() ? nullptr : offsets.data() + dim * points.neighbours.start[p];
    const double w = weights[p];
    for (std::size_t k = 0; k < near.size(); ++k) {
      double* at = sums + width * near[k];
      double squared = 0.0;
      for (int i = 0; i < dim; ++i) {
        at[i] += w * (g[dim * k + i] + (o ? o[dim * k + i] : 0.0));
        squared += g[dim * k + i] * g[dim * k + i];
      }
      at[dim] += w * std::sqrt(squared);
      at[dim + 1] += w * psi[k];
    }
  });
  VolumeTerms t{std::vector<double>(dim * node_count), std::vector<double>(node_count),
                std::vector<double>(node_count)};
  for (Index I = 0; I < node_count; ++I) {
    for (int i = 0; i < dim; ++i) t.gradient_sum[dim * I + i] = packed[width * I + i];
    t.magnitude[I] = packed[width * I + dim];
    t.value_sum[I] = packed[width * I + dim + 1];
  }
  return t;
}

ConstraintResidual constraint_residual(std::span<const double> boundary_terms, const VolumeTerms& volume,
                                       int dimension) {
  ConstraintResidual result;
  const Index N = static_cast<Index>(volume.magnitude.size());
  double sum = 0.0;
  Index counted = 0;
  for (Index I = 0; I < N; ++I) {
    if (volume.magnitude[I] == 0.0) continue;  // a node no integration point sees
    double squared = 0.0;
    for (int i = 0; i < dimension; ++i) {
      const double r = boundary_terms[dimension * I + i] - volume.gradient_sum[dimension * I + i];
      squared += r * r;
    }
    const double relative = std::sqrt(squared) / volume.magnitude[I];
    sum += relative * relative;
    ++counted;
    if (relative > result.max) result.max = relative, result.worst = I;
  }
  result.rms = counted ? std::sqrt(sum / counted) : 0.0;
  return result;
}

namespace {

/// eta_L = sum_J psi_J(x_L) x_J for every point L.
void point_means(const ShapeTable& points, const Vector& x, Vector& eta) {
  eta.resize(points.point_count());
  for (Index p = 0; p < points.point_count(); ++p) {
    auto near = points.neighbours.of(p);
    const double* psi = points.values_of(p);
    double sum = 0.0;
    for (std::size_t k = 0; k < near.size(); ++k) sum += psi[k] * x[near[k]];
    eta[p] = sum;
  }
}

/// y = (D - C) x: y_I = sum_L V_L psi_I(x_L) (x_I - eta_L).
void apply_laplacian(const ShapeTable& points, std::span<const double> weights, const Vector& x, Vector& eta,
                     Vector& y) {
  point_means(points, x, eta);
  y = Vector::Zero(x.size());
  for (Index p = 0; p < points.point_count(); ++p) {
    auto near = points.neighbours.of(p);
    const double* psi = points.values_of(p);
    for (std::size_t k = 0; k < near.size(); ++k) y[near[k]] += weights[p] * psi[k] * (x[near[k]] - eta[p]);
  }
}

/// (D - C) xi = r (r orthogonal to its null space) by GMRES, Jacobi-
/// preconditioned by D: the matrix is symmetric but, where a cut's enriched
/// psi go negative, indefinite (conjugate gradients broke down there).
Vector solve_laplacian(const ShapeTable& points, std::span<const double> weights, const std::vector<double>& D,
                       const Vector& r) {
  const Index N = static_cast<Index>(r.size());
  Vector x = Vector::Zero(N), eta;
  const LinearOperator A = [&](const Vector& v, Vector& y) { apply_laplacian(points, weights, v, eta, y); };
  const LinearOperator jacobi = [&](const Vector& v, Vector& y) {
    y.resize(N);
    for (Index I = 0; I < N; ++I) y[I] = D[I] > 0.0 ? v[I] / D[I] : 0.0;
  };
  const int limit = 20 * static_cast<int>(std::sqrt(static_cast<double>(N))) + 200;
  gmres(A, jacobi, r, x, 1e-13, 60, limit);  // short of it, the residual recorded says so
  return x;
}

/// The parts of the body the shape functions join (a cut through it makes
/// two): a label per node, nodes joined when a point's psi is non-zero for both.
std::vector<Index> joined_parts(const ShapeTable& points, Index node_count) {
  std::vector<Index> parent(node_count);
  for (Index I = 0; I < node_count; ++I) parent[I] = I;
  auto root = [&](Index I) {
    while (parent[I] != I) I = parent[I] = parent[parent[I]];
    return I;
  };
  for (Index p = 0; p < points.point_count(); ++p) {
    auto near = points.neighbours.of(p);
    const double* psi = points.values_of(p);
    Index first = -1;
    for (std::size_t k = 0; k < near.size(); ++k) {
      if (psi[k] == 0.0) continue;
      if (first < 0)
        first = root(near[k]);
      else
        parent[root(near[k])] = first;
    }
  }
  for (Index I = 0; I < node_count; ++I) parent[I] = root(I);
  return parent;
}

}  // namespace

std::vector<double> consistent_offsets(const ShapeTable& points, std::span<const double> weights,
                                       std::span<const double> boundary_terms, const VolumeTerms& plain) {
  const int dim = points.dimension;
  const Index N = static_cast<Index>(plain.magnitude.size());
  // Per part the shape functions join, the residuals' mean is out of the
  // Laplacian's reach (its closed boundary's integral of n, zero but for the
  // Gauss rule of a boundary facet a cut crosses): a constant per node,
  // mean / the node's support volume, takes it, as plain VCI would.
  const std::vector<Index> part = joined_parts(points, N);
  std::vector<double> support(N, 0.0), mean(N, 0.0), count(N, 0.0);  // mean, count: per part (its root node)
  for (Index p = 0; p < points.point_count(); ++p)
    for (Index I : points.neighbours.of(p)) support[I] += weights[p];
  std::vector<double> offsets(dim * points.neighbours.index.size(), 0.0);
  Vector eta;
  for (int i = 0; i < dim; ++i) {
    Vector r(N);
    for (Index I = 0; I < N; ++I) r[I] = boundary_terms[dim * I + i] - plain.gradient_sum[dim * I + i];
    std::fill(mean.begin(), mean.end(), 0.0), std::fill(count.begin(), count.end(), 0.0);
    for (Index I = 0; I < N; ++I) mean[part[I]] += r[I], count[part[I]] += 1.0;
    for (Index I = 0; I < N; ++I) r[I] -= mean[part[I]] / count[part[I]];
    const Vector xi = solve_laplacian(points, weights, plain.value_sum, r);
    point_means(points, xi, eta);
    for (Index p = 0; p < points.point_count(); ++p) {
      auto near = points.neighbours.of(p);
      const double* psi = points.values_of(p);
      const Index first = points.neighbours.start[p];
      for (std::size_t k = 0; k < near.size(); ++k) {
        const Index K = near[k];
        const double constant = support[K] > 0.0 ? mean[part[K]] / count[part[K]] / support[K] : 0.0;
        offsets[dim * (first + k) + i] = psi[k] * (xi[K] - eta[p]) + constant;
      }
    }
  }
  return offsets;
}

}  // namespace kerf

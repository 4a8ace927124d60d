#include "discretization/meshless/shape_table.h"

#include <algorithm>
#include <sstream>

#include "core/check.h"
#include "discretization/meshless/mls_shape.h"

namespace kerf {

namespace {

/// Fills row p of the table (values, gradients, condition, weight factors); false when singular.
bool fill_row(ShapeTable& t, const NodeSet& nodes, MlsBasis basis, const Vec3& point, Index p,
              const EnrichmentRule* enrichment, PointShapes& scratch) {
  const int dim = t.dimension;
  auto near = t.neighbours.of(p);
  const std::size_t s = t.neighbours.start[p];
  const bool ok = scratch.evaluate(nodes, basis, point, near, enrichment);
  t.condition[p] = scratch.shape.condition;
  if (!t.weight_factor.empty())
    std::copy(scratch.weight_factor.begin(), scratch.weight_factor.end(), t.weight_factor.begin() + s);
  if (!ok) return false;
  for (std::size_t k = 0; k < near.size(); ++k) {
    t.value[s + k] = scratch.shape.value[k];
    for (int i = 0; i < dim; ++i) t.gradient[dim * (s + k) + i] = scratch.shape.gradient[k][i];
  }
  return true;
}

/// Fills the rows `rows(i)`, i < count, in parallel; throws naming the first singular one.
template <class Rows>
void fill_rows(ShapeTable& t, const NodeSet& nodes, MlsBasis basis, std::span<const Vec3> points, Index count,
               Rows rows, const EnrichmentRule* enrichment, const std::string& what, const std::string& context,
               const std::string& remedy) {
  Index failed = -1;
#pragma omp parallel
  {
    PointShapes scratch;
#pragma omp for schedule(dynamic, 64)
    for (Index i = 0; i < count; ++i) {
      const Index p = rows(i);
      if (fill_row(t, nodes, basis, points[p], p, enrichment, scratch)) continue;
#pragma omp critical
      if (failed < 0 || p < failed) failed = p;
    }
  }
  if (failed < 0) return;
  const Index covering = static_cast<Index>(t.neighbours.of(failed).size());
  throw Error(singular_moment_message(t.dimension, basis, points[failed], covering, t.condition[failed], what, context,
                                      remedy));
}

}  // namespace

std::string singular_moment_message(int dim, MlsBasis basis, const Vec3& x, Index covering, double condition,
                                   const std::string& what, const std::string& context, const std::string& remedy) {
  std::ostringstream why;
  why << context << "the MLS moment matrix at " << what << " [" << x.transpose() << "] cannot be inverted ("
      << covering << " node supports cover it, condition number " << condition << "; the "
      << mls_basis_size(dim, basis) << "-term basis needs at least that many nodes not on one "
      << (dim == 3 ? "plane" : "line") << "); " << remedy;
  return why.str();
}

bool PointShapes::evaluate(const NodeSet& nodes, MlsBasis basis, const Vec3& point, std::span<const Index> near,
                           const EnrichmentRule* enrichment) {
  x_.clear();
  w_.clear();
  weight_factor.assign(near.size(), 1.0);
  double scale = 0.0;
  for (std::size_t k = 0; k < near.size(); ++k) {
    const Index I = near[k];
    x_.push_back(nodes.positions[I]);
    scale = std::max(scale, nodes.support[I]);
    WeightValue wI = quartic_weight(point, nodes.positions[I], nodes.support[I]);
    if (enrichment && enrichment->enriches(I)) {
      // (w g)' = w' g + w g'; the Hessian is not enriched (tables hold none).
      const WeightFactor g = enrichment->factor(I, point);
      wI.gradient = g.value * wI.gradient + wI.value * g.gradient;
      wI.value *= g.value;
      wI.hessian *= g.value;
      weight_factor[k] = g.value;
    }
    w_.push_back(wI);
  }
  return mls_shape_functions(nodes.dimension, basis, point, x_, w_, scale, false, shape);
}

ShapeTable shape_table(const NodeSet& nodes, const PointIndex& index, MlsBasis basis, std::span<const Vec3> points,
                       const std::string& what, const std::string& context, const std::string& remedy,
                       const EnrichmentRule* enrichment) {
  const int dim = nodes.dimension;
  ShapeTable t;
  t.dimension = dim;
  t.neighbours = covering_supports(index, nodes.support, points);
  const Index P = t.point_count();
  t.value.assign(t.neighbours.index.size(), 0.0);
  t.gradient.assign(dim * t.neighbours.index.size(), 0.0);
  t.condition.assign(P, 0.0);
  if (enrichment) t.weight_factor.assign(t.neighbours.index.size(), 1.0);
  fill_rows(t, nodes, basis, points, P, [](Index i) { return i; }, enrichment, what, context, remedy);
  return t;
}

void refresh_shape_rows(ShapeTable& table, const NodeSet& nodes, MlsBasis basis, std::span<const Vec3> points,
                        std::span<const Index> rows, const EnrichmentRule& enrichment, const std::string& what,
                        const std::string& context, const std::string& remedy) {
  if (table.weight_factor.empty()) table.weight_factor.assign(table.neighbours.index.size(), 1.0);
  fill_rows(table, nodes, basis, points, static_cast<Index>(rows.size()), [&](Index i) { return rows[i]; },
            &enrichment, what, context, remedy);
}

Mat3 deformation_gradient(const ShapeTable& table, Index point, const Vector& u) {
  const int dim = table.dimension;
  auto near = table.neighbours.of(point);
  const double* g = table.gradients_of(point);
  Mat3 F = Mat3::Identity();
  for (std::size_t k = 0; k < near.size(); ++k)
    for (int i = 0; i < dim; ++i)
      for (int l = 0; l < dim; ++l) F(i, l) += u[dim * near[k] + i] * g[dim * k + l];
  return F;
}

Vec3 interpolated_displacement(const ShapeTable& table, Index point, const Vector& u) {
  const int dim = table.dimension;
  auto near = table.neighbours.of(point);
  const double* phi = table.values_of(point);
  Vec3 value = Vec3::Zero();
  for (std::size_t k = 0; k < near.size(); ++k)
    for (int i = 0; i < dim; ++i) value[i] += phi[k] * u[dim * near[k] + i];
  return value;
}

void neighbour_dofs(const ShapeTable& table, Index point, std::vector<Index>& dofs) {
  const int dim = table.dimension;
  dofs.clear();
  for (Index K : table.neighbours.of(point))
    for (int i = 0; i < dim; ++i) dofs.push_back(dim * K + i);
}

}  // namespace kerf

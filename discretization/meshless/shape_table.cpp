#include "discretization/meshless/shape_table.h"

#include <algorithm>
#include <sstream>

#include "core/check.h"
#include "discretization/meshless/mls_shape.h"

namespace kerf {

namespace {

/// Scratch of one thread filling rows.
struct RowScratch {
  MlsShape shape;
  std::vector<Vec3> x;
  std::vector<WeightValue> w;
};

/// Fills row p of the table (values, gradients, condition, weight factors); false when singular.
bool fill_row(ShapeTable& t, const NodeSet& nodes, MlsBasis basis, const Vec3& point, Index p,
              const WeightEnrichment* enrichment, RowScratch& scratch) {
  const int dim = t.dimension;
  auto near = t.neighbours.of(p);
  const std::size_t s = t.neighbours.start[p];
  scratch.x.clear();
  scratch.w.clear();
  double scale = 0.0;
  for (std::size_t k = 0; k < near.size(); ++k) {
    const Index I = near[k];
    scratch.x.push_back(nodes.positions[I]);
    scale = std::max(scale, nodes.support[I]);
    WeightValue wI = quartic_weight(point, nodes.positions[I], nodes.support[I]);
    if (!t.weight_factor.empty()) t.weight_factor[s + k] = 1.0;
    if (enrichment && enrichment->enriches(I)) {
      // (w g)' = w' g + w g'; the Hessian is not enriched (tables hold none).
      const WeightFactor g = enrichment->factor(I, point);
      wI.gradient = g.value * wI.gradient + wI.value * g.gradient;
      wI.value *= g.value;
      wI.hessian *= g.value;
      t.weight_factor[s + k] = g.value;
    }
    scratch.w.push_back(wI);
  }
  MlsShape& shape = scratch.shape;
  const bool ok = mls_shape_functions(dim, basis, point, scratch.x, scratch.w, scale, false, shape);
  t.condition[p] = shape.condition;
  if (!ok) return false;
  for (std::size_t k = 0; k < near.size(); ++k) {
    t.value[s + k] = shape.value[k];
    for (int i = 0; i < dim; ++i) t.gradient[dim * (s + k) + i] = shape.gradient[k][i];
  }
  return true;
}

/// Fills the rows `rows(i)`, i < count, in parallel; throws naming the first singular one.
template <class Rows>
void fill_rows(ShapeTable& t, const NodeSet& nodes, MlsBasis basis, std::span<const Vec3> points, Index count,
               Rows rows, const WeightEnrichment* enrichment, const std::string& what, const std::string& context,
               const std::string& remedy) {
  Index failed = -1;
#pragma omp parallel
  {
    RowScratch scratch;
#pragma omp for schedule(dynamic, 64)
    for (Index i = 0; i < count; ++i) {
      const Index p = rows(i);
      if (fill_row(t, nodes, basis, points[p], p, enrichment, scratch)) continue;
#pragma omp critical
      if (failed < 0 || p < failed) failed = p;
    }
  }
  if (failed < 0) return;
  std::ostringstream why;
  why << context << "the MLS moment matrix at " << what << " [" << points[failed].transpose() << "] cannot be inverted ("
      << t.neighbours.of(failed).size() << " node supports cover it, condition number " << t.condition[failed]
      << "; the " << mls_basis_size(t.dimension, basis) << "-term basis needs at least that many nodes not on one "
      << (t.dimension == 3 ? "plane" : "line") << "); " << remedy;
  throw Error(why.str());
}

}  // namespace

ShapeTable shape_table(const NodeSet& nodes, const PointIndex& index, MlsBasis basis, std::span<const Vec3> points,
                       const std::string& what, const std::string& context, const std::string& remedy,
                       const WeightEnrichment* enrichment) {
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
                        std::span<const Index> rows, const WeightEnrichment& enrichment, const std::string& what,
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

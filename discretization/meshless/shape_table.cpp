#include "discretization/meshless/shape_table.h"

#include <algorithm>
#include <sstream>

#include "core/check.h"
#include "core/parallel_failure.h"
#include "discretization/meshless/mls_shape.h"

namespace kerf {

namespace {

/// Are row p's stored factors those just looked up (values and gradients)?
bool same_factors(const ShapeTable& t, Index p, const PointShapes& scratch) {
  const std::size_t s = t.neighbours.start[p];
  const std::vector<WeightFactor>& g = scratch.factors();
  for (std::size_t k = 0; k < g.size(); ++k)
    if (g[k].value != t.weight_factor[s + k] || g[k].gradient != t.weight_factor_gradient[s + k]) return false;
  return true;
}

enum class Filled { row, unchanged, singular };

/// A node's weight times its cut factor, (w g)' = w' g + w g' (either weight
/// type); false, and w as it was, where the factor is 1 and flat.
template <class Weight>
bool apply_factor(const WeightFactor& g, Weight& w) {
  if (g.value == 1.0 && g.gradient == Vec3::Zero()) return false;
  w.gradient = g.value * w.gradient + w.value * g.gradient;
  w.value *= g.value;
  return true;
}

// A cut can leave a point's side nodes thin along some direction: the linear
// fields they still tell apart are kept, and no steep gradient. Nodes that
// thin make the moment matrix's condition at least 1 / (1e-2 of their largest
// variance, itself below 0.1 in the scaled basis), so a better conditioned
// full basis (most points at a cut: 10 to 110) is kept without looking at the spread.
constexpr double surely_spread = 300.0;

/// Fills row p of the table (values, gradients, condition, weight factors);
/// with `only_if_changed`, leaves a row whose factors are unchanged as it is.
Filled fill_row(ShapeTable& t, const NodeSet& nodes, MlsBasis basis, const Vec3& point, Index p,
                const EnrichmentRule* enrichment, bool only_if_changed, PointShapes& scratch) {
  const int dim = t.dimension;
  auto near = t.neighbours.of(p);
  const std::size_t s = t.neighbours.start[p];
  scratch.look_up_factors(point, near, enrichment);
  if (only_if_changed && same_factors(t, p, scratch)) return Filled::unchanged;
  const bool ok = scratch.evaluate_looked_up(nodes, basis, point, near);
  t.condition[p] = scratch.shape.condition;
  if (!t.weight_factor.empty())
    for (std::size_t k = 0; k < near.size(); ++k) t.weight_factor[s + k] = scratch.factors()[k].value;
  if (!t.weight_factor_gradient.empty())
    for (std::size_t k = 0; k < near.size(); ++k) t.weight_factor_gradient[s + k] = scratch.factors()[k].gradient;
  if (!ok) return Filled::singular;
  if (!t.basis_directions.empty()) t.basis_directions[p] = static_cast<std::int8_t>(scratch.shape.spanned_directions);
  for (std::size_t k = 0; k < near.size(); ++k) {
    t.value[s + k] = scratch.shape.value[k];
    for (int i = 0; i < dim; ++i) t.gradient[dim * (s + k) + i] = scratch.shape.gradient[k][i];
  }
  return Filled::row;
}

/// Fills the rows `rows(i)`, i < count, in parallel (with `only_if_changed`,
/// those whose factors changed; `filled[i]` says which); throws naming the
/// first singular one, or with `singular` zeroes those rows and counts them.
template <class Rows>
void fill_rows(ShapeTable& t, const NodeSet& nodes, MlsBasis basis, std::span<const Vec3> points, Index count,
               Rows rows, const EnrichmentRule* enrichment, bool only_if_changed, std::vector<char>& filled,
               const std::string& what, const std::string& context, const std::string& remedy,
               Index* singular = nullptr, const std::function<void(Index)>& after_row = {}) {
  Index failed = -1;
  filled.assign(count, 0);
  for_each_with_scratch<PointShapes>(count, [&](Index i, PointShapes& scratch) {
    const Index p = rows(i);
    const Filled result = fill_row(t, nodes, basis, points[p], p, enrichment, only_if_changed, scratch);
    filled[i] = result != Filled::unchanged;
    if (result == Filled::singular && !singular) {
#pragma omp critical
      if (failed < 0 || p < failed) failed = p;
      return;
    }
    if (result == Filled::singular) {  // no shape functions there: the row adds nothing
      const std::size_t s0 = t.neighbours.start[p], s1 = t.neighbours.start[p + 1];
      std::fill(t.value.begin() + s0, t.value.begin() + s1, 0.0);
      std::fill(t.gradient.begin() + t.dimension * s0, t.gradient.begin() + t.dimension * s1, 0.0);
#pragma omp atomic
      ++*singular;
    }
    if (filled[i] && after_row) after_row(p);  // every row recomputed, zeroed ones too
  });
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
  look_up_factors(point, near, enrichment);
  return evaluate_looked_up(nodes, basis, point, near);
}

void PointShapes::look_up_factors(const Vec3& point, std::span<const Index> near, const EnrichmentRule* enrichment) {
  factors_.assign(near.size(), WeightFactor{});
  if (enrichment) enrichment->factors(near, point, factors_);
}

bool PointShapes::evaluate_looked_up(const NodeSet& nodes, MlsBasis basis, const Vec3& point,
                                     std::span<const Index> near, bool hessians) {
  if (basis == MlsBasis::linear && !hessians) return evaluate_linear(nodes, point, near);
  x_.clear();
  w_.clear();
  weight_factor.assign(near.size(), 1.0);
  double scale = 0.0;
  for (std::size_t k = 0; k < near.size(); ++k) {
    const Index I = near[k];
    x_.push_back(nodes.positions[I]);
    scale = std::max(scale, nodes.support[I]);
    WeightValue wI = quartic_weight(point, nodes.positions[I], nodes.support[I], hessians);
    const WeightFactor& g = factors_[k];
    if (hessians)  // (w g)'' without w g'' (see the header), from w' before the factor
      wI.hessian = g.value * wI.hessian + wI.gradient * g.gradient.transpose() + g.gradient * wI.gradient.transpose();
    if (apply_factor(g, wI)) weight_factor[k] = g.value;
    w_.push_back(wI);
  }
  const int dim = nodes.dimension;
  const bool cut_hides_nodes =
      std::any_of(weight_factor.begin(), weight_factor.end(), [](double g) { return g < 1.0; });
  // Without a cut a singular matrix is the support's fault, and is refused.
  if (!cut_hides_nodes) return mls_shape_functions(dim, basis, point, x_, w_, scale, hessians, shape);
  return keep_spanned_directions(dim, basis, point, scale, hessians,
                                 mls_shape_functions(dim, basis, point, x_, w_, scale, hessians, shape));
}

bool PointShapes::evaluate_linear(const NodeSet& nodes, const Vec3& point, std::span<const Index> near) {
  const std::size_t n = near.size();
  x_.resize(n);
  linear_w_.resize(n);
  weight_factor.assign(n, 1.0);
  double scale = 0.0;
  bool cut_hides_nodes = false;
  for (std::size_t k = 0; k < n; ++k) {
    const Index I = near[k];
    x_[k] = nodes.positions[I];
    scale = std::max(scale, nodes.support[I]);
    WeightWithGradient& wI = linear_w_[k];
    wI = quartic_weight_with_gradient(point, nodes.positions[I], nodes.support[I]);
    if (apply_factor(factors_[k], wI)) weight_factor[k] = factors_[k].value;
    cut_hides_nodes |= weight_factor[k] < 1.0;
  }
  const int dim = nodes.dimension;
  const bool full = mls_linear_shape_functions(dim, point, x_, linear_w_, scale, shape);
  // Without a cut a singular matrix is the support's fault, and is refused.
  if (!cut_hides_nodes || (full && shape.condition < surely_spread)) return full;
  w_.resize(n);
  for (std::size_t k = 0; k < n; ++k) w_[k] = WeightValue{linear_w_[k].value, linear_w_[k].gradient, Mat3::Zero()};
  return keep_spanned_directions(dim, MlsBasis::linear, point, scale, false, full);
}

bool PointShapes::keep_spanned_directions(int dim, MlsBasis basis, const Vec3& point, double scale, bool hessians,
                                          bool full) {
  if (full && shape.condition < surely_spread) return true;
  const NodeSpread spread = node_spread(dim, point, x_, w_, scale);
  if (full && spread.directions == dim) return true;
  return mls_spanned_linear(dim, point, x_, w_, spread, scale, hessians, shape);
}

ShapeTable shape_table(const NodeSet& nodes, const SupportIndex& index, MlsBasis basis, std::span<const Vec3> points,
                       const std::string& what, const std::string& context, const std::string& remedy,
                       const EnrichmentRule* enrichment, bool keep_factor_gradients, Index* singular,
                       Index group_size) {
  const int dim = nodes.dimension;
  ShapeTable t;
  t.dimension = dim;
  t.neighbours = covering_supports(index, points, group_size);
  const Index P = t.point_count();
  // Not zeroed: fill_rows writes every row on the thread that computes it (zeroes a singular one it counts,
  // throws at one it does not).
  t.value.resize(t.neighbours.index.size());
  t.gradient.resize(dim * t.neighbours.index.size());
  t.condition.assign(P, 0.0);
  if (enrichment) t.weight_factor.assign(t.neighbours.index.size(), 1.0);
  if (enrichment) t.basis_directions.assign(P, -1);
  if (enrichment && keep_factor_gradients) t.weight_factor_gradient.assign(t.neighbours.index.size(), Vec3::Zero());
  std::vector<char> filled;
  fill_rows(t, nodes, basis, points, P, [](Index i) { return i; }, enrichment, false, filled, what, context, remedy,
            singular);
  return t;
}

std::vector<Index> refresh_shape_rows(ShapeTable& table, const NodeSet& nodes, MlsBasis basis,
                                      std::span<const Vec3> points, std::span<const Index> rows,
                                      const EnrichmentRule& enrichment, const std::string& what,
                                      const std::string& context, const std::string& remedy, Index* singular,
                                      const std::function<void(Index)>& after_row) {
  const std::size_t slots = table.neighbours.index.size();
  if (table.weight_factor.empty()) {  // built before any cut: every factor was 1
    table.weight_factor.assign(slots, 1.0);
    table.weight_factor_gradient.assign(slots, Vec3::Zero());
  }
  if (table.basis_directions.empty()) table.basis_directions.assign(table.point_count(), -1);
  KERF_CHECK(table.weight_factor_gradient.size() == slots,
             "internal: a table refreshed for a growing cut must keep its factors' gradients (keep_factor_gradients)");
  std::vector<char> filled;
  fill_rows(table, nodes, basis, points, static_cast<Index>(rows.size()), [&](Index i) { return rows[i]; },
            &enrichment, true, filled, what, context, remedy, singular, after_row);
  std::vector<Index> recomputed;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (filled[i]) recomputed.push_back(rows[i]);
  return recomputed;
}

void append_rows(ShapeTable& table, const ShapeTable& more) {
  KERF_CHECK(table.dimension == more.dimension && table.weight_factor.empty() == more.weight_factor.empty() &&
                 table.weight_factor_gradient.empty() == more.weight_factor_gradient.empty(),
             "internal: appending rows of a table built another way");
  const Index offset = static_cast<Index>(table.neighbours.index.size());
  for (Index p = 0; p < more.point_count(); ++p) table.neighbours.start.push_back(offset + more.neighbours.start[p + 1]);
  auto append = [](auto& to, const auto& from) { to.insert(to.end(), from.begin(), from.end()); };
  append(table.neighbours.index, more.neighbours.index);
  append(table.value, more.value);
  append(table.gradient, more.gradient);
  append(table.condition, more.condition);
  append(table.weight_factor, more.weight_factor);
  append(table.weight_factor_gradient, more.weight_factor_gradient);
  append(table.basis_directions, more.basis_directions);
}

Index ShapeTable::reduced_basis_points() const {
  return static_cast<Index>(std::count_if(basis_directions.begin(), basis_directions.end(),
                                          [](std::int8_t r) { return r >= 0; }));
}

namespace {

/// F at one point with the dimension fixed: plain scalar accumulators (an
/// Eigen matrix updated in the loop waits on store-to-load forwarding).
template <int Dim>
Mat3 deformation_gradient_fixed(const ShapeTable& table, Index point, const Vector& u) {
  auto near = table.neighbours.of(point);
  const double* g = table.gradients_of(point);
  const double* x = u.data();
  double h[Dim][Dim] = {};
  for (std::size_t k = 0; k < near.size(); ++k) {
    const double* uk = x + Dim * near[k];
    const double* gk = g + Dim * k;
    for (int i = 0; i < Dim; ++i)
      for (int l = 0; l < Dim; ++l) h[i][l] += uk[i] * gk[l];
  }
  Mat3 F = Mat3::Identity();
  for (int i = 0; i < Dim; ++i)
    for (int l = 0; l < Dim; ++l) F(i, l) += h[i][l];
  return F;
}

}  // namespace

Mat3 deformation_gradient(const ShapeTable& table, Index point, const Vector& u) {
  return table.dimension == 3 ? deformation_gradient_fixed<3>(table, point, u)
                              : deformation_gradient_fixed<2>(table, point, u);
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

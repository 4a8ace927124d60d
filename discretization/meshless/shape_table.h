#pragma once
// MLS shape functions of a node set evaluated once at a batch of points (the
// nodes themselves for nodal integration, Gauss points for EFG), stored flat:
// point p's neighbours are neighbours.of(p), their values start at
// neighbours.start[p] and their gradients at dim * neighbours.start[p].
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "core/uninitialized_vector.h"
#include "discretization/enrichment/enrichment_rule.h"
#include "discretization/meshless/mls_linear.h"
#include "discretization/meshless/mls_shape.h"
#include "discretization/meshless/node_set.h"
#include "geometry/support_index.h"

namespace kerf {

struct ShapeTable {
  int dimension = 3;
  NeighborLists neighbours;       // per point: the nodes whose support covers it
  UninitializedVector<double> value;     // per (point, neighbour)
  UninitializedVector<double> gradient;  // per (point, neighbour), dimension entries (1/m)
  std::vector<double> condition;  // per point: condition number of the scaled moment matrix
  std::vector<double> weight_factor;  // per (point, neighbour): a cut's g_I (empty without cuts)
  std::vector<Vec3> weight_factor_gradient;  // per (point, neighbour): grad g_I (1/m; tables refreshed for cuts)
  // per point (with cuts): -1 the full basis, else the r directions of
  // mls_spanned_linear's basis (a cut left too few nodes on the point's side)
  std::vector<std::int8_t> basis_directions;
  /// Points whose basis a cut reduced (basis_directions >= 0).
  Index reduced_basis_points() const;
  Index point_count() const { return neighbours.size(); }
  const double* values_of(Index p) const { return value.data() + neighbours.start[p]; }
  const double* gradients_of(Index p) const { return gradient.data() + dimension * neighbours.start[p]; }
};

/// MLS shape functions at one point at a time, for callers that combine
/// several points (smoothed gradients) or fill table rows; one per thread.
class PointShapes {
 public:
  /// Shape functions of the nodes `near` (those whose support covers `point`)
  /// into `shape`, their cut factors g_I into weight_factor; false when the
  /// moment matrix is singular.
  bool evaluate(const NodeSet& nodes, MlsBasis basis, const Vec3& point, std::span<const Index> near,
                const EnrichmentRule* enrichment);
  /// The factors g_I of `near` at `point` alone (1 where not enriched), into factors().
  void look_up_factors(const Vec3& point, std::span<const Index> near, const EnrichmentRule* enrichment);
  /// evaluate() with the factors looked up last. With `hessians`, shape.hessian
  /// too: the enriched weight's Hessian is g H_w + grad w grad g^T + grad g
  /// grad w^T, without w H_g (the factors carry no second derivatives; the
  /// MLS Hessians still reproduce those of linear fields, zero, exactly).
  bool evaluate_looked_up(const NodeSet& nodes, MlsBasis basis, const Vec3& point, std::span<const Index> near,
                          bool hessians = false);
  const std::vector<WeightFactor>& factors() const { return factors_; }
  MlsShape shape;
  std::vector<double> weight_factor;

 private:
  /// evaluate_looked_up for a linear basis without Hessians (mls_linear_shape_functions).
  bool evaluate_linear(const NodeSet& nodes, const Vec3& point, std::span<const Index> near);
  /// The full basis failed or is ill-conditioned where a cut hides nodes: the
  /// linear fields the nodes on the point's side still tell apart (x_, w_ filled).
  bool keep_spanned_directions(int dim, MlsBasis basis, const Vec3& point, double scale, bool hessians, bool full);

  std::vector<Vec3> x_;
  std::vector<WeightValue> w_;
  std::vector<WeightWithGradient> linear_w_;
  std::vector<WeightFactor> factors_;
};

/// What a singular moment matrix at `what` [x] is told with: `context` (where
/// the setting comes from), how many supports cover x, the condition number, `remedy`.
std::string singular_moment_message(int dim, MlsBasis basis, const Vec3& x, Index covering, double condition,
                                   const std::string& what, const std::string& context, const std::string& remedy);

/// Shape functions at `points`, with the cuts' enriched weights w_I g_I when
/// `enrichment` is given. Throws when the moment matrix at a point cannot be
/// inverted: `context` (where the setting comes from), then the point
/// ("`what` [x y z]"), how many nodes cover it, and `remedy`.
/// With `keep_factor_gradients`, the factors' gradients are stored too
/// (refresh_shape_rows needs them; 24 bytes a slot). With `singular`, a
/// point whose matrix cannot be inverted gets a row of zeros, counted there,
/// instead of the refusal (for figures that must not stop a run).
/// `group_size`: covering_supports' (runs of points that lie close together).
ShapeTable shape_table(const NodeSet& nodes, const SupportIndex& index, MlsBasis basis, std::span<const Vec3> points,
                       const std::string& what, const std::string& context, const std::string& remedy,
                       const EnrichmentRule* enrichment = nullptr, bool keep_factor_gradients = false,
                       Index* singular = nullptr, Index group_size = 1);

/// Recomputes rows `rows` of a table built by shape_table at `points` (the
/// same points, same neighbour lists) with the cuts' current enrichment: the
/// cut grew. A row whose factors g_I (values and gradients) are those it was
/// built with is left as it is. Returns the rows recomputed, in the order
/// given. Throws like shape_table (or counts, with `singular`). `after_row`,
/// when given, is called with each row recomputed, on the thread that
/// recomputed it, as soon as it is (work that reads the row joins its pass).
std::vector<Index> refresh_shape_rows(ShapeTable& table, const NodeSet& nodes, MlsBasis basis, std::span<const Vec3> points,
                        std::span<const Index> rows, const EnrichmentRule& enrichment, const std::string& what,
                        const std::string& context, const std::string& remedy, Index* singular = nullptr,
                        const std::function<void(Index)>& after_row = {});

/// Appends the rows of `more` (a table of the same nodes, built the same way) after those of `table`.
void append_rows(ShapeTable& table, const ShapeTable& more);

/// F = I + sum_k u_{node_k} (x) grad phi_k at one point of a table.
Mat3 deformation_gradient(const ShapeTable& table, Index point, const Vector& u);
/// u_h = sum_k phi_k u_{node_k} at one point (m; z = 0 in 2D).
Vec3 interpolated_displacement(const ShapeTable& table, Index point, const Vector& u);
/// The dofs of one point's neighbours, node-major.
void neighbour_dofs(const ShapeTable& table, Index point, std::vector<Index>& dofs);

}  // namespace kerf

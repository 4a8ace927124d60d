#pragma once
// Naturally stabilized nodal integration (Hillman and Chen 2016), nodal
// integration's parameter-free stabilisation: the strain expanded about each
// node to first order, the energy of its gradient integrated with the node's
// cell second moments,
//   E_stab = 1/2 sum_L sum_i M_L,i eps_,i(u)_L : C : eps_,i(u)_L,
//   eps_,i(u)_L = sym(sum_J u_J (d_i grad psi_J(x_L))^T),
//   M_L,i = int over node L's dual cell of (x_i - x_L,i)^2,
// C the small-strain moduli at rest (the cross terms i != j are dropped, as
// the paper does). It holds the zero-energy modes with no parameter, scales
// with each node's own cell (graded node sets), and vanishes for every linear
// field (MLS second derivatives reproduce those of a linear field, zero), so
// for rigid motions of any size and in patch tests. Quadratic in u, as the
// hourglass term it replaces (meshless.stabilization: nsni).
#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include "discretization/enrichment/enrichment_rule.h"
#include "discretization/meshless/node_set.h"
#include "discretization/meshless/shape_table.h"
#include "problem/material.h"

namespace kerf {

class NaturalStabilization {
 public:
  /// The second derivatives at the nodes of the shape functions of `at_nodes`'
  /// rows (its neighbour lists), with the cuts' enrichment when given;
  /// `moments` the cells' second moments, per node (M_L, i).
  NaturalStabilization(const NodeSet& nodes, MlsBasis basis, const ShapeTable& at_nodes,
                       const EnrichmentRule* enrichment, const Lame& lame, std::vector<Vec3> moments);

  /// The cells' moments changed (a cut grew across them).
  void set_moments(std::vector<Vec3> moments) { moment_ = std::move(moments); }

  /// Recomputes the second derivatives of rows `rows` (a cut grew). A row
  /// whose moment matrix is singular (refused, or zeroed, by the table's own
  /// build) gets zeros: it adds nothing here either.
  void refresh(const NodeSet& nodes, MlsBasis basis, const ShapeTable& at_nodes, std::span<const Index> rows,
               const EnrichmentRule* enrichment);

  /// The forces of the terms of nodes [points.first, points.second) added into f.
  void add_forces(const ShapeTable& at_nodes, std::pair<Index, Index> points, const Vector& u, Vector& f) const;
  /// The energy of those terms (J).
  double energy(const ShapeTable& at_nodes, std::pair<Index, Index> points, const Vector& u) const;
  /// Node L's term's stiffness into the block of its neighbours (at_nodes' order, dim per node).
  void add_block(const ShapeTable& at_nodes, Index L, std::vector<double>& block) const;

  /// Bytes one force pass reads from the tables (second derivatives, moments).
  std::size_t table_bytes() const { return (hessian_.size() + 3 * moment_.size()) * sizeof(double); }

 private:
  int dim_;
  Lame lame_;
  std::vector<double> hessian_;  // per slot of at_nodes, dim x dim: d_a d_b psi (1/m^2)
  std::vector<Vec3> moment_;     // per node
  mutable std::vector<double> thread_forces_;
};

}  // namespace kerf

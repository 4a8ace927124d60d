#pragma once
// Integration points of a meshless weak form (the nodes themselves for nodal
// integration, Gauss points for EFG): weights, MLS gradients, and for each node
// the slots where it appears, so that forces are gathered node by node (no two
// threads write the same entry, no atomics) and results do not depend on the
// thread count.
#include <span>
#include <vector>

#include "discretization/meshless/shape_table.h"

namespace kerf {

class PointIntegration {
 public:
  /// `weights`: one per point of `shapes` (m^3; 2D: m^2).
  PointIntegration(ShapeTable shapes, std::vector<double> weights, Index node_count);

  const ShapeTable& shapes() const { return shapes_; }
  double weight(Index p) const { return weights_[p]; }
  Index point_count() const { return shapes_.point_count(); }
  std::span<const Index> neighbours(Index p) const { return shapes_.neighbours.of(p); }

  /// f_K = sum over the points p whose neighbours hold K of stress[p] grad phi_K(x_p),
  /// plus slot_force[slot] for each such slot when slot_force is not empty.
  /// stress: a dim x dim (top-left) matrix per point (N/m, i.e. weight x P); f: dim per node.
  void gather(std::span<const Mat3> stress, std::span<const Vec3> slot_force, Vector& f) const;

  /// Adds scale * G^T dPdF G into `block` ((n dim)^2, row-major over the point's
  /// n neighbours, dof order node-major): the material stiffness of point p.
  void add_material_block(Index p, const Mat9& dPdF, double scale, std::vector<double>& block) const;
  /// The dofs of point p's neighbours, node-major.
  void neighbour_dofs(Index p, std::vector<Index>& dofs) const;

 private:
  ShapeTable shapes_;
  std::vector<double> weights_;
  NeighborLists users_;           // per node: the slots holding it
  std::vector<Index> slot_point_; // per slot: its point
};

}  // namespace kerf

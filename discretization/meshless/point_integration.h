#pragma once
// Integration over points of a meshless weak form (the nodes themselves for
// nodal integration, Gauss points for EFG): the material stiffness of a
// point, and for EFG the gather of forces node by node through the
// transposed neighbour lists (no two threads write the same entry, no
// atomics, results independent of the thread count).
#include <functional>
#include <span>
#include <vector>

#include "discretization/discrete_body.h"
#include "discretization/meshless/shape_table.h"
#include "problem/material.h"

namespace kerf {

/// Adds scale * G^T dPdF G into `block` ((n dim)^2, row-major over the point's
/// n neighbours, dof order node-major): the material stiffness of one point.
void add_material_block(const ShapeTable& table, Index point, const Mat9& dPdF, double scale,
                        std::vector<double>& block);

/// Adds a method's own terms (stabilisation) to one point's block.
using BlockExtra = std::function<void(Index point, std::vector<double>& block)>;

/// K(u) of every point (weight w_p, the law's tangent at F_p, plus `extra`
/// when given) into the sink. Blocks are computed in parallel and handed to
/// the sink one at a time: the blocks of nearby points overlap almost
/// entirely, so there is no conflict-free order worth having.
void assemble_material_blocks(const ShapeTable& table, std::span<const double> weights, const MaterialLaw& law,
                              const Vector& u, const BlockSink& sink, const BlockExtra& extra = {});

/// Gauss points with weights, and for each node the slots where it appears.
class PointIntegration {
 public:
  /// `weights`: one per point of `shapes` (m^3; 2D: m^2).
  PointIntegration(ShapeTable shapes, std::vector<double> weights, Index node_count);

  const ShapeTable& shapes() const { return shapes_; }
  std::span<const double> weights() const { return weights_; }
  double weight(Index p) const { return weights_[p]; }
  Index point_count() const { return shapes_.point_count(); }

  /// f_K = sum over the points p whose neighbours hold K of stress[p] grad phi_K(x_p).
  /// stress: a dim x dim (top-left) matrix per point (weight x P, N m); f: dim per node.
  void gather(std::span<const Mat3> stress, Vector& f) const;

 private:
  ShapeTable shapes_;
  std::vector<double> weights_;
  NeighborLists users_;           // per node: the slots holding it
  std::vector<Index> slot_point_; // per slot: its point
};

}  // namespace kerf

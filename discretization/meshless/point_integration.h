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
/// dPdF must have major symmetry (every law here derives from an energy): half
/// the node pairs are computed, the other half mirrored.
void add_material_block(const ShapeTable& table, Index point, const Mat9& dPdF, double scale,
                        std::vector<double>& block);

/// Adds a method's own terms (stabilisation) to one point's block.
using BlockExtra = std::function<void(Index point, std::vector<double>& block)>;

/// The points of a table in groups whose blocks may reach a sink at the same
/// time: points binned into cubes at least as wide as two points sharing a
/// node can be apart (each point's neighbours lie within a radius of the
/// neighbours' centroid; the cube is twice the largest such radius), the
/// cubes coloured by the parity of their indices. Two cubes of one colour are
/// a cube apart: their points share no node.
struct PointSchedule {
  std::vector<std::vector<std::vector<Index>>> colours;  // colour -> cube -> points, in order
};
PointSchedule schedule_points(const ShapeTable& table, std::span<const Vec3> nodes);

/// K(u) of every point (weight w_p, the law's tangent at F_p, plus `extra`
/// when given) into the sink: colour by colour, the cubes of a colour in
/// parallel, each cube's points in order (the sum in each entry does not
/// depend on the thread count).
void assemble_material_blocks(const ShapeTable& table, const PointSchedule& schedule, std::span<const double> weights,
                              const MaterialLaw& law, const Vector& u, const BlockSink& sink,
                              const BlockExtra& extra = {});

/// Gauss points with weights, and for each node the slots where it appears.
class PointIntegration {
 public:
  /// `weights`: one per point of `shapes` (m^3; 2D: m^2); `nodes`: the node positions.
  PointIntegration(ShapeTable shapes, std::vector<double> weights, std::span<const Vec3> nodes);

  const ShapeTable& shapes() const { return shapes_; }
  std::span<const double> weights() const { return weights_; }
  double weight(Index p) const { return weights_[p]; }
  const PointSchedule& schedule() const { return schedule_; }
  Index point_count() const { return shapes_.point_count(); }

  /// f_K = sum over the points p whose neighbours hold K of stress[p] grad phi_K(x_p).
  /// stress: a dim x dim (top-left) matrix per point (weight x P, N m); f: dim per node.
  void gather(std::span<const Mat3> stress, Vector& f) const;

 private:
  ShapeTable shapes_;
  std::vector<double> weights_;
  PointSchedule schedule_;        // for assembly
  NeighborLists users_;           // per node: the slots holding it
  std::vector<Index> slot_point_; // per slot: its point
};

}  // namespace kerf

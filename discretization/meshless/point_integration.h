#pragma once
// Integration over points of a meshless weak form (the nodes themselves for
// nodal integration, Gauss points for EFG): the material stiffness of a
// point, and for EFG the gather of forces node by node through the
// transposed neighbour lists (no two threads write the same entry, no
// atomics, results independent of the thread count).
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

#include "discretization/body_capabilities.h"
#include "discretization/discrete_body.h"
#include "discretization/meshless/shape_table.h"
#include "problem/material.h"

namespace kerf {

/// Adds scale * G^T dPdF G into `block` ((block_nodes dim)^2, row-major, dof
/// order node-major): the material stiffness of one point, whose k-th
/// neighbour is node place[k] of the block. dPdF must have major symmetry
/// (every law here derives from an energy): half the node pairs are computed,
/// the other half mirrored. With `offsets` (dim per slot of the table, 1/m: VCI's),
/// the test side uses G + offsets (Petrov-Galerkin): every pair, not symmetric.
/// With `upper_half` (no offsets), only the node blocks at or above the
/// block's diagonal are written: the caller mirrors them once (mirror_upper_half).
void add_material_block(const ShapeTable& table, Index point, const Mat9& dPdF, double scale,
                        std::span<const Index> place, Index block_nodes, std::vector<double>& block,
                        std::span<const double> offsets = {}, bool upper_half = false);
/// Copies a symmetric block's node blocks above the diagonal onto those below
/// ((block_nodes dim)^2, row-major).
void mirror_upper_half(Index block_nodes, int dim, std::vector<double>& block);

/// Adds a method's own terms (stabilisation) to one point's block.
using BlockExtra = std::function<void(Index point, std::vector<double>& block)>;

/// The points of a table in groups of `group_size` consecutive points (a
/// cell's Gauss points: their blocks are summed before they reach the sink,
/// which then places each entry once a cell rather than once a point), the
/// groups binned into cubes at least as wide as two groups sharing a node can
/// be apart (a group's nodes lie within a radius of their centroid; the cube
/// is twice the largest such radius), the cubes coloured by the parity of
/// their indices. Two cubes of one colour are a cube apart: their groups share
/// no node.
struct PointSchedule {
  Index group_size = 1;
  std::vector<std::vector<std::vector<Index>>> colours;  // colour -> cube -> first point of each group, in order
};
PointSchedule schedule_points(const ShapeTable& table, std::span<const Vec3> nodes, Index group_size = 1);
/// The schedule of the points [points.first, points.second) alone (an MPI
/// rank's own), in the same order: the groups that start in the range (it
/// must start at a group's start).
PointSchedule only_points(PointSchedule schedule, std::pair<Index, Index> points);
/// The schedule of the groups whose `own_group` entry is set (group g: points
/// from g * group_size; groups past its end are not taken).
PointSchedule only_groups(PointSchedule schedule, std::span<const char> own_group);

/// Adds one point's term into the block of its group: the point's k-th
/// neighbour is node place[k] of the block's block_nodes.
using PointBlockTerm =
    std::function<void(Index point, std::span<const Index> place, Index block_nodes, std::vector<double>& block)>;

/// Every point's term into the sink, a group's points summed first: colour by
/// colour, the cubes of a colour in parallel, each cube's groups in order (the
/// sum in each entry does not depend on the thread count). `extra` (groups of
/// one point only) adds a method's own terms to the point's block. With
/// `upper_half`, the terms write a symmetric block's upper half only, and it
/// is mirrored once a group, before `extra` and the sink.
void assemble_point_blocks(const ShapeTable& table, const PointSchedule& schedule, const PointBlockTerm& term,
                           const BlockSink& sink, const BlockExtra& extra = {}, bool upper_half = false);

/// K(u) of every point (weight w_p, the law's tangent at F_p, plus `extra`)
/// into the sink, by assemble_point_blocks; `offsets` as add_material_block's.
void assemble_material_blocks(const ShapeTable& table, const PointSchedule& schedule, std::span<const double> weights,
                              const MaterialLaw& law, const Vector& u, const BlockSink& sink,
                              const BlockExtra& extra = {}, std::span<const double> offsets = {});

/// The diagonal of the material stiffness at rest (small strain, isotropic),
/// per dof (K, i): sum_p w_p (mu |grad psi_K(x_p)|^2 + (lambda + mu) d_i psi_K(x_p)^2).
std::vector<double> material_diagonal(const ShapeTable& table, std::span<const double> weights, const Lame& lame,
                                      Index node_count);
/// The same with the law's tangent at u, per dof (K, i): sum_p w_p sum_lm
/// d_l psi_K dP_il/dF_im d_m psi_K, the diagonal of K(u)'s material part.
std::vector<double> material_diagonal(const ShapeTable& table, std::span<const double> weights, const MaterialLaw& law,
                                      const Vector& u, Index node_count);

/// The consistent mass rho w_p phi_a phi_b (times the identity) of every point into the sink.
void assemble_mass_blocks(const ShapeTable& table, const PointSchedule& schedule, std::span<const double> weights,
                          double density, const BlockSink& sink);

/// Gauss points with weights, and for each node the slots where it appears.
class PointIntegration {
 public:
  /// `shapes` at `positions` (m), `weights` one per point (m^3; 2D: m^2);
  /// `nodes`: the node positions; `points_per_cell`: the points come cell by
  /// cell, this many each.
  PointIntegration(ShapeTable shapes, std::vector<Vec3> positions, std::vector<double> weights,
                   std::span<const Vec3> nodes, Index points_per_cell);

  const ShapeTable& shapes() const { return shapes_; }
  /// For a growing cut to recompute rows in place: the neighbour lists, hence
  /// the schedule and the transposed lists, must stay as they are.
  ShapeTable& shapes_in_place() { return shapes_; }
  std::span<const Vec3> positions() const { return positions_; }
  /// The points whose neighbours hold one of `nodes`, ascending.
  std::vector<Index> points_holding(std::span<const Index> nodes) const;
  std::span<const double> weights() const { return weights_; }
  double weight(Index p) const { return weights_[p]; }
  /// The schedule of the points' blocks through a sink (their cells' groups),
  /// made at its first call (the solvers' path, add_stiffness_rows, needs none).
  const PointSchedule& schedule() const;
  /// The points of a group (a cell's Gauss points).
  Index points_per_group() const { return points_per_group_; }
  Index point_count() const { return shapes_.point_count(); }

  /// f_K = sum over the points p whose neighbours hold K of stress[p] grad phi_K(x_p).
  /// stress: a dim x dim (top-left) matrix per point (weight x P, N m); f: dim per node.
  void gather(std::span<const Mat3> stress, Vector& f) const;
  /// Adds sum_p w_p G_p^T dPdF_p G_p into K, node by node: each node's rows
  /// gather the points holding it (no two threads write one entry, none is
  /// searched, no block is formed, the sums do not depend on the thread
  /// count). `tangents`: one per point, or one for every point (a linear
  /// law). K's pattern holds whole nodes (dim dofs each) and every node pair a
  /// point couples. The upper node blocks are added and the lower ones copied
  /// from them: K must hold a symmetric matrix before (zero, as the solvers pass it).
  void add_stiffness_rows(std::span<const Mat9> tangents, const CsrView& K) const;

 private:
  ShapeTable shapes_;
  std::vector<Vec3> positions_;
  std::vector<double> weights_;
  std::vector<Vec3> nodes_;       // the node positions, for the schedule
  Index points_per_group_;
  struct LazySchedule {
    std::once_flag made;
    PointSchedule schedule;
  };
  std::unique_ptr<LazySchedule> schedule_ = std::make_unique<LazySchedule>();
  NeighborLists users_;           // per node: the slots holding it
  std::vector<Index> user_point_; // per entry of users_.index: its slot's point (read with it, not through it)
};

}  // namespace kerf

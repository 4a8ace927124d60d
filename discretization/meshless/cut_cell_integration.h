#pragma once
// Nodal integration at a cut (direct gradients, meshless.cut_cells: split):
// the node set's cells a cut splits, and those its front runs through or next
// to, are integrated by their parts, one point per corner's part at its
// centroid weighted by its volume (a part a cut hands to another corner is
// that corner's, on its side: visible_dual_cells.h); the nodes' own points
// keep the rest of their cells. Follows the cuts as they grow.
#include <functional>
#include <span>
#include <vector>

#include "discretization/enrichment/cut_weights.h"
#include "discretization/meshless/node_cell_search.h"
#include "discretization/meshless/node_set.h"
#include "discretization/meshless/visible_dual_cells.h"

namespace kerf {

class CutCellIntegration {
 public:
  struct Points {
    std::vector<Vec3> position;
    std::vector<double> weight;       // m^3 (2D m^2)
    std::vector<double> node_volume;  // per node: its own point's weight, the rest of its cell
    std::vector<Vec3> node_moment;    // per node: that rest's second moments (NSNI)
    Index cells = 0;
  };

  /// The nodes' dual cells, split by the cuts present (`nodes.volume` takes the split volumes).
  CutCellIntegration(NodeSet& nodes, const NodeCellSearch& search, const CutWeights& cuts);

  /// Splits the cells the pieces since the last call cross; returns the
  /// nodes whose volume changed (`nodes.volume` updated).
  std::vector<Index> update(NodeSet& nodes, const NodeCellSearch& search, const CutWeights& cuts);
  /// The parts' points as the cuts stand; empty `position` without such cells.
  Points points(const NodeSet& nodes, const NodeCellSearch& search, const CutWeights& cuts) const;
  /// Every group of nodes a point may ever join, at any stage of the growth
  /// (the sparsity is fixed at set-up): per cell near the whole cut, the
  /// nodes whose support reaches the cell.
  void visit_reach(const NodeSet& nodes, const NodeCellSearch& search, const CutWeights& cuts,
                   const std::function<void(std::span<const Index>)>& visit) const;
  /// NSNI's second moments of the nodes' cells, split as the volumes are.
  const std::vector<Vec3>& second_moment() const { return visible_.second_moment(); }

 private:
  /// The cells a cut's front passes through or next to (a few cells' size).
  std::vector<Index> front_cells(const NodeSet& nodes, const NodeCellSearch& search, const CutWeights& cuts) const;

  VisibleDualCells visible_;
  std::vector<Index> pieces_taken_;  // per cut: pieces the volumes have seen
};

}  // namespace kerf

#pragma once
// Stabilised conforming nodal integration (SCNI, Chen et al. 2001) for the
// nodal method (meshless.gradient: smoothed): the gradient of shape function
// K at node I is its mean over I's cell Omega_I,
//   g_K(I) = 1/V_I [ sum over the cell's boundary of phi_K n dA
//                    - integral over the cuts inside the cell of (phi_K+ - phi_K-) n dA ],
// the divergence theorem on the cell minus the cut (n the cut's normal,
// phi_K+ on the side it points to), so the jump across a crack is not smeared
// into the strain. The cells are the barycentric dual cells of the node set's
// simplices (their measures are the nodal volumes), sampled as
// dual_cell_boundaries.h says; the cut's faces as cut_face_points.h says.
// Every rule is exact for linear fields, so the smoothed gradient of an
// affine field is exact (patch test).
#include <array>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "discretization/enrichment/cut_weights.h"
#include "discretization/meshless/dual_cell_boundaries.h"
#include "discretization/meshless/node_set.h"
#include "discretization/meshless/shape_table.h"
#include "geometry/support_index.h"

namespace kerf {

class CellLocator;

class SmoothedGradients {
 public:
  /// The boundary samples of every node's cell (nodes.cells must cover the
  /// nodes); `index`, over the nodes and their supports, must outlive this object.
  SmoothedGradients(const NodeSet& nodes, const SupportIndex& index);
  ~SmoothedGradients();

  /// Takes in the pieces `cuts` has gained since the last call: samples on
  /// both faces of each (in the cell holding each point, a hair off the
  /// face), and the boundaries of the cells a new piece crosses sampled
  /// again, split where the cut crosses them.
  void set_cuts(const CutWeights& cuts, const NodeSet& nodes);

  /// Shape functions at the nodes with smoothed gradients: per node, the
  /// nodes whose support covers it or a sample of its cell; values and cut
  /// factors at the node itself. Throws like shape_table (`context`, `remedy`).
  ShapeTable table(const NodeSet& nodes, MlsBasis basis, const EnrichmentRule* enrichment, const std::string& context,
                   const std::string& remedy) const;
  /// Recomputes rows of a table made by table() (the cut grew).
  void refresh(ShapeTable& table, std::span<const Index> rows, const NodeSet& nodes, MlsBasis basis,
               const EnrichmentRule& enrichment, const std::string& context, const std::string& remedy) const;

  /// Samples of node I's cell (boundary, then cut faces).
  std::vector<CellSample> samples_of(Index node) const;

 private:
  struct Row;
  /// Row I computed alone; throws (context, remedy) when a moment matrix is singular.
  void compute_row(Index I, const NodeSet& nodes, MlsBasis basis, const EnrichmentRule* enrichment,
                   const std::string& context, const std::string& remedy, Row& row) const;
  template <class Store>
  void compute_rows(std::span<const Index> rows, const NodeSet& nodes, MlsBasis basis, const EnrichmentRule* enrichment,
                    const std::string& context, const std::string& remedy, Store store) const;

  const SupportIndex& index_;
  std::unique_ptr<CellLocator> locator_;  // over nodes.cells, built at the first cut
  std::vector<Index> parts_start_{0};     // per node I: parts_[parts_start_[I] .. parts_start_[I + 1])
  std::vector<CellPart> parts_;
  std::vector<std::vector<CellSample>> samples_;  // per node: its boundary's samples
  std::vector<std::vector<CellSample>> on_cuts_;  // per node: samples on the cuts' faces inside the cell
  std::vector<double> radius_;                    // per node: farthest point of its cell (m)
  std::vector<Index> pieces_done_;                // per cut: pieces taken in by set_cuts
  double largest_radius_ = 0.0;
};

}  // namespace kerf

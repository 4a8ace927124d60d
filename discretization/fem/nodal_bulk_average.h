#pragma once
// The averaged-nodal-pressure simplex (Bonet and Burton 1998; Joldes, Wittek
// and Miller 2009): a linear tetrahedron (triangle) holds its law's bulk
// term k/2 m^2 (MaterialLaw::bulk_measure) at the nodes instead of the cells,
// which lifts the volumetric locking of linear simplices (one constraint per
// node, not one per cell):
//   m_a = sum over the cells e around node a of V_e / ((dim+1) V_a) m_e
//   energy = sum_e V_e (W(F_e) - k/2 m_e^2) + sum_a V_a k/2 m_a^2
// so each cell feels the mean of its nodes' m in its pressure, and the
// nodal term's stiffness V_a k b_a b_a^T (b_a = dm_a/du) couples every
// pair of nodes of the cells around a: its star.
#include <functional>
#include <span>
#include <vector>

#include "core/types.h"
#include "geometry/mesh.h"

namespace kerf {

class NodalBulkAverage {
 public:
  /// For a linear mesh (tet4 or tri3); `cell_volume` is each cell's reference measure.
  NodalBulkAverage(const Mesh& mesh, std::span<const double> cell_volume);

  /// m_a from the cells' m_e.
  void to_nodes(std::span<const double> cell, std::span<double> node) const;
  /// The mean of each of `mesh`'s cells' nodes' values (the mesh it was built for).
  void to_cells(const Mesh& mesh, std::span<const double> node, std::span<double> cell) const;
  /// sum_a V_a k/2 m_a^2 over the nodes a in [begin, end).
  double nodal_energy(std::span<const double> node, double k, Index begin, Index end) const;

  /// The star of node a: the nodes of the cells around it, sorted.
  std::span<const Index> star(Index a) const {
    return {star_nodes_.data() + star_start_[a], static_cast<std::size_t>(star_start_[a + 1] - star_start_[a])};
  }
  /// Receives node a's star dofs (dim per star node) and its dense row-major block.
  using StarSink = std::function<void(Index a, std::span<const Index> dofs, std::span<const double> block)>;
  /// For each node a in [begin, end): V_a k b_a b_a^T, b_a's entry for
  /// dof i of node n of cell e being V_e/((dim+1)V_a) sum_l dm_e(i,l) G_e(n,l),
  /// where `dm` is each cell's dm/dF and `gradient` each cell's dN/dX (npc x dim, row-major).
  void star_tangents(std::span<const Mat3> dm, std::span<const double> gradient, double k, Index begin,
                     Index end, const StarSink& sink) const;

 private:
  int dim_, npc_;
  std::vector<double> node_volume_;            // V_a
  std::vector<double> cell_volume_;            // V_e
  std::vector<Index> around_start_, around_;   // the cells around each node (CSR)
  std::vector<Index> star_start_, star_nodes_; // each node's star (CSR, sorted)
  std::vector<Index> slot_;                    // for each entry of around_: where the cell's nodes sit in the star (npc_ each)
};

}  // namespace kerf

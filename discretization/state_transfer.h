#pragma once
// Carrying a run's nodal fields (u, v, a) from one body onto the mesh of the
// next, remeshed or with more cells removed because a cut grew (FEM). Each new
// node takes the old field interpolated (the old body's interpolation_at) at a
// point a hair inside one of its own cells, so a node duplicated on a crack
// face takes its own side's value where the old mesh was already cut there,
// and the common value where the old mesh was whole (the cut opens from there).
#include <vector>

#include "discretization/discrete_body.h"
#include "geometry/mesh.h"

namespace kerf {

class StateTransfer {
 public:
  /// Throws, naming the node, when a node of `to` lies outside `from`.
  StateTransfer(const DiscreteBody& from, const Mesh& to);
  /// field over from's dofs (dim per node) -> over to's dofs.
  Vector operator()(const Vector& field) const;

 private:
  int dim_;
  std::vector<PointInterpolation> at_;  // per node of `to`
};

}  // namespace kerf

#pragma once
// Carrying a run's nodal fields (u, v, a) from one FEM mesh of a body to the
// next one, remeshed or with more cells removed because a cut grew. Each new
// node takes the old field interpolated at a point a hair inside one of its
// own cells, so a node duplicated on a crack face takes its own side's value
// where the old mesh was already cut there, and the common value where the
// old mesh was whole (the cut opens from there).
#include <vector>

#include "discretization/fem/fem_body.h"

namespace kerf {

class StateTransfer {
 public:
  /// Throws, naming the node, when a node of `to` lies outside `from`.
  StateTransfer(const FemBody& from, const FemBody& to);
  /// field over from's dofs (dim per node) -> over to's dofs.
  Vector operator()(const Vector& field) const;

 private:
  int dim_;
  std::vector<PointInterpolation> at_;  // per node of `to`
};

}  // namespace kerf

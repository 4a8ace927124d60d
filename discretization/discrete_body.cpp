#include "discretization/discrete_body.h"

#include <sstream>

namespace kerf {

std::string DiscreteBody::describe_dof(Index dof) const {
  const int dim = dofs_per_node();
  const Index node = dof / dim;
  std::ostringstream out;
  out << "dof " << dof << ": node " << node << " at [" << node_position(node).head(dim).transpose() << "] m, component "
      << "xyz"[dof % dim];
  return out.str();
}

}  // namespace kerf

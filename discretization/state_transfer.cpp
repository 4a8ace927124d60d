#include "discretization/state_transfer.h"

#include "core/check.h"

namespace kerf {

StateTransfer::StateTransfer(const DiscreteBody& from, const Mesh& mesh) : dim_(mesh.dimension) {
  const int corners = mesh.dimension + 1;
  // A cell of each node (its first), and a point 1e-6 of the way to that cell's centroid.
  std::vector<Index> cell_of(mesh.node_count(), -1);
  for (Index c = mesh.cell_count() - 1; c >= 0; --c)
    for (Index n : mesh.cell(c)) cell_of[n] = c;
  at_.resize(mesh.node_count());
  for (Index n = 0; n < mesh.node_count(); ++n) {
    KERF_CHECK(cell_of[n] >= 0, "state transfer: node ", n, " of the new mesh belongs to no cell");
    Vec3 centroid = Vec3::Zero();
    for (int a = 0; a < corners; ++a) centroid += mesh.nodes[mesh.cell(cell_of[n])[a]] / corners;
    const Vec3 inside = mesh.nodes[n] + 1e-6 * (centroid - mesh.nodes[n]);
    auto at = from.interpolation_at(inside);
    KERF_CHECK(at, "state transfer: node ", n, " of the new mesh at [", mesh.nodes[n].transpose(),
               "] lies outside the previous mesh; expected the new mesh to cover no more than the old one");
    at_[n] = std::move(*at);
  }
}

Vector StateTransfer::operator()(const Vector& field) const {
  Vector out = Vector::Zero(dim_ * static_cast<Index>(at_.size()));
  for (std::size_t n = 0; n < at_.size(); ++n)
    for (std::size_t k = 0; k < at_[n].nodes.size(); ++k)
      for (int i = 0; i < dim_; ++i) out[dim_ * n + i] += at_[n].weights[k] * field[dim_ * at_[n].nodes[k] + i];
  return out;
}

}  // namespace kerf

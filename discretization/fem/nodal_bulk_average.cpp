#include "discretization/fem/nodal_bulk_average.h"

#include <Eigen/Dense>
#include <algorithm>

#include "core/check.h"

namespace kerf {

NodalBulkAverage::NodalBulkAverage(const Mesh& mesh, std::span<const double> cell_volume)
    : dim_(mesh.dimension), npc_(mesh.nodes_per_cell()), cell_volume_(cell_volume.begin(), cell_volume.end()) {
  KERF_CHECK(mesh.order == 1, "internal: the averaged-nodal-pressure element needs linear cells");
  const Index nodes = mesh.node_count(), cells = mesh.cell_count();
  node_volume_.assign(nodes, 0.0);
  around_start_.assign(nodes + 1, 0);
  for (Index c = 0; c < cells; ++c)
    for (Index n : mesh.cell(c)) {
      node_volume_[n] += cell_volume_[c] / npc_;
      ++around_start_[n + 1];
    }
  for (Index n = 0; n < nodes; ++n) around_start_[n + 1] += around_start_[n];
  around_.resize(around_start_[nodes]);
  std::vector<Index> fill(around_start_.begin(), around_start_.end() - 1);
  for (Index c = 0; c < cells; ++c)
    for (Index n : mesh.cell(c)) around_[fill[n]++] = c;
  // Each star: the sorted union of its cells' nodes, and where each cell's nodes sit in it.
  star_start_.assign(nodes + 1, 0);
  slot_.resize(around_.size() * npc_);
  std::vector<Index> star;
  for (Index a = 0; a < nodes; ++a) {
    star.clear();
    for (Index k = around_start_[a]; k < around_start_[a + 1]; ++k)
      for (Index n : mesh.cell(around_[k])) star.push_back(n);
    std::sort(star.begin(), star.end());
    star.erase(std::unique(star.begin(), star.end()), star.end());
    star_nodes_.insert(star_nodes_.end(), star.begin(), star.end());
    star_start_[a + 1] = static_cast<Index>(star_nodes_.size());
    for (Index k = around_start_[a]; k < around_start_[a + 1]; ++k) {
      auto nodes_of = mesh.cell(around_[k]);
      for (int j = 0; j < npc_; ++j)
        slot_[k * npc_ + j] = static_cast<Index>(std::lower_bound(star.begin(), star.end(), nodes_of[j]) - star.begin());
    }
  }
}

void NodalBulkAverage::to_nodes(std::span<const double> cell, std::span<double> node) const {
  const Index nodes = static_cast<Index>(node_volume_.size());
#pragma omp parallel for schedule(static)
  for (Index a = 0; a < nodes; ++a) {
    double sum = 0.0;
    for (Index k = around_start_[a]; k < around_start_[a + 1]; ++k) sum += cell_volume_[around_[k]] * cell[around_[k]];
    node[a] = node_volume_[a] > 0.0 ? sum / (npc_ * node_volume_[a]) : 0.0;
  }
}

void NodalBulkAverage::to_cells(const Mesh& mesh, std::span<const double> node, std::span<double> cell) const {
  const Index cells = mesh.cell_count();
#pragma omp parallel for schedule(static)
  for (Index c = 0; c < cells; ++c) {
    double sum = 0.0;
    for (Index n : mesh.cell(c)) sum += node[n];
    cell[c] = sum / npc_;
  }
}

double NodalBulkAverage::nodal_energy(std::span<const double> node, double k, Index begin, Index end) const {
  double sum = 0.0;
  for (Index a = begin; a < end; ++a) sum += node_volume_[a] * node[a] * node[a];
  return 0.5 * k * sum;
}

void NodalBulkAverage::star_tangents(std::span<const Mat3> dm, std::span<const double> gradient, double k,
                                     Index begin, Index end, const StarSink& sink) const {
  Eigen::VectorXd b;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> block;
  std::vector<Index> dofs;
  for (Index a = begin; a < end; ++a) {
    const auto nodes = star(a);
    const Index size = static_cast<Index>(nodes.size()) * dim_;
    if (size == 0) continue;
    b.setZero(size);
    for (Index k = around_start_[a]; k < around_start_[a + 1]; ++k) {
      const Index c = around_[k];
      const double w = cell_volume_[c] / (npc_ * node_volume_[a]);
      const double* G = &gradient[static_cast<std::size_t>(c) * npc_ * dim_];
      for (int j = 0; j < npc_; ++j)
        for (int i = 0; i < dim_; ++i) {
          double s = 0.0;
          for (int l = 0; l < dim_; ++l) s += dm[c](i, l) * G[j * dim_ + l];
          b[slot_[k * npc_ + j] * dim_ + i] += w * s;
        }
    }
    block.noalias() = (node_volume_[a] * k) * b * b.transpose();
    dofs.resize(size);
    for (std::size_t n = 0; n < nodes.size(); ++n)
      for (int i = 0; i < dim_; ++i) dofs[n * dim_ + i] = dim_ * nodes[n] + i;
    sink(a, dofs, std::span<const double>(block.data(), static_cast<std::size_t>(size * size)));
  }
}

}  // namespace kerf

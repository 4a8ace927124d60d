#include "geometry/point_location.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace kerf {
namespace {

/// Reference coordinates of x in cell c, clamped onto the cell when x lies
/// outside; `outside` is how far outside (m), 0 inside.
CellPoint cell_point(const Mesh& mesh, Index c, const Vec3& x, double& outside) {
  const int dim = mesh.dimension;
  auto n = mesh.cell(c);
  const Vec3& x0 = mesh.nodes[n[0]];
  Mat3 J = Mat3::Identity();
  for (int k = 0; k < dim; ++k) J.col(k) = mesh.nodes[n[k + 1]] - x0;
  Vec3 local = J.inverse() * (x - x0);
  if (dim == 2) local.z() = 0.0;
  // How far outside the reference simplex, measured in physical length.
  Vec3 clamped = local.cwiseMax(0.0);
  double sum = clamped.head(dim).sum();
  if (sum > 1.0) clamped.head(dim) /= sum;
  outside = (J * (clamped - local)).norm();
  return {c, outside > 0.0 ? clamped : local};
}

}  // namespace

std::optional<CellPoint> locate_point(const Mesh& mesh, const Vec3& x, double distance) {
  CellPoint best;
  double best_outside = std::numeric_limits<double>::infinity();
  for (Index c = 0; c < mesh.cell_count(); ++c) {
    double outside = 0.0;
    CellPoint p = cell_point(mesh, c, x, outside);
    if (outside < best_outside) best_outside = outside, best = p;
    if (outside == 0.0) break;
  }
  if (best.cell < 0 || best_outside > distance) return std::nullopt;
  return best;
}

CellLocator::CellLocator(const Mesh& mesh) {
  const int dim = mesh.dimension;
  const Index C = mesh.cell_count();
  if (C == 0) return;
  const auto [low, high] = bounding_box(mesh);
  const Vec3 extent = (high - low).cwiseMax(1e-300);
  double volume = 1.0;
  for (int k = 0; k < dim; ++k) volume *= extent[k];
  bin_size_ = std::pow(volume / C, 1.0 / dim);  // about one cell per bin
  origin_ = low;
  for (int k = 0; k < dim; ++k) bins_[k] = std::max<Index>(1, static_cast<Index>(std::ceil(extent[k] / bin_size_)));
  const std::size_t total = static_cast<std::size_t>(bins_[0]) * bins_[1] * bins_[2];
  std::vector<std::vector<Index>> lists(total);
  for (Index c = 0; c < C; ++c) {
    std::array<Index, 3> from{0, 0, 0}, to{0, 0, 0};
    for (int k = 0; k < dim; ++k) {
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (int a = 0; a <= dim; ++a) {
        lo = std::min(lo, mesh.nodes[mesh.cell(c)[a]][k]);
        hi = std::max(hi, mesh.nodes[mesh.cell(c)[a]][k]);
      }
      from[k] = std::clamp<Index>(static_cast<Index>(std::floor((lo - origin_[k]) / bin_size_)), 0, bins_[k] - 1);
      to[k] = std::clamp<Index>(static_cast<Index>(std::floor((hi - origin_[k]) / bin_size_)), 0, bins_[k] - 1);
    }
    for (Index i = from[0]; i <= to[0]; ++i)
      for (Index j = from[1]; j <= to[1]; ++j)
        for (Index l = from[2]; l <= to[2]; ++l) lists[(static_cast<std::size_t>(l) * bins_[1] + j) * bins_[0] + i].push_back(c);
  }
  start_.assign(total + 1, 0);
  for (std::size_t b = 0; b < total; ++b) start_[b + 1] = start_[b] + static_cast<Index>(lists[b].size());
  cells_.reserve(start_.back());
  for (const auto& list : lists) cells_.insert(cells_.end(), list.begin(), list.end());
}

Index CellLocator::bin_of(const Vec3& x) const {
  std::array<Index, 3> b{0, 0, 0};
  for (int k = 0; k < 3; ++k) {
    const double at = std::floor((x[k] - origin_[k]) / bin_size_);
    if (at < 0.0 || at >= bins_[k]) return -1;
    b[k] = static_cast<Index>(at);
  }
  return (b[2] * bins_[1] + b[1]) * bins_[0] + b[0];
}

std::optional<CellPoint> CellLocator::locate(const Mesh& mesh, const Vec3& x, double distance) const {
  const Index bin = start_.empty() ? -1 : bin_of(x);
  if (bin >= 0)
    for (Index i = start_[bin]; i < start_[bin + 1]; ++i) {
      double outside = 0.0;
      CellPoint p = cell_point(mesh, cells_[i], x, outside);
      if (outside == 0.0) return p;
    }
  // Outside every cell (near the boundary, or on no cell at all): the nearest, by looking at all.
  return locate_point(mesh, x, distance);
}

}  // namespace kerf

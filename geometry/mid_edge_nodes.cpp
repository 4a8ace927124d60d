#include "geometry/mid_edge_nodes.h"

#include <algorithm>
#include <unordered_map>

#include "core/check.h"
#include "core/element_types.h"

namespace kerf {

std::vector<std::size_t> add_mid_edge_nodes(int dimension, std::span<const std::size_t> linear_cells,
                                            std::vector<double>& coordinates) {
  const ElementDescriptor& linear = element_descriptor(dimension, 1);
  const ElementDescriptor& quadratic = element_descriptor(dimension, 2);
  const std::size_t corners = static_cast<std::size_t>(linear.nodes);
  const std::size_t cells = linear_cells.size() / corners;
  std::vector<std::size_t> raised;
  raised.reserve(cells * static_cast<std::size_t>(quadratic.nodes));
  KERF_CHECK(coordinates.size() / 3 < (std::size_t{1} << 32), "a mesh of ", coordinates.size() / 3,
             " nodes is raised to second order only below 2^32 nodes");
  std::unordered_map<std::uint64_t, std::size_t> middle_of;  // edge (low, high position) -> its mid-point
  middle_of.reserve(cells * quadratic.edges.size() / 2);
  for (std::size_t c = 0; c < cells; ++c) {
    const std::size_t* corner = &linear_cells[c * corners];
    raised.insert(raised.end(), corner, corner + corners);
    for (const auto& [a, b] : quadratic.edges) {
      const std::size_t low = std::min(corner[a], corner[b]), high = std::max(corner[a], corner[b]);
      const auto [it, added] = middle_of.try_emplace((static_cast<std::uint64_t>(low) << 32) | high,
                                                     coordinates.size() / 3);
      if (added)
        for (int k = 0; k < 3; ++k) coordinates.push_back(0.5 * (coordinates[3 * low + k] + coordinates[3 * high + k]));
      raised.push_back(it->second);
    }
  }
  return raised;
}

Mesh with_mid_edge_nodes(const Mesh& linear) {
  KERF_CHECK(linear.order == 1, "internal: a mesh of order ", linear.order, " raised to second order");
  std::vector<double> coordinates;
  coordinates.reserve(3 * linear.nodes.size());
  for (const Vec3& p : linear.nodes) coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
  const std::vector<std::size_t> corners(linear.cells.begin(), linear.cells.end());
  const std::vector<std::size_t> cells = add_mid_edge_nodes(linear.dimension, corners, coordinates);
  Mesh raised;
  raised.dimension = linear.dimension;
  raised.order = 2;
  for (std::size_t n = 0; n < coordinates.size(); n += 3)
    raised.nodes.emplace_back(coordinates[n], coordinates[n + 1], coordinates[n + 2]);
  raised.cells.assign(cells.begin(), cells.end());
  return raised;
}

}  // namespace kerf

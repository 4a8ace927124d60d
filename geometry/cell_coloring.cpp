#include "geometry/cell_coloring.h"

#include <bitset>

#include "core/check.h"

namespace kerf {

CellColoring color_cells(const Mesh& mesh) {
  constexpr int max_colors = 256;
  std::vector<std::bitset<max_colors>> used(mesh.nodes.size());
  std::vector<int> color(mesh.cell_count());
  int colors = 0;
  for (Index c = 0; c < mesh.cell_count(); ++c) {
    std::bitset<max_colors> taken;
    for (Index n : mesh.cell(c)) taken |= used[n];
    int k = 0;
    while (k < max_colors && taken[k]) ++k;
    KERF_CHECK(k < max_colors, "cell colouring needs more than ", max_colors, " colours (a node in too many cells?)");
    color[c] = k;
    colors = std::max(colors, k + 1);
    for (Index n : mesh.cell(c)) used[n].set(k);
  }
  CellColoring out;
  out.start.assign(colors + 1, 0);
  for (int k : color) ++out.start[k + 1];
  for (int k = 0; k < colors; ++k) out.start[k + 1] += out.start[k];
  std::vector<Index> next(out.start.begin(), out.start.end() - 1);
  out.cells.resize(mesh.cell_count());
  for (Index c = 0; c < mesh.cell_count(); ++c) out.cells[next[color[c]]++] = c;
  return out;
}

}  // namespace kerf

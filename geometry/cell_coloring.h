#pragma once
// Greedy colouring of cells so that no two cells of one colour share a node:
// the cells of a colour can be assembled in parallel without write conflicts.
#include <vector>

#include "geometry/mesh.h"

namespace kerf {

/// Cells grouped by colour: colour k holds cells[start[k] .. start[k+1]).
struct CellColoring {
  std::vector<Index> cells;
  std::vector<Index> start;
  int color_count() const { return static_cast<int>(start.size()) - 1; }
};

CellColoring color_cells(const Mesh& mesh);

}  // namespace kerf

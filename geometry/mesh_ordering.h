#pragma once
// Renumbers a mesh for memory locality: nodes in reverse Cuthill-McKee order
// (neighbours get nearby numbers, so matrix rows and the vectors they touch
// stay close), cells sorted by their lowest node.
#include "geometry/mesh.h"

namespace kerf {

void order_for_locality(Mesh& mesh);

}  // namespace kerf

#include "discretization/cut_snapshot.h"

#include <algorithm>
#include <limits>

#include "core/check.h"

namespace kerf {

void cut_snapshot(const CutTimeline& cuts, double t, const DiscreteBody& body, const Vector& u, BodySnapshot& out) {
  out = BodySnapshot{};
  const int dim = body.dofs_per_node();
  const int corners = dim;  // segment ends, triangle corners
  OutputField opening{"opening", 3, {}};
  OutputField appears{"appears", 1, {}}, which{"cut", 1, {}};
  for (Index c = 0; c < cuts.cut_count(); ++c) {
    const CutSurface& cut = cuts.surface(c);
    const Index pieces = cut.pieces_at(t);
    if (pieces == 0) continue;
    // Just off the faces, on either side: the displacement jump across the cut.
    const double delta = 1e-6 * cut.extent;
    const Index first_point = static_cast<Index>(out.points.size());
    const Index vertices = pieces + corners - 1;
    for (Index v = 0; v < vertices; ++v) {
      Vec3 normal = Vec3::Zero();  // mean of the pieces that share the vertex
      for (Index k = std::max<Index>(0, v - corners + 1); k <= std::min(v, pieces - 1); ++k)
        normal += cut.pieces[k].normal;
      normal.normalize();
      Vec3 jump = Vec3::Zero();
      try {
        auto plus = body.interpolation_at(cut.vertices[v] + delta * normal);
        auto minus = body.interpolation_at(cut.vertices[v] - delta * normal);
        // Outside the body: no opening.
        if (plus && minus) jump = interpolate(*plus, u, dim) - interpolate(*minus, u, dim);
      } catch (const Error&) {
        // Output only: a vertex where too few nodes see either side shows NaN, not a stopped run.
        jump = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
      }
      out.points.push_back(cut.vertices[v]);
      opening.values.insert(opening.values.end(), {jump.x(), jump.y(), jump.z()});
    }
    for (Index k = 0; k < pieces; ++k) {
      for (int corner = 0; corner < corners; ++corner) {
        // Odd strip triangles are wound (k+1, k, k+2), as the pieces are.
        const Index v = dim == 3 && k % 2 == 1 && corner < 2 ? k + 1 - corner : k + corner;
        out.connectivity.push_back(first_point + v);
      }
      out.offsets.push_back(static_cast<Index>(out.connectivity.size()));
      out.cell_types.push_back(dim == 2 ? 3 : 5);  // VTK_LINE, VTK_TRIANGLE
      appears.values.push_back(cut.appears[k]);
      which.values.push_back(static_cast<double>(c));
    }
  }
  out.point_fields.push_back(std::move(opening));
  out.cell_fields.push_back(std::move(appears));
  out.cell_fields.push_back(std::move(which));
}

}  // namespace kerf

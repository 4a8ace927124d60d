#include "mls_rows_floor.h"

#include <algorithm>

#include "discretization/meshless/mls_linear.h"

namespace kerf::bench {

void mls_rows_floor(const MlsRowsFloorData& d, std::span<const Index> rows, std::vector<double>& value,
                    std::vector<double>& gradient) {
  const Index count = static_cast<Index>(rows.size());
#pragma omp parallel
  {
    std::vector<Vec3> near;
    std::vector<WeightWithGradient> w;
    MlsShape shape;
#pragma omp for schedule(dynamic, 16)
    for (Index r = 0; r < count; ++r) {
      const Index p = rows[r], s0 = d.start[p], s1 = d.start[p + 1];
      const Vec3& x = d.point[p];
      double h = 0.0;
      near.clear(), w.clear();
      for (Index s = s0; s < s1; ++s) {  // the quartic weight times the factor (and its gradient)
        const Index I = d.index[s];
        h = std::max(h, d.support[I]);
        near.push_back(d.node[I]);
        WeightWithGradient wI = quartic_weight_with_gradient(x, d.node[I], d.support[I]);
        wI.value *= d.factor[s], wI.gradient *= d.factor[s];
        w.push_back(wI);
      }
      mls_linear_shape_functions(3, x, near, w, h, shape);
      for (Index s = s0; s < s1; ++s) {
        value[s] = shape.value[s - s0];
        for (int k = 0; k < 3; ++k) gradient[3 * s + k] = shape.gradient[s - s0][k];
      }
    }
  }
}

}  // namespace kerf::bench

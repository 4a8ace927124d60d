#include "mls_rows_floor.h"

#include <Eigen/Dense>
#include <algorithm>

namespace kerf::bench {

void mls_rows_floor(const MlsRowsFloorData& d, std::span<const Index> rows, std::vector<double>& value,
                    std::vector<double>& gradient) {
  using Vec4 = Eigen::Vector4d;
  using Mat4 = Eigen::Matrix4d;
  const Index count = static_cast<Index>(rows.size());
#pragma omp parallel for schedule(dynamic, 16)
  for (Index r = 0; r < count; ++r) {
    const Index p = rows[r], s0 = d.start[p], s1 = d.start[p + 1];
    const Vec3& x = d.point[p];
    double h = 0.0;
    for (Index s = s0; s < s1; ++s) h = std::max(h, d.support[d.index[s]]);
    Mat4 A = Mat4::Zero(), dA[3] = {Mat4::Zero(), Mat4::Zero(), Mat4::Zero()};
    auto weight = [&](Index s, double& w, Vec3& dw) {  // quartic weight times the factor
      const Vec3 e = x - d.node[d.index[s]];
      const double radius = d.support[d.index[s]], q = e.norm() / radius, a = 1.0 - q;
      w = q < 1.0 ? d.factor[s] * (1.0 - 6.0 * q * q + 8.0 * q * q * q - 3.0 * q * q * q * q) : 0.0;
      dw = q < 1.0 ? Vec3(-12.0 * a * a * d.factor[s] / (radius * radius) * e) : Vec3::Zero();
    };
    auto basis = [&](Index s) {
      const Vec3 xi = (d.node[d.index[s]] - x) / h;
      return Vec4(1.0, xi[0], xi[1], xi[2]);
    };
    for (Index s = s0; s < s1; ++s) {
      double w;
      Vec3 dw;
      weight(s, w, dw);
      const Vec4 q = basis(s);
      const Mat4 qqT = q * q.transpose();
      A += w * qqT;
      for (int k = 0; k < 3; ++k) dA[k] += dw[k] * qqT;
    }
    const Mat4 Ainv = A.inverse();
    const Vec4 gamma = Ainv.col(0);  // A^-1 p(0), p(0) = e_0
    Vec4 dgamma[3];
    for (int k = 0; k < 3; ++k) dgamma[k] = Ainv * (Vec4::Unit(1 + k) / h - dA[k] * gamma);
    for (Index s = s0; s < s1; ++s) {
      double w;
      Vec3 dw;
      weight(s, w, dw);
      const Vec4 q = basis(s);
      const double gq = gamma.dot(q);
      value[s] = gq * w;
      for (int k = 0; k < 3; ++k) gradient[3 * s + k] = dgamma[k].dot(q) * w + gq * dw[k];
    }
  }
}

}  // namespace kerf::bench

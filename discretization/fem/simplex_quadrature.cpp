#include "discretization/fem/simplex_quadrature.h"

#include <cmath>
#include <numbers>

namespace kerf {

QuadratureRule gauss_legendre_unit(int n) {
  QuadratureRule rule;
  for (int i = 0; i < n; ++i) {
    // Newton on P_n from the Chebyshev guess.
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      if (n == 1) p0 = 1.0, p1 = x;
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      double step = p1 / dp;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    double w = 2.0 / ((1.0 - x * x) * dp * dp);
    rule.points.push_back(Vec3(0.5 * (x + 1.0), 0.0, 0.0));
    rule.weights.push_back(0.5 * w);
  }
  return rule;
}

QuadratureRule simplex_quadrature(int dim, int degree) {
  QuadratureRule rule;
  if (degree <= 1) {  // centroid
    double measure = dim == 1 ? 1.0 : dim == 2 ? 0.5 : 1.0 / 6.0;
    rule.points.push_back(Vec3::Constant(1.0 / (dim + 1)).cwiseProduct(Vec3(1, dim > 1, dim > 2)));
    rule.weights.push_back(measure);
    return rule;
  }
  if (degree == 2 && dim == 3) {  // 4-point rule
    const double a = 0.5854101966249685, b = 0.1381966011250105;
    rule.points = {Vec3(b, b, b), Vec3(a, b, b), Vec3(b, a, b), Vec3(b, b, a)};
    rule.weights.assign(4, 1.0 / 24.0);
    return rule;
  }
  if (degree == 2 && dim == 2) {  // 3-point rule
    rule.points = {Vec3(1.0 / 6, 1.0 / 6, 0), Vec3(2.0 / 3, 1.0 / 6, 0), Vec3(1.0 / 6, 2.0 / 3, 0)};
    rule.weights.assign(3, 1.0 / 6.0);
    return rule;
  }
  // The collapsed rule's Jacobian (1-u)^(dim-1) (1-v)^(dim-2) raises the
  // degree to integrate by dim - 1.
  return collapsed_gauss(dim, (degree + dim) / 2 + 1);
}

QuadratureRule collapsed_gauss(int dim, int n) {
  QuadratureRule rule;
  QuadratureRule g = gauss_legendre_unit(n);
  if (dim == 1) return g;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      double u = g.points[i].x(), v = g.points[j].x();
      if (dim == 2) {
        rule.points.push_back(Vec3(u, v * (1.0 - u), 0.0));
        rule.weights.push_back(g.weights[i] * g.weights[j] * (1.0 - u));
        continue;
      }
      for (int k = 0; k < n; ++k) {
        double w = g.points[k].x();
        rule.points.push_back(Vec3(u, v * (1.0 - u), w * (1.0 - u) * (1.0 - v)));
        rule.weights.push_back(g.weights[i] * g.weights[j] * g.weights[k] * (1.0 - u) * (1.0 - u) * (1.0 - v));
      }
    }
  return rule;
}

}  // namespace kerf

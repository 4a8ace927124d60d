// Quadrature on the reference simplex: the collapsed Gauss rules and the
// symmetric ones integrate every monomial up to their degree exactly; the
// symmetric ones have the point counts, positive weights and inner points
// they are chosen for, and are not exact one degree higher.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <stdexcept>

#include "discretization/fem/simplex_quadrature.h"
#include "discretization/fem/symmetric_simplex_quadrature.h"

namespace kerf {
namespace {

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

/// The largest error of `rule` over the monomials x^a y^b z^c of total degree
/// exactly `degree`, against their exact integrals over the unit simplex.
double monomial_error(const QuadratureRule& rule, int dim, int degree) {
  double worst = 0.0;
  for (int a = 0; a <= degree; ++a)
    for (int b = 0; b <= (dim > 1 ? degree - a : 0); ++b) {
      const int c = degree - a - b;
      if ((dim == 1 && b + c > 0) || (dim == 2 && c > 0)) continue;
      double numeric = 0.0;
      for (std::size_t q = 0; q < rule.points.size(); ++q) {
        const Vec3& x = rule.points[q];
        numeric += rule.weights[q] * std::pow(x[0], a) * std::pow(x[1], b) * std::pow(x[2], c);
      }
      const double exact = factorial(a) * factorial(b) * factorial(c) / factorial(a + b + c + dim);
      worst = std::max(worst, std::abs(numeric - exact));
    }
  return worst;
}

TEST(SimplexQuadrature, IntegratesMonomialsExactly) {
  for (int dim = 1; dim <= 3; ++dim)
    for (int degree = 0; degree <= 6; ++degree) {
      QuadratureRule rule = simplex_quadrature(dim, degree);
      for (int d = 0; d <= degree; ++d)
        EXPECT_LT(monomial_error(rule, dim, d), 1e-14) << "dim " << dim << " degree " << degree << " monomials " << d;
    }
}

TEST(SymmetricSimplexQuadrature, IntegratesMonomialsExactlyAndNoMore) {
  for (int dim : {2, 3})
    for (int degree : symmetric_rule_degrees(dim)) {
      QuadratureRule rule = symmetric_simplex_rule(dim, degree);
      for (int d = 0; d <= degree; ++d)
        EXPECT_LT(monomial_error(rule, dim, d), 1e-16) << "dim " << dim << " degree " << degree << " monomials " << d;
      // The monomials' integrals at degree + 1 are 1e-3 to 1e-5: a rule
      // exact there would claim too low a degree here.
      EXPECT_GT(monomial_error(rule, dim, degree + 1), 1e-7) << "dim " << dim << " degree " << degree;
    }
}

TEST(SymmetricSimplexQuadrature, PositiveWeightsInsideWithTheirPointCounts) {
  const std::map<std::pair<int, int>, std::size_t> points{{{2, 1}, 1}, {{2, 2}, 3}, {{2, 4}, 6}, {{2, 5}, 7},
                                                         {{3, 1}, 1}, {{3, 2}, 4}, {{3, 5}, 14}};
  for (auto [key, count] : points) {
    const auto [dim, degree] = key;
    QuadratureRule rule = symmetric_simplex_rule(dim, degree);
    EXPECT_EQ(rule.points.size(), count) << "dim " << dim << " degree " << degree;
    for (std::size_t q = 0; q < rule.points.size(); ++q) {
      const Vec3& x = rule.points[q];
      EXPECT_GT(rule.weights[q], 0.0);
      EXPECT_GT(x.head(dim).minCoeff(), 0.0);
      EXPECT_LT(x.head(dim).sum(), 1.0);
      if (dim == 2) {
        EXPECT_EQ(x.z(), 0.0);
      }
    }
  }
}

TEST(SymmetricSimplexQuadrature, RefusesDegreesItHasNoRuleFor) {
  EXPECT_THROW(symmetric_simplex_rule(3, 3), std::invalid_argument);
  EXPECT_THROW(symmetric_simplex_rule(3, 6), std::invalid_argument);
  EXPECT_THROW(symmetric_simplex_rule(2, 3), std::invalid_argument);
  EXPECT_THROW(symmetric_simplex_rule(1, 2), std::invalid_argument);
  EXPECT_TRUE(symmetric_rule_degrees(1).empty());
}

}  // namespace
}  // namespace kerf

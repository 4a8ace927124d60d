#include "discretization/fem/symmetric_simplex_quadrature.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace kerf {
namespace {

// Orbits of the symmetry group in barycentric coordinates: every distinct
// permutation of the pattern carries the same weight. The coefficients were
// solved for in 40 digits (Newton on the moment equations, mpmath); the
// degree-5 tetrahedral rule is Keast's / Walkington's 14-point rule, the
// triangle rules are Strang and Fix's 6-point and Radon's 7-point ones.
// Weights here are shares of the simplex measure.
struct Orbit {
  std::array<double, 4> pattern;  // barycentric coordinates, sorted so that permutations can be listed
  double weight;                  // each point's share of the simplex measure
};

void add_orbit(int dim, const Orbit& orbit, QuadratureRule& rule, double measure) {
  std::vector<double> b(orbit.pattern.begin(), orbit.pattern.begin() + dim + 1);
  std::sort(b.begin(), b.end());
  do {
    rule.points.push_back(Vec3(b[1], b[2], dim == 3 ? b[3] : 0.0));
    rule.weights.push_back(orbit.weight * measure);
  } while (std::next_permutation(b.begin(), b.end()));
}

std::vector<Orbit> orbits(int dim, int degree) {
  if (dim == 2 && degree == 1) return {{{1.0 / 3, 1.0 / 3, 1.0 / 3}, 1.0}};
  if (dim == 2 && degree == 2) return {{{1.0 / 6, 1.0 / 6, 2.0 / 3}, 1.0 / 3}};
  if (dim == 2 && degree == 4) {
    const double a = 0.44594849091596488632, b = 0.09157621350977074346;
    return {{{a, a, 1 - 2 * a}, 0.2233815896780114657}, {{b, b, 1 - 2 * b}, 0.10995174365532186764}};
  }
  if (dim == 2 && degree == 5) {
    const double a = 0.47014206410511508977, b = 0.1012865073234563388;
    return {{{1.0 / 3, 1.0 / 3, 1.0 / 3}, 0.225},
            {{a, a, 1 - 2 * a}, 0.13239415278850618074},
            {{b, b, 1 - 2 * b}, 0.1259391805448271526}};
  }
  if (dim == 3 && degree == 1) return {{{0.25, 0.25, 0.25, 0.25}, 1.0}};
  if (dim == 3 && degree == 2) {
    const double a = 0.13819660112501051518;
    return {{{a, a, a, 1 - 3 * a}, 0.25}};
  }
  if (dim == 3 && degree == 5) {
    const double a = 0.092735250310891226402, b = 0.3108859192633006098, c = 0.045503704125649649492;
    return {{{a, a, a, 1 - 3 * a}, 0.073493043116361949544},
            {{b, b, b, 1 - 3 * b}, 0.1126879257180158508},
            {{c, c, 0.5 - c, 0.5 - c}, 0.042546020777081466438}};
  }
  throw std::invalid_argument("no symmetric rule of degree " + std::to_string(degree) + " in dimension " +
                              std::to_string(dim));
}

}  // namespace

QuadratureRule symmetric_simplex_rule(int dim, int degree) {
  QuadratureRule rule;
  const double measure = dim == 2 ? 0.5 : 1.0 / 6.0;
  for (const Orbit& orbit : orbits(dim, degree)) add_orbit(dim, orbit, rule, measure);
  return rule;
}

}  // namespace kerf

#pragma once
// Quadrature over a split cell's fragment (geometry/cell_split.h): a rule of
// the reference simplex moved onto each of the fragment's sub-simplices, in
// the parent cell's reference coordinates, so that the parent's own shape
// functions are integrated over the fragment alone.
#include <span>

#include "discretization/fem/simplex_quadrature.h"

namespace kerf {

/// `fragment`: (dim + 1) reference points per sub-simplex. The weights are
/// the reference rule's times each sub-simplex's share of the reference
/// simplex (they add up to the fragment's reference measure).
QuadratureRule fragment_quadrature(int dim, std::span<const Vec3> fragment, const QuadratureRule& reference);

/// The fragment's reference measure (the reference simplex's is 1/6, 1/2 in 2D).
double fragment_measure(int dim, std::span<const Vec3> fragment);

/// Is the reference point xi inside one of the fragment's sub-simplices (to `tolerance`)?
bool fragment_holds(int dim, std::span<const Vec3> fragment, const Vec3& xi, double tolerance = 1e-10);

}  // namespace kerf

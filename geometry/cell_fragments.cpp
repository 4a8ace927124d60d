#include "geometry/cell_fragments.h"

#include <algorithm>

#include "core/check.h"

namespace kerf {

double simplex_measure(int dimension, const Vec3* p) {
  if (dimension == 2) return 0.5 * ((p[1] - p[0]).x() * (p[2] - p[0]).y() - (p[1] - p[0]).y() * (p[2] - p[0]).x());
  return (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0])) / 6.0;
}

namespace {

/// Builds the fragments of a cell with fewer + corners than - ones (or as
/// many): callers flip the sides first and swap the answer.
class FragmentBuilder {
 public:
  FragmentBuilder(int dimension, const std::array<Vec3, 4>& corners, double scale)
      : dim_(dimension), corners_(corners), tiny_(1e-13 * std::pow(scale, dimension)) {}

  /// Appends the simplex to `side`, oriented positively; skips a flat one.
  void simplex(int side, std::initializer_list<Vec3> points) {
    std::array<Vec3, 4> p{};
    std::copy(points.begin(), points.end(), p.begin());
    const double measure = simplex_measure(dim_, p.data());
    if (std::abs(measure) <= tiny_) return;
    if (measure < 0) std::swap(p[dim_ - 1], p[dim_]);
    out_.simplices[side].insert(out_.simplices[side].end(), p.begin(), p.begin() + dim_ + 1);
  }
  /// The prism a0 a1 a2 | b0 b1 b2 (a_k joined to b_k) as three tets; its
  /// quadrilateral a1 a2 b2 b1 is split along a2-b1, so two prisms that share
  /// it, listed alike, split it the same way.
  void prism(int side, const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b) {
    simplex(side, {a[0], a[1], a[2], b[0]});
    simplex(side, {a[1], a[2], b[0], b[1]});
    simplex(side, {a[2], b[0], b[1], b[2]});
  }
  const Vec3& corner(int k) const { return corners_[k]; }
  CellFragments take() { return std::move(out_); }

 private:
  int dim_;
  const std::array<Vec3, 4>& corners_;
  double tiny_;
  CellFragments out_;
};

constexpr int plus = 0, minus = 1;

void tetrahedron_fragments(FragmentBuilder& f, const std::vector<int>& P, const std::vector<int>& M,
                           const std::vector<int>& Z, const std::function<Vec3(int, int)>& x) {
  const auto c = [&](int k) { return f.corner(k); };
  if (P.size() == 1 && M.size() == 3) {
    const int i = P[0], j = M[0], k = M[1], l = M[2];
    f.simplex(plus, {c(i), x(i, j), x(i, k), x(i, l)});
    f.prism(minus, {c(j), c(k), c(l)}, {x(i, j), x(i, k), x(i, l)});
  } else if (P.size() == 2 && M.size() == 2) {
    const int i = P[0], j = P[1], k = M[0], l = M[1];
    f.prism(plus, {c(i), x(i, k), x(i, l)}, {c(j), x(j, k), x(j, l)});
    f.prism(minus, {c(k), x(i, k), x(j, k)}, {c(l), x(i, l), x(j, l)});
  } else if (P.size() == 1 && M.size() == 2) {
    const int i = P[0], j = M[0], k = M[1], z = Z[0];
    f.simplex(plus, {c(i), c(z), x(i, j), x(i, k)});
    f.simplex(minus, {c(z), c(j), c(k), x(i, k)});  // the pyramid on j k x_ik x_ij, apex z
    f.simplex(minus, {c(z), c(j), x(i, k), x(i, j)});
  } else {
    KERF_CHECK(P.size() == 1 && M.size() == 1 && Z.size() == 2, "internal: no fragment rule for a tet with ",
               P.size(), " + and ", M.size(), " - corners");
    const int i = P[0], j = M[0];
    f.simplex(plus, {c(i), c(Z[0]), c(Z[1]), x(i, j)});
    f.simplex(minus, {c(j), c(Z[0]), c(Z[1]), x(i, j)});
  }
}

void triangle_fragments(FragmentBuilder& f, const std::vector<int>& P, const std::vector<int>& M,
                        const std::vector<int>& Z, const std::function<Vec3(int, int)>& x) {
  const auto c = [&](int k) { return f.corner(k); };
  if (P.size() == 1 && M.size() == 2) {
    const int i = P[0], j = M[0], k = M[1];
    f.simplex(plus, {c(i), x(i, j), x(i, k)});
    f.simplex(minus, {c(j), c(k), x(i, k)});
    f.simplex(minus, {c(j), x(i, k), x(i, j)});
  } else {
    KERF_CHECK(P.size() == 1 && M.size() == 1 && Z.size() == 1, "internal: no fragment rule for a triangle with ",
               P.size(), " + and ", M.size(), " - corners");
    const int i = P[0], j = M[0];
    f.simplex(plus, {c(i), c(Z[0]), x(i, j)});
    f.simplex(minus, {c(j), c(Z[0]), x(i, j)});
  }
}

}  // namespace

CellFragments cell_fragments(int dimension, const std::array<Vec3, 4>& corners, const std::array<int, 4>& sides,
                             const std::function<Vec3(int, int)>& crossing) {
  std::vector<int> P, M, Z;
  for (int k = 0; k <= dimension; ++k) (sides[k] > 0 ? P : sides[k] < 0 ? M : Z).push_back(k);
  KERF_CHECK(!P.empty() && !M.empty(), "internal: a cell with corners on one side only has no fragments");
  // The rules have the lone corner on the + side: flip a cell with more + corners.
  const bool flipped = P.size() > M.size();
  if (flipped) std::swap(P, M);
  const auto x = [&](int a, int b) { return crossing(a, b); };
  double scale = 0.0;
  for (int a = 0; a <= dimension; ++a)
    for (int b = a + 1; b <= dimension; ++b) scale = std::max(scale, (corners[a] - corners[b]).norm());
  FragmentBuilder builder(dimension, corners, scale);
  if (dimension == 3)
    tetrahedron_fragments(builder, P, M, Z, x);
  else
    triangle_fragments(builder, P, M, Z, x);
  CellFragments out = builder.take();
  if (flipped) std::swap(out.simplices[0], out.simplices[1]);
  return out;
}

}  // namespace kerf

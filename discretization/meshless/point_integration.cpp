#include "discretization/meshless/point_integration.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "core/check.h"
#include "core/parallel_failure.h"
#include "discretization/meshless/point_sums.h"

namespace kerf {

PointIntegration::PointIntegration(ShapeTable shapes, std::vector<Vec3> positions, std::vector<double> weights,
                                   std::span<const Vec3> nodes, Index points_per_cell)
    : shapes_(std::move(shapes)),
      positions_(std::move(positions)),
      weights_(std::move(weights)),
      nodes_(nodes.begin(), nodes.end()),
      points_per_group_(points_per_cell) {
  const Index node_count = static_cast<Index>(nodes.size());
  KERF_CHECK(static_cast<Index>(weights_.size()) == shapes_.point_count() && positions_.size() == weights_.size(),
             "integration weights and positions: ", weights_.size(), " and ", positions_.size(), " for ",
             shapes_.point_count(), " points");
  const auto& nb = shapes_.neighbours;
  for (Index p = 0; p < nb.size(); ++p)
    for (Index s = nb.start[p] + 1; s < nb.start[p + 1]; ++s)
      KERF_CHECK(nb.index[s - 1] < nb.index[s], "internal: the neighbours of point ", p,
                 " are not in increasing order");  // add_stiffness_rows reads the nodes after one in its list
  users_ = transpose_slots(nb, node_count, &user_point_);
}

const PointSchedule& PointIntegration::schedule() const {
  std::call_once(schedule_->made, [&] { schedule_->schedule = schedule_points(shapes_, nodes_, points_per_group_); });
  return schedule_->schedule;
}

std::vector<Index> PointIntegration::points_holding(std::span<const Index> nodes) const {
  std::vector<char> holds(point_count(), 0);
  for (Index K : nodes)
    for (Index k = users_.start[K]; k < users_.start[K + 1]; ++k) holds[user_point_[k]] = 1;
  std::vector<Index> points;
  for (Index p = 0; p < point_count(); ++p)
    if (holds[p]) points.push_back(p);
  return points;
}

void PointIntegration::gather(std::span<const Mat3> stress, Vector& f) const {
  const int dim = shapes_.dimension;
  const Index N = users_.size();
  f.resize(dim * N);
  const double* g = shapes_.gradient.data();
#pragma omp parallel for schedule(static)
  for (Index K = 0; K < N; ++K) {
    Vec3 acc = Vec3::Zero();
    for (Index k = users_.start[K]; k < users_.start[K + 1]; ++k) {
      const Mat3& Q = stress[user_point_[k]];
      const double* gs = g + dim * users_.index[k];
      if (dim == 3)
        acc += Q * Vec3(gs[0], gs[1], gs[2]);
      else
        acc += Q * Vec3(gs[0], gs[1], 0.0);
    }
    for (int i = 0; i < dim; ++i) f[dim * K + i] = acc[i];
  }
}

namespace {

/// add_material_block with the dimension fixed, so each node pair's DIM x DIM
/// block is formed in registers and written a row at a time.
/// With test gradients `test` other than g (a Petrov-Galerkin point, VCI)
/// every node pair is computed: the block is not symmetric.
template <int DIM>
void add_material_block_fixed(const double* g, const double* test, Index n, const Mat9& dPdF, double scale,
                              const Index* place, Index size, double* block, bool upper_half) {
  using Grad = Eigen::Matrix<double, DIM, 1>;
  using Block = Eigen::Matrix<double, DIM, DIM>;
  for (Index b = 0; b < n; ++b) {
    const Grad gb = Eigen::Map<const Grad>(g + DIM * b);
    // T[k](i, j) = sum_l dP(i,j)/dF(k,l) g_b(l), scaled by the weight
    std::array<Block, DIM> T;
    for (int k = 0; k < DIM; ++k)
      for (int j = 0; j < DIM; ++j)
        for (int i = 0; i < DIM; ++i) {
          double t = 0.0;
          for (int l = 0; l < DIM; ++l) t += dPdF(i + 3 * j, k + 3 * l) * gb[l];
          T[k](i, j) = scale * t;
        }
    // A hyperelastic tangent has major symmetry, so with test gradients
    // equal to the trial ones K is symmetric: the blocks a <= b are computed and mirrored.
    const bool symmetric = test == g;
    const Index column = DIM * place[b];
    for (Index a = 0; a < (symmetric ? b + 1 : n); ++a) {
      const Grad ga = Eigen::Map<const Grad>(test + DIM * a);
      Block K;  // K(i, k) = sum_j T[k](i, j) ghat_a(j)
      for (int k = 0; k < DIM; ++k) K.col(k) = T[k] * ga;
      const Index row = DIM * place[a];
      if (upper_half && row > column) {  // below the diagonal: its mirror image above
        for (int k = 0; k < DIM; ++k)
          for (int i = 0; i < DIM; ++i) block[(column + k) * size + row + i] += K(i, k);
        continue;
      }
      for (int i = 0; i < DIM; ++i)
        for (int k = 0; k < DIM; ++k) block[(row + i) * size + column + k] += K(i, k);
      if (symmetric && a < b && !upper_half)
        for (int k = 0; k < DIM; ++k)
          for (int i = 0; i < DIM; ++i) block[(column + k) * size + row + i] += K(i, k);
    }
  }
}

}  // namespace

void add_material_block(const ShapeTable& table, Index point, const Mat9& dPdF, double scale,
                        std::span<const Index> place, Index block_nodes, std::vector<double>& block,
                        std::span<const double> offsets, bool upper_half) {
  KERF_CHECK(!upper_half || offsets.empty(), "internal: a Petrov-Galerkin block is not symmetric: no upper half");
  const int dim = table.dimension;
  auto near = table.neighbours.of(point);
  const Index n = static_cast<Index>(near.size()), size = block_nodes * dim;
  KERF_DCHECK(static_cast<Index>(place.size()) == n);
  KERF_DCHECK(static_cast<Index>(block.size()) == size * size);
  const double* g = table.gradients_of(point);
  const double* test = g;
  thread_local std::vector<double> corrected;
  if (!offsets.empty()) {
    corrected.assign(g, g + dim * n);
    for (Index a = 0; a < n; ++a)
      for (int i = 0; i < dim; ++i) corrected[dim * a + i] += offsets[dim * (table.neighbours.start[point] + a) + i];
    test = corrected.data();
  }
  if (dim == 3)
    add_material_block_fixed<3>(g, test, n, dPdF, scale, place.data(), size, block.data(), upper_half);
  else
    add_material_block_fixed<2>(g, test, n, dPdF, scale, place.data(), size, block.data(), upper_half);
}

void mirror_upper_half(Index block_nodes, int dim, std::vector<double>& block) {
  const Index size = block_nodes * dim;
  for (Index r = dim; r < size; ++r) {
    const Index below = (r / dim) * dim;  // the columns of the node blocks left of r's diagonal block
    for (Index c = 0; c < below; ++c) block[r * size + c] = block[c * size + r];
  }
}

namespace {

/// The range of points in the group starting at `first`.
std::pair<Index, Index> group_points(Index first, Index group_size, Index point_count) {
  return {first, std::min(point_count, first + group_size)};
}

}  // namespace

PointSchedule only_points(PointSchedule schedule, std::pair<Index, Index> points) {
  const Index size = schedule.group_size;
  KERF_CHECK(points.first % size == 0, "internal: points from ", points.first, " split a group of ", size);
  std::vector<char> own_group((points.second + size - 1) / size, 0);  // groups starting before points.second
  std::fill(own_group.begin() + points.first / size, own_group.end(), 1);
  return only_groups(std::move(schedule), own_group);
}

PointSchedule only_groups(PointSchedule schedule, std::span<const char> own_group) {
  for (auto& colour : schedule.colours)
    for (std::vector<Index>& cube : colour)
      std::erase_if(cube, [&](Index p) {
        const std::size_t g = static_cast<std::size_t>(p / schedule.group_size);
        return g >= own_group.size() || !own_group[g];
      });
  return schedule;
}

PointSchedule schedule_points(const ShapeTable& table, std::span<const Vec3> nodes, Index group_size) {
  KERF_CHECK(group_size >= 1, "internal: a point group of ", group_size, " points");
  const Index P = table.point_count(), groups = (P + group_size - 1) / group_size;
  std::vector<Vec3> centre(groups, Vec3::Zero());
  double reach = 0.0;  // the largest distance from a group's centroid to one of its nodes
#pragma omp parallel for schedule(static) reduction(max : reach)
  for (Index g = 0; g < groups; ++g) {
    const auto [begin, end] = group_points(g * group_size, group_size, P);
    std::size_t count = 0;
    for (Index p = begin; p < end; ++p)
      for (Index J : table.neighbours.of(p)) centre[g] += nodes[J], ++count;
    if (count > 0) centre[g] /= static_cast<double>(count);
    for (Index p = begin; p < end; ++p)
      for (Index J : table.neighbours.of(p)) reach = std::max(reach, (nodes[J] - centre[g]).norm());
  }
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
  for (const Vec3& c : centre) low = low.cwiseMin(c), high = high.cwiseMax(c);
  // Two groups sharing a node have centroids within 2 reach: cubes of that width
  // (a hair more for round-off), same-colour cubes a cube apart.
  const double width = 2.0 * reach * (1.0 + 1e-9) + 1e-300;
  std::array<Index, 3> count{1, 1, 1};
  for (int a = 0; a < table.dimension; ++a)
    count[a] = std::max<Index>(1, static_cast<Index>(std::floor((high[a] - low[a]) / width)) + 1);
  std::vector<std::vector<Index>> cubes(static_cast<std::size_t>(count[0]) * count[1] * count[2]);
  for (Index g = 0; g < groups; ++g) {
    std::array<Index, 3> at{0, 0, 0};
    for (int a = 0; a < table.dimension; ++a)
      at[a] = std::min(count[a] - 1, static_cast<Index>((centre[g][a] - low[a]) / width));
    cubes[at[0] + count[0] * (at[1] + count[1] * at[2])].push_back(g * group_size);
  }
  PointSchedule schedule;
  schedule.group_size = group_size;
  schedule.colours.resize(table.dimension == 3 ? 8 : 4);
  for (Index k = 0; k < count[2]; ++k)
    for (Index j = 0; j < count[1]; ++j)
      for (Index i = 0; i < count[0]; ++i) {
        auto& cube = cubes[i + count[0] * (j + count[1] * k)];
        if (!cube.empty()) schedule.colours[(i % 2) + 2 * (j % 2) + 4 * (k % 2)].push_back(std::move(cube));
      }
  return schedule;
}

namespace {

/// One group's summed point blocks, over the union of its points' nodes
/// (one point: its own neighbours in their order, the order a method's extra
/// terms are written in).
class GroupBlock {
 public:
  void assemble(const ShapeTable& table, Index begin, Index end, const PointBlockTerm& term, bool upper_half) {
    const int dim = table.dimension;
    nodes_.clear();
    for (Index p = begin; p < end; ++p) {
      auto near = table.neighbours.of(p);
      nodes_.insert(nodes_.end(), near.begin(), near.end());
    }
    if (end - begin > 1) {
      std::sort(nodes_.begin(), nodes_.end());
      nodes_.erase(std::unique(nodes_.begin(), nodes_.end()), nodes_.end());
    }
    const Index count = static_cast<Index>(nodes_.size());
    block_.assign(static_cast<std::size_t>(count * dim) * (count * dim), 0.0);
    for (Index p = begin; p < end; ++p) {
      place_.clear();
      if (end - begin == 1)
        for (Index k = 0; k < count; ++k) place_.push_back(k);
      else
        for (Index J : table.neighbours.of(p))
          place_.push_back(static_cast<Index>(std::lower_bound(nodes_.begin(), nodes_.end(), J) - nodes_.begin()));
      term(p, place_, count, block_);
    }
    if (upper_half) mirror_upper_half(count, dim, block_);
    dofs_.clear();
    for (Index J : nodes_)
      for (int i = 0; i < dim; ++i) dofs_.push_back(dim * J + i);
  }
  std::span<const Index> dofs() const { return dofs_; }
  std::vector<double>& block() { return block_; }

 private:
  std::vector<Index> nodes_, place_, dofs_;
  std::vector<double> block_;
};

}  // namespace

void assemble_point_blocks(const ShapeTable& table, const PointSchedule& schedule, const PointBlockTerm& term,
                           const BlockSink& sink, const BlockExtra& extra, bool upper_half) {
  KERF_CHECK(!extra || schedule.group_size == 1, "internal: a method's extra terms need one point a group");
  const Index P = table.point_count();
  ParallelFailure failure;
#pragma omp parallel
  {
    GroupBlock group;  // empty until its first group: constructing it cannot throw
    for (const auto& colour : schedule.colours) {
#pragma omp for schedule(dynamic, 1)
      for (std::size_t c = 0; c < colour.size(); ++c)
        failure.run([&] {
          // No other thread writes these dofs now: this colour's cubes share no node.
          for (Index first : colour[c]) {
            const auto [begin, end] = group_points(first, schedule.group_size, P);
            group.assemble(table, begin, end, term, upper_half);
            if (extra) extra(begin, group.block());
            sink(group.dofs(), group.block());
          }
        });
    }
  }
  failure.rethrow_if_failed();
}

void assemble_material_blocks(const ShapeTable& table, const PointSchedule& schedule, std::span<const double> weights,
                              const MaterialLaw& law, const Vector& u, const BlockSink& sink,
                              const BlockExtra& extra, std::span<const double> offsets) {
  const PointBlockTerm material = [&](Index p, std::span<const Index> place, Index block_nodes,
                                      std::vector<double>& block) {
    Mat3 P;
    Mat9 dPdF;
    law.stress_and_tangent(deformation_gradient(table, p, u), P, dPdF);
    add_material_block(table, p, dPdF, weights[p], place, block_nodes, block, offsets, offsets.empty());
  };
  // Symmetric without VCI's offsets: each point writes the group block's upper half, mirrored once a group.
  assemble_point_blocks(table, schedule, material, sink, extra, offsets.empty());
}

std::vector<double> material_diagonal(const ShapeTable& table, std::span<const double> weights, const Lame& lame,
                                      Index node_count) {
  const int dim = table.dimension;
  std::vector<double> diagonal(dim * node_count, 0.0);
  add_over_points(table.point_count(), diagonal, [&](Index p, double* sums) {
    auto near = table.neighbours.of(p);
    const double* g = table.gradients_of(p);
    for (std::size_t k = 0; k < near.size(); ++k) {
      double squared = 0.0;
      for (int l = 0; l < dim; ++l) squared += g[dim * k + l] * g[dim * k + l];
      for (int i = 0; i < dim; ++i)
        sums[dim * near[k] + i] +=
            weights[p] * (lame.mu * squared + (lame.lambda + lame.mu) * g[dim * k + i] * g[dim * k + i]);
    }
  });
  return diagonal;
}

std::vector<double> material_diagonal(const ShapeTable& table, std::span<const double> weights, const MaterialLaw& law,
                                      const Vector& u, Index node_count) {
  const int dim = table.dimension;
  std::vector<double> diagonal(dim * node_count, 0.0);
  add_over_points(table.point_count(), diagonal, [&](Index p, double* sums) {
    Mat3 P;
    Mat9 A;
    law.stress_and_tangent(deformation_gradient(table, p, u), P, A);
    auto near = table.neighbours.of(p);
    const double* g = table.gradients_of(p);
    for (std::size_t k = 0; k < near.size(); ++k)
      for (int i = 0; i < dim; ++i) {
        double sum = 0.0;
        for (int l = 0; l < dim; ++l)
          for (int m = 0; m < dim; ++m) sum += g[dim * k + l] * A(i + 3 * l, i + 3 * m) * g[dim * k + m];
        sums[dim * near[k] + i] += weights[p] * sum;
      }
  });
  return diagonal;
}

void assemble_mass_blocks(const ShapeTable& table, const PointSchedule& schedule, std::span<const double> weights,
                          double density, const BlockSink& sink) {
  const int dim = table.dimension;
  const PointBlockTerm mass = [&](Index p, std::span<const Index> place, Index block_nodes,
                                  std::vector<double>& block) {
    const double* phi = table.values_of(p);
    const Index n = static_cast<Index>(place.size()), size = dim * block_nodes;
    const double scale = density * weights[p];
    for (Index a = 0; a < n; ++a)
      for (Index b = 0; b < n; ++b) {
        const double m = scale * phi[a] * phi[b];
        for (int i = 0; i < dim; ++i) block[(dim * place[a] + i) * size + dim * place[b] + i] += m;
      }
  };
  assemble_point_blocks(table, schedule, mass, sink);
}

}  // namespace kerf

// Nitsche's alpha estimated again from the material's tangents at the state an
// implicit time step starts from: the stiffness diagonal it divides by is the
// assembled tangent's, at rest it is the rest estimate exactly, a linear law
// never changes it, and a compressed neo-Hookean block raises it.
#include <gtest/gtest.h>

#include "discretization/body_factory.h"
#include "discretization/meshless/efg_body.h"
#include "discretization/meshless/point_integration.h"
#include "support/test_support.h"

namespace kerf {
namespace {

const MaterialModel all_models[] = {MaterialModel::linear, MaterialModel::corotational, MaterialModel::stvk,
                                    MaterialModel::neohookean, MaterialModel::neohookean_uncoupled};

/// A 3 x 2 x 2 cm EFG block at 5 mm spacing clamped at x = 0 (`essential` its method).
std::unique_ptr<DiscreteBody> clamped_block(MaterialModel model, const std::string& essential) {
  const std::string yaml =
      "domain: {box: {min: [0,0,0], max: [0.03,0.02,0.02]}}\n"
      "boundary:\n"
      "  - {select: {plane: {axis: x, at: 0.0}}, fix: [x, y, z]}\n"
      "material: {young: 1.0e4, poisson: 0.45}\n"
      "discretization: {method: efg, meshless: {spacing: 0.005}}\n"
      "solve: {analysis: static}\n";
  Scene scene = testing::scene_from_text(
      yaml, {std::string("material.model=") + to_string(model), "discretization.meshless.essential=" + essential});
  RunReport report;
  return make_body(scene, report);
}

/// u = (F - I) x at every node: a uniform deformation.
Vector affine(const DiscreteBody& body, const Mat3& F) {
  Vector u(body.dof_count());
  for (Index n = 0; n < body.node_count(); ++n) u.segment<3>(3 * n) = (F - Mat3::Identity()) * body.node_position(n);
  return u;
}

/// Squeezed 30% along x, bulging 10% in y and z, sheared: P has no minor symmetry.
Mat3 squeezed() {
  Mat3 F;
  F << 0.7, 0.15, 0.0, 0.05, 1.1, 0.0, 0.0, 0.1, 1.1;
  return F;
}

// The diagonal from the tangents is the assembled tangent's (EFG with its
// essential conditions on parameters adds nothing to the volume's blocks),
// and at rest the small-strain one, for every law.
TEST(NitscheAlpha, TangentDiagonalIsTheAssembledOneAndAtRestTheSmallStrainOne) {
  for (MaterialModel model : all_models) {
    const auto body = clamped_block(model, "parameters");
    const auto& efg = dynamic_cast<const EfgBody&>(*body);
    const ShapeTable& table = efg.points().shapes();
    const MaterialLaw law(model, 1.0e4, 0.45);
    const Index N = body->node_count();
    const Vector rest = Vector::Zero(body->dof_count());
    const std::vector<double> small = material_diagonal(table, efg.points().weights(), law.lame(), N);
    const std::vector<double> at_rest = material_diagonal(table, efg.points().weights(), law, rest, N);
    const Vector u = affine(*body, squeezed());
    const std::vector<double> deformed = material_diagonal(table, efg.points().weights(), law, u, N);
    const Vector assembled = testing::assemble_stiffness(*body, u).diagonal();
    double worst_rest = 0.0, worst_assembled = 0.0, scale = 0.0;
    for (Index d = 0; d < 3 * N; ++d) {
      scale = std::max(scale, std::abs(assembled[d]));
      worst_rest = std::max(worst_rest, std::abs(at_rest[d] - small[d]) / small[d]);
      worst_assembled = std::max(worst_assembled, std::abs(deformed[d] - assembled[d]));
    }
    EXPECT_LT(worst_rest, 1e-12) << to_string(model);
    EXPECT_LT(worst_assembled, 1e-12 * scale) << to_string(model);
  }
}

TEST(NitscheAlpha, RisesAsTheMaterialStiffensAndIsTheRestOneAtRest) {
  auto body = clamped_block(MaterialModel::neohookean, "nitsche");
  const WeakBoundaryConditions& weak = *dynamic_cast<const EfgBody&>(*body).weak_conditions();
  const double rest_low = weak.smallest_alpha(), rest_high = weak.largest_alpha();
  body->begin_time_step(affine(*body, squeezed()));
  EXPECT_GT(weak.largest_alpha(), 1.5 * rest_high);
  EXPECT_GE(weak.smallest_alpha(), rest_low) << "never below the rest estimate";
  EXPECT_GT(weak.largest_alpha_growth(), 1.5);
  body->begin_time_step(Vector::Zero(body->dof_count()));
  EXPECT_EQ(weak.smallest_alpha(), rest_low);
  EXPECT_EQ(weak.largest_alpha(), rest_high);

  auto linear = clamped_block(MaterialModel::linear, "nitsche");
  const WeakBoundaryConditions& fixed = *dynamic_cast<const EfgBody&>(*linear).weak_conditions();
  const double linear_high = fixed.largest_alpha();
  linear->begin_time_step(affine(*linear, squeezed()));
  EXPECT_EQ(fixed.largest_alpha(), linear_high) << "a linear law's tangent does not change";
}

}  // namespace
}  // namespace kerf

// Contact with a rigid sphere (the solver side's ContactTerm in a
// MechanicalSystem): tangent by finite differences for
// every method, the force on the sphere equal and opposite to the body's, the
// linear part and its remainder adding up to the whole, the indentation
// measured from the undeformed surface (beside an edge, by hand), and a sphere
// out of reach or starting inside refused with a message that says so.
#include <gtest/gtest.h>

#include "core/check.h"
#include "core/run_report.h"
#include "discretization/body_factory.h"
#include "solvers/mechanical_system.h"
#include "support/test_support.h"

namespace kerf {
namespace {

/// A 10 mm cube, a 5 mm sphere resting on its top face at (5, 5) mm.
Scene indentation_scene(const std::string& method, const std::string& drive) {
  return testing::scene_from_text(R"(
domain: {box: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}}
material: {young: 1.0e4, poisson: 0.3}
discretization:
  method: )" + method + R"(
  fem: {element: tet4, size: 0.002}
  meshless: {spacing: 0.002}
boundary:
  - {select: {plane: {axis: z, at: 0}}, fix: [x, y, z]}
contact:
  - sphere: {center: [0.005, 0.005, 0.015], radius: 0.005}
    )" + drive + R"(
output: {vtk: false}
)");
}

/// A body and its mechanical system with the scene's sphere.
struct PressedBody {
  std::unique_ptr<DiscreteBody> body;
  std::unique_ptr<MechanicalSystem> mechanics;
};

PressedBody pressed_body(const Scene& scene) {
  RunReport report;
  PressedBody p;
  p.body = make_body(scene, report);
  p.mechanics = std::make_unique<MechanicalSystem>(*p.body, scene, report);
  return p;
}

/// A displacement that presses the top face up into the sphere, plus the sphere's own motion.
Vector pressing_state(const MechanicalSystem& mechanics, double lift, double sphere_drop) {
  const int dim = mechanics.dofs_per_node();
  const DiscreteBody& body = mechanics.body();
  Vector u = Vector::Zero(mechanics.dof_count());
  std::srand(5);  // the tests' random directions follow
  for (Index n = 0; n < body.node_count(); ++n) {
    const Vec3 x = body.node_position(n);
    u[dim * n + 2] = lift * x.z() / 0.01;
    u[dim * n] = 1e-5 * std::sin(300.0 * x.y());
  }
  const Index sphere = body.dof_count();  // the sphere's dofs follow the body's
  u[sphere + 2] = -sphere_drop;
  u[sphere] = 2e-6;
  return u;
}

class ContactTest : public ::testing::TestWithParam<std::string> {};

TEST_P(ContactTest, TangentMatchesFiniteDifferences) {
  const PressedBody pressed = pressed_body(indentation_scene(GetParam(), "force: [0, 0, -0.01]"));
  const MechanicalSystem& system = *pressed.mechanics;
  ASSERT_NE(system.contact(), nullptr);
  // 50 um at the centre (1e-2 of the radius): deeper than the 25 um gap at
  // the Gauss points nearest the centre on these 2 mm facets.
  const double penetration = 5e-5;
  const Vector u = pressing_state(system, 3e-5, 2e-5);
  // The contact part alone (the body's own tangent has its own test).
  SparseMatrix K = build_pattern(system);
  const BlockSink sink = add_into(K);
  Vector f = Vector::Zero(system.dof_count());
  system.add_terms(u, f, &sink);
  ASSERT_GT(f.norm(), 0.0) << "no point presses";
  Vector du = Vector::Random(system.dof_count());
  Vector fp = Vector::Zero(system.dof_count()), fm = fp;
  const double h = 1e-12;  // m: far inside the active set
  system.add_terms(u + h * du, fp, nullptr);
  system.add_terms(u - h * du, fm, nullptr);
  const Vector numeric = (fp - fm) / (2 * h);
  const Vector analytic = K * du;
  // The tangent leaves out the curvature term, penetration / R of the normal stiffness.
  EXPECT_LT((analytic - numeric).norm(), 2.0 * penetration / 0.005 * analytic.norm());
  // The force with the tangent is the internal force; the body's + the terms' is the whole.
  SparseMatrix pattern = build_pattern(system);
  Vector whole, with_tangent, split;
  system.tangent(u, add_into(pattern), &with_tangent);
  system.internal_force(u, whole);
  EXPECT_LT((with_tangent - whole).norm(), 1e-12 * whole.norm());
  ASSERT_TRUE(system.linear_body_with_terms());
  Vector body_u;
  system.body().internal_force(system.body_part(u, body_u), split);
  split.conservativeResizeLike(Vector::Zero(system.dof_count()));
  system.add_terms(u, split, nullptr);
  EXPECT_LT((split - whole).norm(), 1e-12 * whole.norm());
}

TEST_P(ContactTest, SphereAndBodyFeelOppositeForces) {
  const PressedBody pressed = pressed_body(indentation_scene(GetParam(), "displacement: [0, 0, -0.0002]"));
  const MechanicalSystem& system = *pressed.mechanics;
  const Vector u = pressing_state(system, 0.0, 2e-4);
  Vector f = Vector::Zero(system.dof_count());
  system.add_terms(u, f, nullptr);
  const int dim = system.dofs_per_node();
  const Index sphere = pressed.body->node_count();  // the sphere's dofs as a node after the body's
  Vec3 on_nodes = Vec3::Zero();
  for (Index n = 0; n < sphere; ++n) on_nodes += f.segment<3>(dim * n);
  const Vec3 on_sphere = f.segment<3>(dim * sphere);
  const ContactReading reading = system.contact()->reading(0, u);
  EXPECT_LT(reading.force.z(), 0.0) << "the sphere pushes the body down";
  EXPECT_LT((on_nodes + on_sphere).norm(), 1e-12 * on_sphere.norm());
  // The force the sphere exerts on the body is minus the contact part of the body's internal force.
  EXPECT_LT((reading.force + on_nodes).norm(), 1e-12 * on_nodes.norm());
  // Moved out past the block's edge x = z = 1 cm, the sphere's centre at
  // (12, 5, 14.5) mm is nearest that edge: by hand, R - |(2, 0, 4.5)| mm.
  Vector beside = u;
  beside.segment(dim * sphere, 3) = Vec3(0.007, 0.0, -0.0005);
  EXPECT_NEAR(system.contact()->reading(0, beside).indentation, 0.005 - std::hypot(0.002, 0.0045), 1e-12);
}

INSTANTIATE_TEST_SUITE_P(AllMethods, ContactTest, ::testing::Values("fem", "efg", "nodal"));

TEST(ContactReach, ASphereThatCannotReachTheBodyIsRefused) {
  Scene scene = indentation_scene("fem", "force: [0, 0, -0.01]");
  scene.contact[0].center.z() = 0.02;  // 5 mm above the top face
  testing::expect_mentions(testing::error_message([&] { pressed_body(scene); }),
                           {"test.yaml:11:", "contact.0", "cannot reach the body's boundary", "radius 0.005 m"});
  scene.contact[0].center.z() = 0.014;  // 1 mm inside
  testing::expect_mentions(testing::error_message([&] { pressed_body(scene); }),
                           {"test.yaml:11:", "contact.0", "the sphere starts 0.001", "inside the body"});
}

}  // namespace
}  // namespace kerf

// Contact with a rigid sphere (ContactBody): tangent by finite differences for
// every method, the force on the sphere equal and opposite to the body's, the
// linear part and its remainder adding up to the whole, the indentation
// measured from the undeformed surface (beside an edge, by hand), and a sphere
// out of reach or starting inside refused with a message that says so.
#include <gtest/gtest.h>

#include "core/check.h"
#include "core/run_report.h"
#include "discretization/body_factory.h"
#include "discretization/contact_body.h"
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

/// A displacement that presses the top face up into the sphere, plus the sphere's own motion.
Vector pressing_state(const DiscreteBody& body, double lift, double sphere_drop) {
  const int dim = body.dofs_per_node();
  Vector u = Vector::Zero(body.dof_count());
  std::srand(5);
  for (Index n = 0; n + 1 < body.node_count(); ++n) {
    const Vec3 x = body.node_position(n);
    u[dim * n + 2] = lift * x.z() / 0.01;
    u[dim * n] = 1e-5 * std::sin(300.0 * x.y());
  }
  u[dim * (body.node_count() - 1) + 2] = -sphere_drop;
  u[dim * (body.node_count() - 1)] = 2e-6;
  return u;
}

class ContactTest : public ::testing::TestWithParam<std::string> {};

TEST_P(ContactTest, TangentMatchesFiniteDifferences) {
  RunReport report;
  std::unique_ptr<DiscreteBody> body = make_body(indentation_scene(GetParam(), "force: [0, 0, -0.01]"), report);
  ASSERT_NE(dynamic_cast<ContactBody*>(body.get()), nullptr);
  // 50 um at the centre (1e-2 of the radius): deeper than the 25 um gap at
  // the Gauss points nearest the centre on these 2 mm facets.
  const double penetration = 5e-5;
  const Vector u = pressing_state(*body, 3e-5, 2e-5);
  // The contact part alone (the body's own tangent has its own test).
  SparseMatrix K = build_pattern(*body);
  const BlockSink sink = add_into(K);
  Vector f = Vector::Zero(body->dof_count());
  body->add_nonlinear_part(u, f, &sink);
  ASSERT_GT(f.norm(), 0.0) << "no point presses";
  Vector du = Vector::Random(body->dof_count());
  Vector fp = Vector::Zero(body->dof_count()), fm = fp;
  const double h = 1e-12;  // m: far inside the active set
  body->add_nonlinear_part(u + h * du, fp, nullptr);
  body->add_nonlinear_part(u - h * du, fm, nullptr);
  const Vector numeric = (fp - fm) / (2 * h);
  const Vector analytic = K * du;
  // The tangent leaves out the curvature term, penetration / R of the normal stiffness.
  EXPECT_LT((analytic - numeric).norm(), 2.0 * penetration / 0.005 * analytic.norm());
  // The force with the tangent is the internal force; linear part + remainder is the whole.
  SparseMatrix pattern = build_pattern(*body);
  Vector whole, with_tangent, split;
  body->tangent(u, add_into(pattern), &with_tangent);
  body->internal_force(u, whole);
  EXPECT_LT((with_tangent - whole).norm(), 1e-12 * whole.norm());
  ASSERT_NE(body->linear_part(), nullptr);
  body->linear_part()->internal_force(u.head(body->linear_part()->dof_count()), split);
  split.conservativeResizeLike(Vector::Zero(body->dof_count()));
  body->add_nonlinear_part(u, split, nullptr);
  EXPECT_LT((split - whole).norm(), 1e-12 * whole.norm());
}

TEST_P(ContactTest, SphereAndBodyFeelOppositeForces) {
  RunReport report;
  std::unique_ptr<DiscreteBody> body =
      make_body(indentation_scene(GetParam(), "displacement: [0, 0, -0.0002]"), report);
  const Vector u = pressing_state(*body, 0.0, 2e-4);
  Vector f = Vector::Zero(body->dof_count());
  body->add_nonlinear_part(u, f, nullptr);
  const int dim = body->dofs_per_node();
  const Index sphere = body->node_count() - 1;
  Vec3 on_nodes = Vec3::Zero();
  for (Index n = 0; n < sphere; ++n) on_nodes += f.segment<3>(dim * n);
  const Vec3 on_sphere = f.segment<3>(dim * sphere);
  const ContactReading reading = *body->contact_reading(0, u);
  EXPECT_LT(reading.force.z(), 0.0) << "the sphere pushes the body down";
  EXPECT_LT((on_nodes + on_sphere).norm(), 1e-12 * on_sphere.norm());
  // The force the sphere exerts on the body is minus the contact part of the body's internal force.
  EXPECT_LT((reading.force + on_nodes).norm(), 1e-12 * on_nodes.norm());
  // Moved out past the block's edge x = z = 1 cm, the sphere's centre at
  // (12, 5, 14.5) mm is nearest that edge: by hand, R - |(2, 0, 4.5)| mm.
  Vector beside = u;
  beside.segment(dim * sphere, 3) = Vec3(0.007, 0.0, -0.0005);
  EXPECT_NEAR(body->contact_reading(0, beside)->indentation, 0.005 - std::hypot(0.002, 0.0045), 1e-12);
}

INSTANTIATE_TEST_SUITE_P(AllMethods, ContactTest, ::testing::Values("fem", "efg", "nodal"));

TEST(ContactReach, ASphereThatCannotReachTheBodyIsRefused) {
  Scene scene = indentation_scene("fem", "force: [0, 0, -0.01]");
  scene.contact[0].center.z() = 0.02;  // 5 mm above the top face
  RunReport report;
  testing::expect_mentions(testing::error_message([&] { make_body(scene, report); }),
                           {"test.yaml:11:", "contact.0", "cannot reach the body's boundary", "radius 0.005 m"});
  scene.contact[0].center.z() = 0.014;  // 1 mm inside
  testing::expect_mentions(testing::error_message([&] { make_body(scene, report); }),
                           {"test.yaml:11:", "contact.0", "the sphere starts 0.001", "inside the body"});
}

}  // namespace
}  // namespace kerf

// Laws registered from outside kerf (problem/user_material.h): chosen by name
// in a scene, their parameters read and refused as any key is, and evaluated
// by MaterialLaw as the built-in models are.
#include <gtest/gtest.h>

#include "core/check.h"
#include "problem/material.h"
#include "problem/scene_json.h"
#include "problem/user_material.h"
#include "support/test_support.h"

namespace kerf {
namespace {

/// The linear law times `scale`: a law whose answer the test knows.
class ScaledLinear : public UserMaterialLaw {
 public:
  ScaledLinear(const Material& m) : linear_(MaterialModel::linear, m.young, m.poisson), scale_(m.parameters.at("scale")) {}
  double energy(const Mat3& F) const override { return scale_ * linear_.energy(F); }
  Mat3 stress(const Mat3& F) const override { return scale_ * linear_.stress(F); }
  void stress_and_tangent(const Mat3& F, Mat3& P, Mat9& dPdF) const override {
    linear_.stress_and_tangent(F, P, dPdF);
    P *= scale_;
    dPdF *= scale_;
  }
  bool is_linear() const override { return true; }

 private:
  MaterialLaw linear_;
  double scale_;
};

const bool registered = register_material("scaled_linear", {"scale"}, [](const Material& m) {
  return std::make_shared<const ScaledLinear>(m);
});

const std::string box = "domain: {box: {min: [0,0,0], max: [1,1,1]}}\n";

using testing::expect_contains;

TEST(UserMaterial, ChosenByNameEvaluatedAsRegisteredAndEchoed) {
  ASSERT_TRUE(registered);
  const Scene scene = testing::scene_from_text(
      box + "material: {model: scaled_linear, young: 2.0e6, poisson: 0.25, parameters: {scale: 3}}");
  EXPECT_EQ(scene.material.model, MaterialModel::user);
  EXPECT_EQ(scene.material.user_model, "scaled_linear");
  const MaterialLaw law(scene.material), linear(MaterialModel::linear, 2.0e6, 0.25);
  Mat3 F = Mat3::Identity();
  F(0, 1) = 0.01;
  F(2, 2) = 1.02;
  EXPECT_LT((law.stress(F) - 3.0 * linear.stress(F)).norm(), 1e-12 * linear.stress(F).norm());
  EXPECT_NEAR(law.energy(F), 3.0 * linear.energy(F), 1e-12 * linear.energy(F));
  Mat3 P;
  Mat9 dPdF, linear_dPdF;
  law.stress_and_tangent(F, P, dPdF);
  linear.stress_and_tangent(F, P, linear_dPdF);
  EXPECT_LT((dPdF - 3.0 * linear_dPdF).norm(), 1e-12 * linear_dPdF.norm());
  EXPECT_TRUE(law.is_linear());
  const auto echo = scene_to_json(scene);
  EXPECT_EQ(echo["material"]["model"], "scaled_linear");
  EXPECT_EQ(echo["material"]["parameters"]["scale"], 3.0);
}

TEST(UserMaterial, ParametersAreRefusedAsAnyKeyIs) {
  expect_contains(testing::scene_refusal(box + "material: {model: scaled_linear}"), "missing 'parameters': model 'scaled_linear' needs scale");
  const std::string unknown = testing::scene_refusal(box + "material: {model: scaled_linear, parameters: {scale: 1, sacle: 2}}");
  expect_contains(unknown, "material.parameters.sacle");
  expect_contains(unknown, "expected one of: scale");
  expect_contains(testing::scene_refusal(box + "material: {model: scaled_linear, parameters: {}}"), "missing 'scale'");
  expect_contains(testing::scene_refusal(box + "material: {model: scaled_linear, parameters: {scale: soft}}"), "expected a number");
  expect_contains(testing::scene_refusal(box + "material: {model: linear, parameters: {scale: 1}}"),
                  "parameters are for a law registered from outside kerf; model 'linear' takes young and poisson only");
  const std::string unknown_model = testing::scene_refusal(box + "material: {model: mooney}");
  expect_contains(unknown_model, "expected one of linear | corotational | stvk | neohookean | neohookean_uncoupled | scaled_linear");
}

TEST(UserMaterial, NamesAreUnique) {
  EXPECT_THROW(register_material("neohookean", {}, [](const Material&) { return nullptr; }), Error);
  EXPECT_THROW(register_material("scaled_linear", {"scale"}, [](const Material& m) {
                 return std::make_shared<const ScaledLinear>(m);
               }),
               Error);
  EXPECT_THROW(MaterialLaw(MaterialModel::user, 1.0, 0.3), Error);
}

}  // namespace
}  // namespace kerf

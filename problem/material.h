#pragma once
// Constitutive laws shared by FEM and meshless code. All work on the
// deformation gradient F (3x3; plane strain keeps F(2,2) = 1):
//   energy(F)  strain energy density (J/m^3)
//   stress(F)  first Piola-Kirchhoff stress P (Pa)
//   tangent    dP/dF as a 9x9 matrix on column-major vec(F): entry (i + 3j, k + 3l)
//              is dP(i,j)/dF(k,l).
#include <memory>

#include "core/types.h"
#include "problem/scene.h"
#include "problem/user_material.h"

namespace kerf {

struct Lame {
  double lambda = 0.0;  // Pa
  double mu = 0.0;      // Pa
  static Lame from_young_poisson(double young, double poisson);
};

/// A material point law: a small value type; the model is chosen once.
class MaterialLaw {
 public:
  /// `definite_tangent`: stress_and_tangent projects dP/dF to positive semidefinite.
  /// A built-in model.
  MaterialLaw(MaterialModel model, double young, double poisson, bool definite_tangent = false);
  /// The scene's material: a built-in model, or one registered from outside kerf (user_material.h).
  explicit MaterialLaw(const Material& m, bool definite_tangent = false);

  double energy(const Mat3& F) const;
  Mat3 stress(const Mat3& F) const;
  /// P and dP/dF together (cheaper than apart for the nonlinear models); with
  /// a definite tangent, dP/dF with its negative eigenvalues set to zero where
  /// it has any (corotational, StVK and neo-Hookean tangents are indefinite
  /// under compression, which stops Cholesky; Newton is then slower there).
  void stress_and_tangent(const Mat3& F, Mat3& P, Mat9& dPdF) const;
  /// Cauchy stress sigma = P F^T / det F.
  Mat3 cauchy_stress(const Mat3& F) const;

  /// The law's bulk term written k/2 m(F)^2 (k: bulk_coefficient), for
  /// elements that average m over the nodes (the averaged-nodal-pressure
  /// tetrahedron): linear tr(eps), corotational tr(R^T F) - 3, StVK tr(E),
  /// neo-Hookean ln J (k = lambda in these); uncoupled neo-Hookean J - 1 (k = K).
  struct BulkMeasure {
    double value = 0.0;
    Mat3 gradient = Mat3::Zero();  // dm/dF
  };
  /// Every built-in model has one; a registered law has none (refused by validation).
  BulkMeasure bulk_measure(const Mat3& F) const;
  /// k of the bulk term k/2 m^2 (Pa): lambda, or the bulk modulus K = lambda + 2 mu / 3.
  double bulk_coefficient() const {
    return model_ == MaterialModel::neohookean_uncoupled ? lame_.lambda + 2.0 * lame_.mu / 3.0 : lame_.lambda;
  }
  /// W(F) less the bulk term: the element's share when the nodes hold k/2 m^2.
  double energy_without_bulk(const Mat3& F) const;
  /// P with the bulk term's measure replaced by `averaged` (m's nodal average
  /// over the element): P + k (averaged - m) dm/dF, `own` being bulk_measure(F).
  Mat3 averaged_bulk_stress(const Mat3& F, const BulkMeasure& own, double averaged) const;
  /// That P and its derivative at fixed `averaged`: dP/dF - k dm (x) dm +
  /// k (averaged - m) d2m/dF2 (the averaged term's own stiffness couples
  /// nodes: the element adds it from m's gradient). Projected as stress_and_tangent is.
  void averaged_bulk_stress_and_tangent(const Mat3& F, const BulkMeasure& own, double averaged, Mat3& P,
                                        Mat9& dPdF) const;

  /// Whether stress_and_tangent projects dP/dF (the solver switches it, per
  /// assembly, when a factorization of the exact tangent fails).
  void set_definite_tangent(bool definite) { definite_tangent_ = definite; }
  bool definite_tangent() const { return definite_tangent_; }
  /// True when P is linear in F, so the stiffness never changes.
  bool is_linear() const { return linear_; }
  MaterialModel model() const { return model_; }
  const Lame& lame() const { return lame_; }
  /// Dilatational wave speed squared times density: lambda + 2 mu (Pa).
  double p_wave_modulus() const { return lame_.lambda + 2.0 * lame_.mu; }

 private:
  /// The exact dP/dF.
  void exact_tangent(const Mat3& F, Mat3& P, Mat9& dPdF) const;
  /// d2m/dF2 of bulk_measure, as dP/dF is laid out.
  Mat9 bulk_measure_hessian(const Mat3& F) const;
  /// With a definite tangent: dP/dF symmetrized and its negative eigenvalues set to zero.
  void make_definite(Mat9& dPdF) const;

  MaterialModel model_;
  Lame lame_;
  bool definite_tangent_;
  std::shared_ptr<const UserMaterialLaw> user_;  // when model_ is user
  bool linear_;
};

/// dP/dF from its directional derivative: `dP(dF)` is the change of P along
/// dF; column k + 3l is the change along the unit dF(k, l).
template <class Directional>
Mat9 tangent_from_directions(Directional&& dP) {
  Mat9 C;
  for (int k = 0; k < 3; ++k)
    for (int l = 0; l < 3; ++l) {
      Mat3 dF = Mat3::Zero();
      dF(k, l) = 1.0;
      const Mat3 d = dP(dF);
      C.col(k + 3 * l) = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(d.data());
    }
  return C;
}

/// R of the polar decomposition F = R S (a proper rotation; S symmetric).
Mat3 polar_rotation(const Mat3& F);

/// von Mises equivalent of a Cauchy stress (Pa).
double von_mises(const Mat3& sigma);

}  // namespace kerf

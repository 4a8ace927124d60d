#pragma once
// Constitutive laws shared by FEM and meshless code. All work on the
// deformation gradient F (3x3; plane strain keeps F(2,2) = 1):
//   energy(F)  strain energy density (J/m^3)
//   stress(F)  first Piola-Kirchhoff stress P (Pa)
//   tangent    dP/dF as a 9x9 matrix on column-major vec(F): entry (i + 3j, k + 3l)
//              is dP(i,j)/dF(k,l).
#include "core/types.h"
#include "problem/scene.h"

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
  MaterialLaw(MaterialModel model, double young, double poisson, bool definite_tangent = false);
  explicit MaterialLaw(const Material& m, bool definite_tangent = false)
      : MaterialLaw(m.model, m.young, m.poisson, definite_tangent) {}

  double energy(const Mat3& F) const;
  Mat3 stress(const Mat3& F) const;
  /// P and dP/dF together (cheaper than apart for the nonlinear models); with
  /// a definite tangent, dP/dF with its negative eigenvalues set to zero where
  /// it has any (corotational, StVK and neo-Hookean tangents are indefinite
  /// under compression, which stops Cholesky; Newton is then slower there).
  void stress_and_tangent(const Mat3& F, Mat3& P, Mat9& dPdF) const;
  /// Cauchy stress sigma = P F^T / det F.
  Mat3 cauchy_stress(const Mat3& F) const;

  /// True when P is linear in F, so the stiffness never changes.
  bool is_linear() const { return model_ == MaterialModel::linear; }
  MaterialModel model() const { return model_; }
  const Lame& lame() const { return lame_; }
  /// Dilatational wave speed squared times density: lambda + 2 mu (Pa).
  double p_wave_modulus() const { return lame_.lambda + 2.0 * lame_.mu; }

 private:
  /// The exact dP/dF.
  void exact_tangent(const Mat3& F, Mat3& P, Mat9& dPdF) const;

  MaterialModel model_;
  Lame lame_;
  bool definite_tangent_;
};

/// R of the polar decomposition F = R S (a proper rotation; S symmetric).
Mat3 polar_rotation(const Mat3& F);

/// von Mises equivalent of a Cauchy stress (Pa).
double von_mises(const Mat3& sigma);

}  // namespace kerf

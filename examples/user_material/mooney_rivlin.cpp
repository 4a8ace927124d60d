// A compressible Mooney-Rivlin law, defined outside kerf and registered under
// the name `mooney_rivlin`:
//   W = c1 (I1 - 3) + c2 (I2 - 3) - 2 (c1 + 2 c2) ln J + (lambda' / 2) ln^2 J,
// with c1 = mu/2 - c2 and lambda' = lambda - 4 c2, mu and lambda from the
// scene's young and poisson, so that the law is stress-free at rest and
// linearises to the same small-strain moduli. Its one constant, c2 (Pa), is
// `material.parameters.c2`; c2 = 0 is kerf's neo-Hookean law exactly.
#include <cmath>
#include <limits>

#include "problem/material.h"
#include "problem/user_material.h"

namespace {

class MooneyRivlin : public kerf::UserMaterialLaw {
 public:
  MooneyRivlin(double mu, double lambda, double c2) : c1_(0.5 * mu - c2), c2_(c2), lambda_(lambda - 4.0 * c2) {}

  double energy(const kerf::Mat3& F) const override {
    const double J = F.determinant();
    if (!(J > 0.0)) return std::numeric_limits<double>::infinity();
    const kerf::Mat3 C = F.transpose() * F;
    const double I1 = C.trace(), I2 = 0.5 * (I1 * I1 - (C * C).trace()), log_J = std::log(J);
    return c1_ * (I1 - 3.0) + c2_ * (I2 - 3.0) - 2.0 * (c1_ + 2.0 * c2_) * log_J + 0.5 * lambda_ * log_J * log_J;
  }

  kerf::Mat3 stress(const kerf::Mat3& F) const override {
    const double J = F.determinant();
    if (!(J > 0.0)) return kerf::Mat3::Constant(std::numeric_limits<double>::quiet_NaN());
    const kerf::Mat3 C = F.transpose() * F, F_inv_T = F.inverse().transpose();
    return 2.0 * c1_ * F + 2.0 * c2_ * (C.trace() * F - F * C) +
           (lambda_ * std::log(J) - 2.0 * (c1_ + 2.0 * c2_)) * F_inv_T;
  }

  void stress_and_tangent(const kerf::Mat3& F, kerf::Mat3& P, kerf::Mat9& dPdF) const override {
    P = stress(F);
    if (!P.allFinite()) {
      dPdF = kerf::Mat9::Constant(std::numeric_limits<double>::quiet_NaN());
      return;
    }
    const kerf::Mat3 C = F.transpose() * F, F_inv = F.inverse(), F_inv_T = F_inv.transpose();
    const double I1 = C.trace(), volumetric = lambda_ * std::log(F.determinant()) - 2.0 * (c1_ + 2.0 * c2_);
    dPdF = kerf::tangent_from_directions([&](const kerf::Mat3& H) {
      const kerf::Mat3 dC = H.transpose() * F + F.transpose() * H;
      return kerf::Mat3(2.0 * c1_ * H + 2.0 * c2_ * (2.0 * (F.array() * H.array()).sum() * F + I1 * H - H * C - F * dC) -
                        volumetric * F_inv_T * H.transpose() * F_inv_T +
                        lambda_ * (F_inv * H).trace() * F_inv_T);
    });
  }

 private:
  double c1_, c2_, lambda_;
};

const bool registered = kerf::register_material("mooney_rivlin", {"c2"}, [](const kerf::Material& m) {
  const kerf::Lame lame = kerf::Lame::from_young_poisson(m.young, m.poisson);
  return std::make_shared<const MooneyRivlin>(lame.mu, lame.lambda, m.parameters.at("c2"));
});

}  // namespace

#pragma once
// The Hertz problem the `hertz` and `pareto` studies share: a quarter block
// pressed by a rigid sphere with the force that gives a contact radius
// a = R / 10 on a half-space (see studies/hertz.cpp for the whole setting).
#include <vector>

#include "problem/scene.h"

namespace kerf::hertz {

constexpr double contact_radius = 1.0e-3;        // a (m)
constexpr double sphere_radius = 10.0e-3;        // R (m)
constexpr double young = 1.0e4, poisson = 0.3;   // Pa: soft tissue
constexpr double finest_box = 1.5 * contact_radius;  // the finest box's edge
constexpr int graded_levels = 8;                 // nested boxes: block edge 1.5 a 2^8 = 384 a
constexpr double graded_block = finest_box * (1 << graded_levels);
constexpr double uniform_block = 8.0 * contact_radius;

/// Hertz's indentation d = a^2 / R (m).
double indentation();
/// The total force (N) that gives indentation() on a half-space.
double force();

/// A discretization of the block: method, FEM element, meshless gradient.
struct MethodChoice {
  Method method;
  ElementType element = ElementType::tet4;
  NodalGradient gradient = NodalGradient::direct;
};

/// The scene: a quarter block of edge `block`, spacing `coarse` outside the
/// refine boxes `refine`, the sphere touching the top face; probes `indent`
/// (indentation) and `push` (contact force).
Scene scene(const MethodChoice& d, double block, double coarse, const std::vector<RefineRegion>& refine = {});

/// The graded scene whose finest spacing is a / n: nested refine boxes at the
/// contact, box k of edge finest_box 2^k and spacing h 2^k, so each coarser
/// lattice falls on the finer one inside it, out to graded_block.
Scene graded_scene(const MethodChoice& d, int n);

}  // namespace kerf::hertz

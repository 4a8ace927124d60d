#pragma once
// Every discretization method, described once: its scene spelling
// (discretization.method), whether it is meshless, where it integrates the
// weak form, how it holds essential conditions by default, and whether a
// growing cut rebuilds its body. The body factory, the scene's validation and
// the resource estimate read these rows (and body_plan.h, which derives what
// a scene's body is built from); a new method is a row here, a case in
// discretization/body_factory.cpp and its body's own files.
#include <array>

#include "core/enum_table.h"

namespace kerf {

enum class Method { fem, efg, nodal };
enum class EssentialMethod { penalty, nitsche, parameters };

/// Where the weak form's integrals are evaluated.
enum class Integration {
  element_quadrature,  // the body's own cells (FEM)
  background_cells,    // Gauss points in a background mesh's cells (EFG)
  at_nodes,            // one point a node, its volume (nodal integration)
};

struct MethodDescriptor {
  Method method;
  const char* name;
  bool meshless;  // MLS shape functions over a node set (discretization.meshless)
  Integration integration;
  /// fix/displacement by default: EFG weakly by Nitsche; nodal integration on
  /// the nodal parameters, the paper's way (Nitsche's form can be indefinite
  /// there: nodal integration holds its low-energy modes weakly). Unused by FEM.
  EssentialMethod essential;
  /// A growing cut meshes the body anew (FEM), where meshless bodies change
  /// shape functions in place: such a body runs whole on every MPI rank.
  bool rebuilt_as_cut_grows;
};

inline constexpr std::array<MethodDescriptor, 3> methods{{
    {Method::fem, "fem", false, Integration::element_quadrature, EssentialMethod::parameters, true},
    {Method::efg, "efg", true, Integration::background_cells, EssentialMethod::nitsche, false},
    {Method::nodal, "nodal", true, Integration::at_nodes, EssentialMethod::parameters, false},
}};

static_assert(rows_follow_enum(methods, &MethodDescriptor::method), "methods: one row per Method, in its order");

constexpr const MethodDescriptor& method_descriptor(Method method) { return row_of(methods, method); }

}  // namespace kerf

#pragma once
// The parsed, validated scene: every key of SCENES.md with its default filled in.
// Units are SI (m, kg, s, Pa, N). In 2D (plane strain) vectors keep z = 0.
#include <array>
#include <map>
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "core/element_types.h"
#include "core/linear_backends.h"
#include "core/types.h"
#include "problem/methods.h"
#include "problem/selection.h"
#include "problem/source_location.h"

namespace kerf {

// `user`: a law registered from outside kerf (user_material.h), named by
// Material::user_model; it has no EnumNames spelling.
enum class MaterialModel { linear, corotational, stvk, neohookean, neohookean_uncoupled, user };
/// Where a linear simplex holds its law's bulk term: in each cell (locks as
/// nu nears 0.5), or averaged over the nodes (averaged nodal pressure).
enum class FemVolumetric { element, averaged_nodal };
enum class NodePlacement { lattice, mesh };
enum class MlsBasis { linear, quadratic };
enum class WeightFunction { quartic };
enum class NodalGradient { direct, smoothed };
/// efg: each background cell's rule: the collapsed Gauss product
/// (quadrature.order points a direction) or a fully symmetric one (exact to
/// quadrature.degree, core/symmetric_rule_degrees.h).
enum class CellRule { gauss, symmetric };
/// The order of the variationally consistent correction of nodal integration's test gradients.
enum class VciOrder { none, linear };
/// nodal: what holds the zero-energy modes (none, the hourglass-type pair
/// term, or naturally stabilized nodal integration's strain gradients).
enum class NodalStabilization { none, hourglass, nsni };
/// nodal: the cells a cut crosses kept whole (the paper's nodal points), or
/// split: the nodes' volumes on their own side, the cells at the cut
/// integrated by their parts (visible_dual_cells.h); automatic: split unless
/// a cut grows (cut_cells_of).
enum class CutCells { automatic, whole, split };
/// efg, and where a meshless body integrates boundary loads or contact: its
/// background cells. `lattice`: the node lattice's own squares and cubes
/// split into simplices (geometry/lattice_cells.h), no mesher; `mesh`: gmsh's
/// mesh of the box at the spacing, or the mesh the nodes come from;
/// automatic: lattice where it can be, uncut and untouched (background_cells_of).
enum class BackgroundCells { automatic, lattice, mesh };
/// fem in a box: who meshes it. `gmsh` (unstructured, edges near fem.size),
/// or `lattice`: the box's lattice at fem.size split into simplices as the
/// meshless background cells are (geometry/lattice_cells.h), mid-edge nodes
/// added for second order; no mesher loaded.
enum class FemBoxMesher { gmsh, lattice };
enum class Analysis { static_analysis, dynamic };
enum class Integrator { implicit_euler, newmark, central_difference };
enum class MassKind { lumped, consistent };
enum class TangentKind { exact, definite, automatic };
enum class Enrichment { grid, multiplicative, single, visibility, diffraction };
enum class GridLookup { exact, interpolated };
enum class FemCut { remesh, remove, split };
/// fem: split's cells that the cut's front passes through: left whole (the
/// papers' rule: the jump ends about a cell behind the front), or split along
/// the nearest piece's plane (the jump reaches about a cell past it), or
/// subdivided so that the front runs along their edges (the jump ends on it).
enum class SplitFront { lag, over, subdivide };
enum class ProbeField { displacement, reaction, indentation, contact_force, energy };

struct BoundaryCondition {
  Selection select;
  std::array<bool, 3> fixed{false, false, false};                  // held at zero
  std::array<std::optional<double>, 3> displacement;               // prescribed (m)
  std::optional<Vec3> traction;                                    // Pa
  std::optional<double> pressure;                                  // Pa, along the inward normal
  bool is_dirichlet() const;
  SourceLocation where;
};

struct Material {
  MaterialModel model = MaterialModel::linear;
  double young = 1.0e6;    // Pa
  double poisson = 0.3;
  double density = 1000.0; // kg/m^3
  double damping_mass = 0.0;       // Rayleigh alpha (1/s)
  double damping_stiffness = 0.0;  // Rayleigh beta (s)
  std::string user_model{};                    // the registered name when model is user
  std::map<std::string, double> parameters{};  // a user model's own constants
};

struct RefineRegion {
  Box box;
  double size = 0.0;  // m
};

struct FemOptions {
  ElementType element = ElementType::tet4;
  double size = 0.0025;  // m
  FemVolumetric volumetric = FemVolumetric::element;
  SplitFront split_front = SplitFront::lag;
  /// fem: split: nodes within this share of their shortest edge of the cut
  /// lie on it (no sliver thinner than about that); 0: the cut exactly as
  /// given, no node moved and no fragment dropped however thin.
  double split_snap = 0.05;
  FemBoxMesher box_mesher = FemBoxMesher::gmsh;
};

struct MeshlessOptions {
  NodePlacement nodes = NodePlacement::lattice;
  double spacing = 0.0025;  // m
  double support = 2.2;     // multiple of spacing
  MlsBasis basis = MlsBasis::linear;
  WeightFunction weight = WeightFunction::quartic;
  CellRule quadrature_rule = CellRule::gauss;
  int quadrature_order = 2;   // gauss: points a cell direction
  int quadrature_degree = 5;  // symmetric: the degree integrated exactly
  /// How fix/displacement act; unset: the method's default (essential_method).
  std::optional<EssentialMethod> essential;
  NodalStabilization stabilization = NodalStabilization::hourglass;  // true: hourglass, false: none
  NodalGradient gradient = NodalGradient::direct;  // nodal: MLS gradient at the node, or SCNI
  /// nodal: test gradients corrected to keep the integration constraint
  /// (integration_constraint.h); off until the studies are re-run with it.
  VciOrder vci = VciOrder::none;
  CutCells cut_cells = CutCells::automatic;
  BackgroundCells background_cells = BackgroundCells::automatic;
  /// Nitsche's alpha over its local estimate; unset: the method's default
  /// (nitsche_safety_default).
  std::optional<double> nitsche_safety;
};

/// fix/displacement for a meshless method: as the scene says, else the method's default (methods.h).
inline EssentialMethod essential_method(const MeshlessOptions& options, Method method) {
  return options.essential.value_or(method_descriptor(method).essential);
}

/// The default safety of Nitsche's alpha over its estimate (the largest
/// one-parameter Rayleigh quotient, a lower bound): the least that held
/// was 4-8 on a curved organ mesh, 8-16 on the cracked plate (EFG); larger
/// stiffens coarse bodies (the organ's EFG end probe -3.5% at 8, -7.5% at 32).
constexpr double nitsche_safety_default = 32.0;
inline double nitsche_safety(const MeshlessOptions& options) {
  return options.nitsche_safety.value_or(nitsche_safety_default);
}

struct DiscretizationOptions {
  Method method = Method::fem;
  FemOptions fem;
  std::vector<RefineRegion> refine;
  MeshlessOptions meshless;
};

struct ContactSphere {
  Vec3 center = Vec3::Zero();
  double radius = 0.0;
  std::optional<Vec3> force;         // N
  std::optional<Vec3> displacement;  // m
  SourceLocation where;
};

struct Cut {
  std::vector<Vec3> vertices;  // 3D strip vertices or 2D polyline vertices; none: fed at run time (live)
  bool is_strip = false;
  std::vector<double> times;   // one per vertex (s)
  /// A session may feed it vertices as the run goes (Session::extend_cut): `live: true`, or no vertex given.
  bool live = false;
  /// Pieces appear after t = 0 (a live cut, or a time > 0).
  bool grows() const { return live || (!times.empty() && times.back() > 0.0); }
  Enrichment enrichment = Enrichment::grid;
  double grid_spacing = 0.0005;  // m
  GridLookup grid_lookup = GridLookup::exact;
  FemCut fem = FemCut::remesh;
  SourceLocation where;
};

struct NewtonOptions {
  double tolerance = 1.0e-8;  // relative residual
  /// N; unset: a fraction of the problem's load scale (newton.h absolute_floor_fraction).
  std::optional<double> absolute_tolerance;
  double step_tolerance = 1.0e-8;        // |du| relative to |u| (PETSc's stol)
  double divergence_tolerance = 1.0e4;   // |r| past this many times the first: diverged (PETSc's divtol)
  int max_iterations = 25;
  bool line_search = true;
};

struct SolveOptions {
  Analysis analysis = Analysis::static_analysis;
  Integrator integrator = Integrator::implicit_euler;
  double dt = 0.001;       // s
  double duration = 1.0;   // s
  /// Central differences run a dt above the critical step instead of refusing
  /// it (the stability study looks for the true limit this way).
  bool allow_unstable_dt = false;
  int load_steps = 1;      // static: load increments (the first guess when adapt is on)
  /// A static increment or implicit time step whose Newton solve fails is
  /// halved (at most max_cutbacks times) and grown again after easy ones;
  /// the run's output steps stay the scene's.
  bool adapt = true;
  int max_cutbacks = 10;
  NewtonOptions newton;
  LinearSolverKind linear_solver = LinearSolverKind::cholmod;
  std::string petsc = "-ksp_type cg -pc_type gamg";
  /// Whether the scene (or --set) wrote solve.petsc: left out, a run on
  /// several MPI ranks adds kerf's memory options to it (petsc_rank_options).
  bool petsc_written = false;
  double linear_tolerance = 1.0e-10;  // relative residual of iterative linear solves
  MassKind mass = MassKind::consistent;  // implicit runs; explicit always lumps
  /// The material tangent implicit solves assemble: exact, made positive
  /// semidefinite point by point (nonlinear materials under compression), or
  /// exact with the definite one for an iteration whose factorization fails.
  TangentKind tangent = TangentKind::automatic;

  /// Static and implicit runs solve linear systems; explicit ones do not.
  bool solves_linear_systems() const {
    return analysis == Analysis::static_analysis || integrator != Integrator::central_difference;
  }
};

struct Probe {
  std::string name;
  ProbeField field = ProbeField::displacement;
  std::optional<Vec3> point;
  std::optional<Selection> select;
  std::optional<int> contact;
  SourceLocation where;
};

struct OutputOptions {
  std::string dir;       // resolved: absolute or relative to the working directory
  int vtk_every = 10;    // 0 = no VTK output
  std::vector<Probe> probes;
};

struct Scene {
  std::string name = "scene";
  std::string file;        // the scene file ("" when built in code)
  int dimension = 3;
  std::optional<Box> box;
  std::string mesh_file;   // resolved path when domain.mesh is used
  Material material;
  DiscretizationOptions discretization;
  std::vector<BoundaryCondition> boundary;
  Vec3 gravity = Vec3::Zero();
  std::vector<ContactSphere> contact;
  std::vector<Cut> cuts;
  SolveOptions solve;
  OutputOptions output;
  KeyLocations sources;  // where each key came from (scenes read from a file)

  /// Where `key` came from: its file position and text when read from a file,
  /// else the scene's file (if any) and the key alone.
  SourceLocation locate(const std::string& key) const;
};

/// meshless.cut_cells as it acts: `auto` is split for direct nodal
/// integration without VCI (the only kind split cells are built for) unless
/// a cut grows, where splitting costs a growth far more than the paper's
/// update (docs/meshless_integration.md, "Cells at a cut").
inline CutCells cut_cells_of(const Scene& scene) {
  const MeshlessOptions& m = scene.discretization.meshless;
  if (m.cut_cells != CutCells::automatic) return m.cut_cells;
  const bool grows = std::any_of(scene.cuts.begin(), scene.cuts.end(), [](const Cut& c) { return c.grows(); });
  const bool built_for = scene.discretization.method == Method::nodal && m.gradient == NodalGradient::direct &&
                         m.vci == VciOrder::none;
  return built_for && !grows ? CutCells::split : CutCells::whole;
}

/// Can the background cells be the node lattice's own: lattice nodes in a
/// box without refine regions (a refined lattice's cells would not meet).
inline bool lattice_cells_possible(const Scene& scene) {
  return scene.box && scene.discretization.meshless.nodes == NodePlacement::lattice &&
         scene.discretization.refine.empty();
}

/// meshless.background_cells as it acts: `auto` is the lattice's own cells
/// where they can be and meet neither a cut nor a sphere, else the mesh. A
/// cut's cells are integrated as they stand, so EFG's answer there depends on
/// how they meet it, and a lattice's planes meet a planar cut all alike (the
/// cut block at 3 mm sagged 5.1% over the reference on lattice cells against
/// 3.1% under on gmsh's, whose figures the cut studies hold). With a sphere
/// a force-driven one settled 2.4e-3 off the depth against 2.6e-4 on gmsh's
/// (its samples on a lattice's faces lie in rings, most likely touching all
/// at once). docs/scenes.md has the figures.
inline BackgroundCells background_cells_of(const Scene& scene) {
  const BackgroundCells asked = scene.discretization.meshless.background_cells;
  if (asked != BackgroundCells::automatic) return asked;
  const bool lattice = lattice_cells_possible(scene) && scene.cuts.empty() && scene.contact.empty();
  return lattice ? BackgroundCells::lattice : BackgroundCells::mesh;
}

/// The scene file's spelling of each value of an enum, in declaration order:
/// the reader, `to_string` and the resolved-scene echo all use these.
template <class E>
struct EnumNames;
#define KERF_ENUM_NAMES(Enum, ...)                                  \
  template <>                                                       \
  struct EnumNames<Enum> {                                          \
    static constexpr auto names = std::to_array<const char*>({__VA_ARGS__}); \
  }
KERF_ENUM_NAMES(MaterialModel, "linear", "corotational", "stvk", "neohookean", "neohookean_uncoupled");
KERF_ENUM_NAMES(FemVolumetric, "element", "averaged_nodal");
KERF_ENUM_NAMES(NodePlacement, "lattice", "mesh");
KERF_ENUM_NAMES(MlsBasis, "linear", "quadratic");
KERF_ENUM_NAMES(WeightFunction, "quartic");
KERF_ENUM_NAMES(EssentialMethod, "penalty", "nitsche", "parameters");
KERF_ENUM_NAMES(NodalGradient, "direct", "smoothed");
KERF_ENUM_NAMES(CellRule, "gauss", "symmetric");
KERF_ENUM_NAMES(VciOrder, "none", "linear");
KERF_ENUM_NAMES(NodalStabilization, "none", "hourglass", "nsni");
KERF_ENUM_NAMES(CutCells, "auto", "whole", "split");
KERF_ENUM_NAMES(BackgroundCells, "auto", "lattice", "mesh");
KERF_ENUM_NAMES(FemBoxMesher, "gmsh", "lattice");
KERF_ENUM_NAMES(Analysis, "static", "dynamic");
KERF_ENUM_NAMES(Integrator, "implicit-euler", "newmark", "central-difference");
KERF_ENUM_NAMES(MassKind, "lumped", "consistent");
KERF_ENUM_NAMES(TangentKind, "exact", "definite", "auto");
KERF_ENUM_NAMES(Enrichment, "grid", "multiplicative", "single", "visibility", "diffraction");
KERF_ENUM_NAMES(GridLookup, "exact", "interpolated");
KERF_ENUM_NAMES(FemCut, "remesh", "remove", "split");
KERF_ENUM_NAMES(SplitFront, "lag", "over", "subdivide");
KERF_ENUM_NAMES(ProbeField, "displacement", "reaction", "indentation", "contact_force", "energy");
#undef KERF_ENUM_NAMES
/// The spellings of the kinds described by a table (core/enum_table.h's names_of).
template <>
struct EnumNames<Method> {
  static constexpr auto names = names_of(methods);
};
template <>
struct EnumNames<LinearSolverKind> {
  static constexpr auto names = names_of(linear_backends);
};
template <>
struct EnumNames<ElementType> {
  static constexpr auto names = names_of(element_types);
};

template <class E>
const char* to_string(E value) {
  return EnumNames<E>::names.at(static_cast<std::size_t>(value));  // MaterialModel::user has no spelling
}

}  // namespace kerf

#include "problem/scene_reader.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <yaml-cpp/depthguard.h>

#include "core/check.h"
#include "problem/scene_overrides.h"
#include "problem/scene_validation.h"
#include "problem/user_material.h"
#include "problem/yaml_access.h"

namespace kerf {
namespace {

namespace fs = std::filesystem;

Box read_box(const YamlField& f, int dim) {
  f.allow_only({"min", "max"});
  Box box;
  box.min = f["min"].vector(dim);
  box.max = f["max"].vector(dim);
  return box;
}

int read_axis(const YamlField& f) {
  static constexpr std::array<const char*, 3> axes{"x", "y", "z"};
  return f.choice(axes);
}

Selection read_selection(const YamlField& f, int dim) {
  Selection s;
  s.where = f.location();
  f.allow_only({"plane", "box", "point"});
  std::string kind = f.exactly_one_of({"plane", "box", "point"});
  if (kind == "plane") {
    YamlField p = f["plane"];
    p.allow_only({"axis", "at"});
    s.kind = Selection::Kind::plane;
    s.axis = read_axis(p["axis"]);
    s.at = p["at"].number();
  } else if (kind == "box") {
    s.kind = Selection::Kind::box;
    s.box = read_box(f["box"], dim);
  } else {
    s.kind = Selection::Kind::point;
    s.point = f["point"].vector(dim);
  }
  return s;
}

std::array<bool, 3> read_fixed_components(const YamlField& f, int dim) {
  if (!f.is_sequence() || f.size() == 0)
    f.fail("expected a list of components such as [x, y" + std::string(dim == 3 ? ", z]" : "]") +
           ", found " + f.value_text());
  std::array<bool, 3> fixed{false, false, false};
  for (std::size_t i = 0; i < f.size(); ++i) fixed[read_axis(f[i])] = true;
  return fixed;
}

BoundaryCondition read_boundary_item(const YamlField& f, int dim) {
  BoundaryCondition bc;
  bc.where = f.location();
  f.allow_only({"select", "fix", "displacement", "traction", "pressure"});
  if (!f.has("select")) f.fail("missing 'select': which part of the boundary this item applies to");
  bc.select = read_selection(f["select"], dim);
  if (f.has("fix")) bc.fixed = read_fixed_components(f["fix"], dim);
  if (f.has("displacement")) bc.displacement = f["displacement"].optional_vector(dim);
  if (f.has("traction")) bc.traction = f["traction"].vector(dim);
  if (f.has("pressure")) bc.pressure = f["pressure"].number();
  return bc;
}

/// A built-in model's name, or one registered from outside kerf (user_material.h).
void read_material_model(const YamlField& f, Material& m) {
  const std::string name = f.text();
  const auto& builtin = EnumNames<MaterialModel>::names;
  if (auto it = std::find(builtin.begin(), builtin.end(), name); it != builtin.end()) {
    m.model = static_cast<MaterialModel>(it - builtin.begin());
    return;
  }
  if (find_user_material(name)) {
    m.model = MaterialModel::user;
    m.user_model = name;
    return;
  }
  std::string list;
  for (const char* b : builtin) list += (list.empty() ? "" : " | ") + std::string(b);
  for (const std::string& u : user_material_names()) list += " | " + u;
  f.fail("value " + f.value_text() + " is not allowed; expected one of " + list +
         " (or a law registered from outside kerf, as examples/user_material does)");
}

/// A registered law's constants: each it declares, and no other.
void read_material_parameters(const YamlField& material, Material& m) {
  const UserMaterialEntry* entry = m.model == MaterialModel::user ? find_user_material(m.user_model) : nullptr;
  std::string names;
  if (entry)
    for (const std::string& p : entry->parameters) names += (names.empty() ? "" : ", ") + p;
  if (!material.has("parameters") || material["parameters"].is_null()) {  // `parameters: ~` is none
    if (entry && !entry->parameters.empty())
      material.fail("missing 'parameters': model '" + m.user_model + "' needs " + names);
    return;
  }
  const YamlField f = material["parameters"];
  if (!entry)
    f.fail(std::string("parameters are for a law registered from outside kerf; model '") + to_string(m.model) +
           "' takes young and poisson only");
  std::vector<const char*> allowed;
  for (const std::string& p : entry->parameters) allowed.push_back(p.c_str());
  f.allow_only(allowed);
  for (const std::string& p : entry->parameters) {
    if (!f.has(p)) f.fail("missing '" + p + "': model '" + m.user_model + "' needs " + names);
    m.parameters[p] = f[p].number();
  }
}

void read_material(const YamlField& f, Material& m) {
  f.allow_only({"model", "young", "poisson", "density", "damping", "parameters"});
  if (f.has("model")) read_material_model(f["model"], m);
  read_material_parameters(f, m);
  if (f.has("young")) m.young = f["young"].number();
  if (f.has("poisson")) m.poisson = f["poisson"].number();
  if (f.has("density")) m.density = f["density"].number();
  if (f.has("damping")) {
    YamlField d = f["damping"];
    d.allow_only({"mass", "stiffness"});
    if (d.has("mass")) m.damping_mass = d["mass"].number();
    if (d.has("stiffness")) m.damping_stiffness = d["stiffness"].number();
  }
}

/// meshless.stabilization: a name, or true and false as the key always took
/// (the hourglass term, none).
NodalStabilization read_stabilization(const YamlField& f) {
  const std::string value = f.text();
  for (const char* name : EnumNames<NodalStabilization>::names)
    if (value == name) return f.enumeration<NodalStabilization>();
  static constexpr const char* accepted[] = {"true (hourglass)", "false (none)", "none", "hourglass", "nsni"};
  try {
    return f.boolean() ? NodalStabilization::hourglass : NodalStabilization::none;
  } catch (const Error&) {
    f.choice(accepted);  // fails, naming what is accepted
    throw;
  }
}

void read_discretization(const YamlField& f, int dim, DiscretizationOptions& d) {
  if (dim == 2) d.fem.element = ElementType::tri3;
  if (f.is_null()) return;
  f.allow_only({"method", "fem", "refine", "meshless"});
  if (f.has("method")) d.method = f["method"].enumeration<Method>();
  if (f.has("fem")) {
    YamlField fe = f["fem"];
    fe.allow_only({"element", "size", "volumetric", "split_front", "split_snap", "box_mesher"});
    if (fe.has("element"))
      d.fem.element = fe["element"].enumeration<ElementType>();
    if (fe.has("size")) d.fem.size = fe["size"].number();
    if (fe.has("volumetric")) d.fem.volumetric = fe["volumetric"].enumeration<FemVolumetric>();
    if (fe.has("split_front")) d.fem.split_front = fe["split_front"].enumeration<SplitFront>();
    if (fe.has("split_snap")) d.fem.split_snap = fe["split_snap"].number();
    if (fe.has("box_mesher")) d.fem.box_mesher = fe["box_mesher"].enumeration<FemBoxMesher>();
  }
  if (f.has("refine")) {
    YamlField list = f["refine"];
    if (!list.is_sequence()) list.fail("expected a list of {box, size} items, found " + list.value_text());
    for (std::size_t i = 0; i < list.size(); ++i) {
      YamlField r = list[i];
      r.allow_only({"box", "size"});
      RefineRegion region;
      region.box = read_box(r["box"], dim);
      region.size = r["size"].number();
      d.refine.push_back(region);
    }
  }
  if (f.has("meshless")) {
    YamlField m = f["meshless"];
    m.allow_only({"nodes", "spacing", "support", "basis", "weight", "quadrature", "essential", "stabilization", "gradient",
                  "vci", "cut_cells", "background_cells", "nitsche_safety"});
    MeshlessOptions& o = d.meshless;
    if (m.has("nodes")) o.nodes = m["nodes"].enumeration<NodePlacement>();
    if (m.has("spacing")) o.spacing = m["spacing"].number();
    if (m.has("support")) o.support = m["support"].number();
    if (m.has("basis")) o.basis = m["basis"].enumeration<MlsBasis>();
    if (m.has("weight")) o.weight = m["weight"].enumeration<WeightFunction>();
    if (m.has("quadrature")) {
      YamlField q = m["quadrature"];
      q.allow_only({"rule", "order", "degree"});
      if (q.has("rule")) o.quadrature_rule = q["rule"].enumeration<CellRule>();
      const bool symmetric = o.quadrature_rule == CellRule::symmetric;
      // Each rule's key beside the other rule would be ignored.
      if (q.has("order") && symmetric)
        q["order"].fail("value " + q["order"].value_text() +
                        " is for rule: gauss, but rule is 'symmetric'; expected degree");
      if (q.has("degree") && !symmetric)
        q["degree"].fail("value " + q["degree"].value_text() +
                         " is for rule: symmetric, but rule is 'gauss' (the default); expected order, or rule: "
                         "symmetric");
      if (q.has("order")) o.quadrature_order = q["order"].integer();
      if (q.has("degree")) o.quadrature_degree = q["degree"].integer();
    }
    if (m.has("essential"))
      o.essential = m["essential"].enumeration<EssentialMethod>();
    if (m.has("stabilization")) o.stabilization = read_stabilization(m["stabilization"]);
    if (m.has("gradient")) o.gradient = m["gradient"].enumeration<NodalGradient>();
    if (m.has("vci")) o.vci = m["vci"].enumeration<VciOrder>();
    if (m.has("cut_cells")) o.cut_cells = m["cut_cells"].enumeration<CutCells>();
    if (m.has("background_cells")) o.background_cells = m["background_cells"].enumeration<BackgroundCells>();
    if (m.has("nitsche_safety")) o.nitsche_safety = m["nitsche_safety"].number();
  }
}

ContactSphere read_contact(const YamlField& f, int dim) {
  ContactSphere c;
  c.where = f.location();
  f.allow_only({"sphere", "force", "displacement"});
  YamlField s = f["sphere"];
  if (s.is_null()) f.fail("missing 'sphere: {center, radius}'");
  s.allow_only({"center", "radius"});
  c.center = s["center"].vector(dim);
  c.radius = s["radius"].number();
  std::string drive = f.exactly_one_of({"force", "displacement"});
  if (drive == "force")
    c.force = f["force"].vector(dim);
  else
    c.displacement = f["displacement"].vector(dim);
  return c;
}

Cut read_cut(const YamlField& f, int dim) {
  Cut cut;
  cut.where = f.location();
  f.allow_only({"strip", "polyline", "times", "enrichment", "grid", "fem", "live"});
  std::string kind = f.exactly_one_of({"strip", "polyline"});
  cut.is_strip = kind == "strip";
  YamlField v = f[kind];
  if (!v.is_sequence()) v.fail("expected a list of vertices, found " + v.value_text());
  for (std::size_t i = 0; i < v.size(); ++i) cut.vertices.push_back(v[i].vector(dim));
  if (f.has("times")) {
    cut.times = f["times"].numbers();
  } else {
    cut.times.assign(cut.vertices.size(), 0.0);
  }
  if (f.has("enrichment"))
    cut.enrichment = f["enrichment"].enumeration<Enrichment>();
  if (f.has("grid")) {
    YamlField g = f["grid"];
    g.allow_only({"spacing", "lookup"});
    if (g.has("spacing")) cut.grid_spacing = g["spacing"].number();
    if (g.has("lookup")) cut.grid_lookup = g["lookup"].enumeration<GridLookup>();
  }
  if (f.has("fem")) cut.fem = f["fem"].enumeration<FemCut>();
  // A cut given no vertex can only be fed at run time: it is live whatever the key says.
  cut.live = cut.vertices.empty() || (f.has("live") && f["live"].boolean());
  return cut;
}

void read_solve(const YamlField& f, Method method, SolveOptions& s) {
  // The nodal method defaults to explicit dynamics at 1 ms, as in the paper.
  if (method == Method::nodal) {
    s.analysis = Analysis::dynamic;
    s.integrator = Integrator::central_difference;
  }
  if (f.is_null()) return;
  f.allow_only({"analysis", "integrator", "dt", "duration", "newton", "linear_solver", "petsc",
                "linear_tolerance", "mass", "load_steps", "allow_unstable_dt", "tangent", "adapt",
                "max_cutbacks"});
  if (f.has("analysis")) s.analysis = f["analysis"].enumeration<Analysis>();
  if (f.has("integrator"))
    s.integrator = f["integrator"].enumeration<Integrator>();
  if (f.has("dt")) s.dt = f["dt"].number();
  if (f.has("duration")) s.duration = f["duration"].number();
  if (f.has("allow_unstable_dt")) s.allow_unstable_dt = f["allow_unstable_dt"].boolean();
  if (f.has("load_steps")) s.load_steps = f["load_steps"].integer();
  if (f.has("adapt")) s.adapt = f["adapt"].boolean();
  if (f.has("max_cutbacks")) s.max_cutbacks = f["max_cutbacks"].integer();
  if (f.has("newton")) {
    YamlField n = f["newton"];
    n.allow_only({"tolerance", "absolute_tolerance", "step_tolerance", "divergence_tolerance", "max_iterations",
                  "line_search"});
    if (n.has("tolerance")) s.newton.tolerance = n["tolerance"].number();
    if (n.has("absolute_tolerance")) s.newton.absolute_tolerance = n["absolute_tolerance"].number();
    if (n.has("step_tolerance")) s.newton.step_tolerance = n["step_tolerance"].number();
    if (n.has("divergence_tolerance")) s.newton.divergence_tolerance = n["divergence_tolerance"].number();
    if (n.has("max_iterations")) s.newton.max_iterations = n["max_iterations"].integer();
    if (n.has("line_search")) s.newton.line_search = n["line_search"].boolean();
  }
  if (f.has("linear_solver"))
    s.linear_solver = f["linear_solver"].enumeration<LinearSolverKind>();
  if (f.has("petsc")) {
    s.petsc = f["petsc"].text();
    s.petsc_written = true;
  }
  if (f.has("linear_tolerance")) s.linear_tolerance = f["linear_tolerance"].number();
  if (f.has("mass")) s.mass = f["mass"].enumeration<MassKind>();
  if (f.has("tangent")) s.tangent = f["tangent"].enumeration<TangentKind>();
}

Probe read_probe(const YamlField& f, int dim) {
  Probe p;
  p.where = f.location();
  f.allow_only({"name", "point", "select", "contact", "field"});
  if (!f.has("name")) f.fail("missing 'name'");
  p.name = f["name"].text();
  if (!f.has("field")) f.fail("missing 'field': displacement | reaction | indentation | contact_force | energy");
  p.field = f["field"].enumeration<ProbeField>();
  if (f.has("point")) p.point = f["point"].vector(dim);
  if (f.has("select")) p.select = read_selection(f["select"], dim);
  if (f.has("contact")) p.contact = f["contact"].integer();
  return p;
}

void read_output(const YamlField& f, const Scene& scene, OutputOptions& o) {
  o.dir = "results/" + scene.name;
  if (f.is_null()) return;
  f.allow_only({"dir", "vtk", "probes"});
  if (f.has("dir")) o.dir = f["dir"].text();
  if (f.has("vtk")) {
    YamlField v = f["vtk"];
    if (v.node().IsScalar()) {
      if (!v.boolean()) o.vtk_every = 0;  // true keeps the default
    } else {
      v.allow_only({"every"});
      // 0 is how the struct says "none"; the file says it with vtk: false.
      if (v.has("every")) o.vtk_every = v["every"].integer();
      if (o.vtk_every < 1) v["every"].out_of_range("every >= 1 (steps); vtk: false for none");
    }
  }
  if (f.has("probes")) {
    YamlField list = f["probes"];
    if (!list.is_sequence()) list.fail("expected a list of probes, found " + list.value_text());
    for (std::size_t i = 0; i < list.size(); ++i) o.probes.push_back(read_probe(list[i], scene.dimension));
  }
}

Scene build_scene(YAML::Node root, const std::string& file, const std::string& directory,
                  const std::vector<std::string>& overrides) {
  Scene scene;
  scene.file = file;
  const YamlContext context{file, apply_overrides(root, overrides), &scene.sources};
  YamlField top(root, "", &context);
  if (!root.IsMap()) throw Error(file + ": expected a YAML map of scene keys at the top level");
  top.allow_only({"name", "dimension", "domain", "material", "discretization", "boundary", "body_force",
                  "contact", "cuts", "solve", "output"});
  if (top.has("name")) scene.name = top["name"].text();
  if (top.has("dimension")) scene.dimension = top["dimension"].integer();
  // Every vector is read with this many components: checked before the
  // rest is read (validate() checks it again, for scenes built in code).
  if (scene.dimension != 2 && scene.dimension != 3) top["dimension"].out_of_range("2 or 3");
  const int dim = scene.dimension;

  YamlField domain = top["domain"];
  if (domain.is_null()) top.fail("missing 'domain': expected box: {min, max} or mesh: FILE.msh");
  domain.allow_only({"box", "mesh"});
  if (domain.exactly_one_of({"box", "mesh"}) == "box") {
    scene.box = read_box(domain["box"], dim);
  } else {
    fs::path mesh = domain["mesh"].text();
    if (mesh.is_relative()) mesh = fs::path(directory) / mesh;
    scene.mesh_file = mesh.lexically_normal().string();
  }

  if (top.has("material")) read_material(top["material"], scene.material);
  read_discretization(top["discretization"], dim, scene.discretization);

  if (top.has("boundary")) {
    YamlField list = top["boundary"];
    if (!list.is_sequence()) list.fail("expected a list of boundary items, found " + list.value_text());
    for (std::size_t i = 0; i < list.size(); ++i) scene.boundary.push_back(read_boundary_item(list[i], dim));
  }
  if (top.has("body_force")) {
    YamlField b = top["body_force"];
    b.allow_only({"gravity"});
    if (b.has("gravity")) scene.gravity = b["gravity"].vector(dim);
  }
  if (top.has("contact")) {
    YamlField list = top["contact"];
    if (!list.is_sequence()) list.fail("expected a list of indenters, found " + list.value_text());
    for (std::size_t i = 0; i < list.size(); ++i) scene.contact.push_back(read_contact(list[i], dim));
  }
  if (top.has("cuts")) {
    YamlField list = top["cuts"];
    if (!list.is_sequence()) list.fail("expected a list of cuts, found " + list.value_text());
    for (std::size_t i = 0; i < list.size(); ++i) scene.cuts.push_back(read_cut(list[i], dim));
  }
  read_solve(top["solve"], scene.discretization.method, scene.solve);
  read_output(top["output"], scene, scene.output);
  validate(scene);
  return scene;
}

}  // namespace

Scene parse_scene(const std::string& yaml_text, const std::string& file, const std::string& directory,
                  const std::vector<std::string>& overrides) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::DeepRecursion& e) {
    throw Error(file + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1) +
                ": not valid YAML: lists or maps nested " + std::to_string(e.depth()) +
                " deep (the YAML reader's limit); expected a scene's few levels");
  } catch (const YAML::ParserException& e) {
    throw Error(file + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1) +
                ": not valid YAML: " + e.msg);
  }
  if (!root) root = YAML::Node(YAML::NodeType::Map);
  return build_scene(root, file, directory, overrides);
}

std::string read_scene_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  KERF_CHECK(in, path, ": cannot open the scene file");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

Scene read_scene(const std::string& path, const std::vector<std::string>& overrides) {
  fs::path directory = fs::path(path).parent_path();
  return parse_scene(read_scene_text(path), path, directory.empty() ? "." : directory.string(), overrides);
}

}  // namespace kerf

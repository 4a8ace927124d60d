#include "problem/scene_json.h"

namespace kerf {
namespace {

using json = nlohmann::ordered_json;

json vec(const Vec3& v, int dim) {
  json a = json::array();
  for (int i = 0; i < dim; ++i) a.push_back(v[i]);
  return a;
}

json box_json(const Box& b, int dim) { return {{"min", vec(b.min, dim)}, {"max", vec(b.max, dim)}}; }

json selection_json(const Selection& s, int dim) {
  switch (s.kind) {
    case Selection::Kind::plane:
      return {{"plane", {{"axis", std::string(1, "xyz"[s.axis])}, {"at", s.at}}}};
    case Selection::Kind::box:
      return {{"box", box_json(s.box, dim)}};
    case Selection::Kind::point:
      return {{"point", vec(s.point, dim)}};
  }
  return {};
}

json boundary_json(const BoundaryCondition& bc, int dim) {
  json j = {{"select", selection_json(bc.select, dim)}};
  json fixed = json::array();
  for (int i = 0; i < dim; ++i)
    if (bc.fixed[i]) fixed.push_back(std::string(1, "xyz"[i]));
  if (!fixed.empty()) j["fix"] = fixed;
  bool any_displacement = false;
  json displacement = json::array();
  for (int i = 0; i < dim; ++i) {
    any_displacement |= bc.displacement[i].has_value();
    displacement.push_back(bc.displacement[i] ? json(*bc.displacement[i]) : json(nullptr));
  }
  if (any_displacement) j["displacement"] = displacement;
  if (bc.traction) j["traction"] = vec(*bc.traction, dim);
  if (bc.pressure) j["pressure"] = *bc.pressure;
  return j;
}

json cut_json(const Cut& c, int dim) {
  json vertices = json::array();
  for (const Vec3& v : c.vertices) vertices.push_back(vec(v, dim));
  json j = {{c.is_strip ? "strip" : "polyline", vertices},
            {"times", c.times},
            {"enrichment", to_string(c.enrichment)},
            {"grid", {{"spacing", c.grid_spacing}, {"lookup", to_string(c.grid_lookup)}}},
            {"fem", to_string(c.fem)},
            {"live", c.live}};
  return j;
}

json probe_json(const Probe& p, int dim) {
  json j = {{"name", p.name}, {"field", to_string(p.field)}};
  if (p.point) j["point"] = vec(*p.point, dim);
  if (p.select) j["select"] = selection_json(*p.select, dim);
  if (p.contact) j["contact"] = *p.contact;
  return j;
}

}  // namespace

json scene_to_json(const Scene& s) {
  const int dim = s.dimension;
  json j;
  j["name"] = s.name;
  j["dimension"] = dim;
  if (s.box)
    j["domain"] = {{"box", box_json(*s.box, dim)}};
  else
    j["domain"] = {{"mesh", s.mesh_file}};
  const Material& m = s.material;
  j["material"] = {{"model", m.model == MaterialModel::user ? m.user_model : to_string(m.model)},
                   {"young", m.young},
                   {"poisson", m.poisson},
                   {"density", m.density},
                   {"damping", {{"mass", m.damping_mass}, {"stiffness", m.damping_stiffness}}}};
  if (!m.parameters.empty()) j["material"]["parameters"] = m.parameters;
  const DiscretizationOptions& d = s.discretization;
  const MeshlessOptions& ml = d.meshless;
  json refine = json::array();
  for (const RefineRegion& r : d.refine) refine.push_back({{"box", box_json(r.box, dim)}, {"size", r.size}});
  j["discretization"] = {
      {"method", to_string(d.method)},
      {"fem", {{"element", to_string(d.fem.element)}, {"size", d.fem.size}, {"volumetric", to_string(d.fem.volumetric)},
               {"split_front", to_string(d.fem.split_front)},
               {"split_snap", d.fem.split_snap}, {"box_mesher", to_string(d.fem.box_mesher)}}},
      {"refine", refine},
      {"meshless",
       {{"nodes", to_string(ml.nodes)},
        {"spacing", ml.spacing},
        {"support", ml.support},
        {"basis", to_string(ml.basis)},
        {"weight", to_string(ml.weight)},
        {"quadrature", ml.quadrature_rule == CellRule::gauss
                           ? json{{"rule", "gauss"}, {"order", ml.quadrature_order}}
                           : json{{"rule", "symmetric"}, {"degree", ml.quadrature_degree}}},
        {"essential", to_string(essential_method(ml, d.method))},
        {"stabilization", to_string(ml.stabilization)},
        {"gradient", to_string(ml.gradient)},
        {"vci", to_string(ml.vci)},
        {"cut_cells", to_string(cut_cells_of(s))},
        {"background_cells", to_string(background_cells_of(s))}}}};
  // Only where it acts: a resolved scene must read back (it is refused elsewhere).
  if (essential_method(ml, d.method) == EssentialMethod::nitsche)
    j["discretization"]["meshless"]["nitsche_safety"] = nitsche_safety(ml);
  json boundary = json::array();
  for (const auto& bc : s.boundary) boundary.push_back(boundary_json(bc, dim));
  j["boundary"] = boundary;
  j["body_force"] = {{"gravity", vec(s.gravity, dim)}};
  json contact = json::array();
  for (const auto& c : s.contact) {
    json item = {{"sphere", {{"center", vec(c.center, dim)}, {"radius", c.radius}}}};
    if (c.force) item["force"] = vec(*c.force, dim);
    if (c.displacement) item["displacement"] = vec(*c.displacement, dim);
    contact.push_back(item);
  }
  j["contact"] = contact;
  json cuts = json::array();
  for (const auto& c : s.cuts) cuts.push_back(cut_json(c, dim));
  j["cuts"] = cuts;
  const SolveOptions& so = s.solve;
  j["solve"] = {{"analysis", to_string(so.analysis)},
                {"integrator", to_string(so.integrator)},
                {"dt", so.dt},
                {"duration", so.duration},
                {"allow_unstable_dt", so.allow_unstable_dt},
                {"load_steps", so.load_steps},
                {"adapt", so.adapt},
                {"max_cutbacks", so.max_cutbacks},
                {"newton",
                 {{"tolerance", so.newton.tolerance},
                  {"step_tolerance", so.newton.step_tolerance},
                  {"divergence_tolerance", so.newton.divergence_tolerance},
                  {"max_iterations", so.newton.max_iterations},
                  {"line_search", so.newton.line_search}}},
                {"linear_solver", to_string(so.linear_solver)},
                {"linear_tolerance", so.linear_tolerance},
                {"mass", to_string(so.mass)},
                {"tangent", to_string(so.tangent)}};
  if (so.newton.absolute_tolerance) j["solve"]["newton"]["absolute_tolerance"] = *so.newton.absolute_tolerance;
  // Left out, solve.petsc means "kerf's choice for the ranks it runs on"
  // (petsc_rank_options): written out, it would mean these options on every
  // rank, so a scene read back would run another solver under mpirun.
  if (so.petsc_written) j["solve"]["petsc"] = so.petsc;
  json probes = json::array();
  for (const auto& p : s.output.probes) probes.push_back(probe_json(p, dim));
  j["output"] = {{"dir", s.output.dir},
                 {"vtk", s.output.vtk_every > 0 ? json{{"every", s.output.vtk_every}} : json(false)},
                 {"probes", probes}};
  return j;
}

}  // namespace kerf

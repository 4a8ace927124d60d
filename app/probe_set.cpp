#include "app/probe_set.h"

#include <algorithm>

#include "core/check.h"
#include "discretization/body_capabilities.h"

namespace kerf {

ProbeSet::ProbeSet(const Scene& scene, const MechanicalSystem& mechanics)
    : mechanics_(mechanics), weak_(capability<WeakConstraints>(mechanics.body())), dim_(mechanics.dofs_per_node()) {
  const DiscreteBody& body = mechanics.body();
  for (const Probe& p : scene.output.probes) {
    Resolved r{p, {}, {}};
    switch (p.field) {
      case ProbeField::displacement: {
        auto interpolation = body.interpolation_at(*p.point);
        KERF_CHECK(interpolation, p.where.describe(), ": probe '", p.name, "' point [", p.point->transpose(),
                   "] lies outside the body; expected a point inside or on it");
        r.interpolation = *interpolation;
        break;
      }
      case ProbeField::reaction:
        r.nodes = body.select_nodes(*p.select);
        break;
      case ProbeField::indentation:
      case ProbeField::contact_force:
        KERF_CHECK(mechanics.contact() && *p.contact < mechanics.contact()->sphere_count(), p.where.describe(),
                   ": probe '", p.name, "': contact ", *p.contact, " is not in the scene");
        break;
      case ProbeField::energy:
        break;
    }
    probes_.push_back(std::move(r));
  }
  displacement_dofs_ = displacement_dofs();
}

std::vector<std::string> ProbeSet::columns() const {
  std::vector<std::string> out;
  const char* axes = "xyz";
  for (const Resolved& r : probes_) {
    const std::string& n = r.probe.name;
    switch (r.probe.field) {
      case ProbeField::displacement:
        for (int i = 0; i < dim_; ++i) out.push_back(n + "_u" + axes[i]);
        break;
      case ProbeField::reaction:
        for (int i = 0; i < dim_; ++i) out.push_back(n + "_r" + axes[i]);
        break;
      case ProbeField::indentation:
        out.push_back(n + "_indentation");
        break;
      case ProbeField::contact_force:
        for (int i = 0; i < dim_; ++i) out.push_back(n + "_f" + axes[i]);
        break;
      case ProbeField::energy:
        for (const char* e : {"_kinetic", "_strain", "_external_work", "_total"}) out.push_back(n + e);
        break;
    }
  }
  return out;
}

bool ProbeSet::needs_reaction() const {
  for (const Resolved& r : probes_)
    if (r.probe.field == ProbeField::reaction) return true;
  return false;
}

bool ProbeSet::needs_energy() const {
  for (const Resolved& r : probes_)
    if (r.probe.field == ProbeField::energy) return true;
  return false;
}

std::optional<std::vector<Index>> ProbeSet::displacement_dofs() const {
  std::vector<Index> dofs;
  for (const Resolved& r : probes_) {
    if (r.probe.field != ProbeField::displacement) return std::nullopt;
    for (Index n : r.interpolation.nodes)
      for (int i = 0; i < dim_; ++i) dofs.push_back(dim_ * n + i);
  }
  std::sort(dofs.begin(), dofs.end());
  dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
  return dofs;
}

std::vector<double> ProbeSet::probe_values(const Resolved& r, const SolverState& state, const Vector& reaction,
                                           const EnergyState& energy) const {
  std::vector<double> v;
  switch (r.probe.field) {
    case ProbeField::displacement: {
      const Vec3 x = interpolate(r.interpolation, state.u, dim_);
      v.assign(x.data(), x.data() + dim_);
      break;
    }
    case ProbeField::reaction:
      v.assign(dim_, 0.0);
    {
      for (Index n : r.nodes)
        for (int i = 0; i < dim_; ++i) v[i] += reaction[dim_ * n + i];
      if (weak_) {
        Vector buffer;
        const Vec3 weak = weak_->weak_reaction(mechanics_.body_part(state.u, buffer), *r.probe.select);
        for (int i = 0; i < dim_; ++i) v[i] += weak[i];
      }
      break;
    }
    case ProbeField::indentation:
      v = {mechanics_.contact()->reading(*r.probe.contact, state.u).indentation};
      break;
    case ProbeField::contact_force: {
      const Vec3 force = mechanics_.contact()->reading(*r.probe.contact, state.u).force;
      v.assign(force.data(), force.data() + dim_);
      break;
    }
    case ProbeField::energy:
      v = {energy.kinetic, energy.strain, energy.external_work, energy.total()};
      break;
  }
  return v;
}

std::vector<double> ProbeSet::values(const SolverState& state, const Vector& reaction,
                                     const EnergyState& energy) const {
  std::vector<double> out;
  for (const Resolved& r : probes_) {
    auto v = probe_values(r, state, reaction, energy);
    out.insert(out.end(), v.begin(), v.end());
  }
  return out;
}

nlohmann::ordered_json ProbeSet::final_values(const SolverState& state, const Vector& reaction,
                                      const EnergyState& energy) const {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (const Resolved& r : probes_) {
    auto v = probe_values(r, state, reaction, energy);
    switch (r.probe.field) {
      case ProbeField::displacement:
        out[r.probe.name] = {{"displacement", v}};
        break;
      case ProbeField::reaction:
        out[r.probe.name] = {{"reaction", v}};
        break;
      case ProbeField::indentation:
        out[r.probe.name] = {{"indentation", v[0]}};
        break;
      case ProbeField::contact_force:
        out[r.probe.name] = {{"contact_force", v}};
        break;
      case ProbeField::energy:
        out[r.probe.name] = {{"kinetic", v[0]}, {"strain", v[1]}, {"external_work", v[2]}, {"total", v[3]}};
        break;
    }
  }
  return out;
}

}  // namespace kerf

/// \file Post-read checks of the whole Model (moved from the solver, which used to run them in
/// the CLI after read_deck).

#include "io/deck/model_checks.hpp"

namespace xpl::io {

namespace {

/// One refusal per plastic material on a deformable element of `type` (elements of rigid
/// bodies do not deform, so their material's plasticity never acts).
void refuse_plasticity_on(const Model& model, ElementType type, std::vector<std::string>& out) {
  std::vector<bool> rigid(static_cast<std::size_t>(model.element_count()), false);
  for (const RigidBody& r : model.rigid_bodies)
    if (r.element_set != NO_INDEX)
      for (Index e : model.element_sets[r.element_set].members) rigid[e] = true;
  std::vector<bool> refused(model.materials.size(), false);
  for (Index e = 0; e < model.element_count(); ++e) {
    if (model.element_types[e] != type || rigid[e]) continue;
    const Index section = model.element_section[e];
    if (section == NO_INDEX) continue;
    const Index m = is_shell(type) ? model.shell_sections[section].material
                                   : model.solid_sections[section].material;
    const Material& material = model.materials[m];
    if (!material.plastic || refused[m]) continue;
    refused[m] = true;
    const SourceLocation& where = material.plastic_where;
    out.push_back(where.file + ":" + std::to_string(where.line) + ": *PLASTIC: plasticity (" +
                  "*PLASTIC) on " + element_type_name(type) + " elements (material " +
                  material.name + ") is not implemented yet; expected an elastic material " +
                  "on " + element_type_name(type) + " elements with this version of xpl");
  }
}

}  // namespace

// Issue 14: each element family's line below goes when its return mapping lands.
void refuse_plastic_hexes(const Model& model, std::vector<std::string>& out) {
  refuse_plasticity_on(model, ElementType::C3D8R, out);
}
void refuse_plastic_shells(const Model& model, std::vector<std::string>& out) {
  refuse_plasticity_on(model, ElementType::S4R, out);
}

std::vector<std::string> unimplemented_kernels(const Model& model) {
  std::vector<std::string> out;
  refuse_plastic_hexes(model, out);   // C3D8R: no return mapping yet
  refuse_plastic_shells(model, out);  // S4R: no plane-stress return yet
  return out;
}

std::vector<std::string> unsupported_features(const Model& model) {
  std::vector<std::string> out;
  auto refuse = [&](const SourceLocation& where, const std::string& keyword,
                    const std::string& what) {
    out.push_back(where.file + ":" + std::to_string(where.line) + ": " + keyword + ": " + what +
                  " is read but not run by this version of xpl yet; expected a model without it");
  };
  // Node-based surfaces carry no faces or areas; the engine takes element-based ones.
  auto node_surface = [&](Index k) {
    return k != NO_INDEX && model.surfaces[k].type == Surface::Type::Node;
  };
  auto check_pair = [&](Index a, Index b, const SourceLocation& where, const std::string& kw) {
    if (node_surface(a) || node_surface(b))
      refuse(where, kw, "contact with a node-based surface (TYPE=NODE)");
  };
  std::vector<bool> is_reference(static_cast<std::size_t>(model.node_count()), false);
  for (const RigidBody& r : model.rigid_bodies)
    if (r.reference_node != NO_INDEX) is_reference[r.reference_node] = true;
  // A node shared by two rigid bodies would weld them into one: an input error.
  std::vector<Index> body_of(model.rigid_bodies.empty() ? 0 : model.node_count(), NO_INDEX);
  for (std::size_t b = 0; b < model.rigid_bodies.size(); ++b) {
    const RigidBody& r = model.rigid_bodies[b];
    if (r.element_set == NO_INDEX) continue;
    for (Index e : model.element_sets[r.element_set].members) {
      const Index* en = model.nodes_of(e);
      for (Index k = 0; k < model.element_offsets[e + 1] - model.element_offsets[e]; ++k) {
        Index& owner = body_of[en[k]];
        if (owner != NO_INDEX && owner != static_cast<Index>(b))
          out.push_back(r.where.file + ":" + std::to_string(r.where.line) + ": *RIGID BODY: node " +
                        std::to_string(model.node_ids[en[k]]) +
                        " also belongs to an earlier rigid body; expected each node in one "
                        "rigid body at most");
        owner = static_cast<Index>(b);
      }
    }
  }
  for (const PointInertia& p : model.point_inertias) {
    const bool rotary = p.inertia[0] != 0.0 || p.inertia[1] != 0.0 || p.inertia[2] != 0.0 ||
                        p.inertia[3] != 0.0 || p.inertia[4] != 0.0 || p.inertia[5] != 0.0;
    if (rotary && !is_reference[p.node])
      refuse(p.where, "*ROTARY INERTIA", "rotary inertia on a node that is no rigid body REF NODE");
  }
  for (const ContactPair& c : model.contact_pairs)
    check_pair(c.slave, c.master, c.where, "*CONTACT PAIR");
  for (const Step& s : model.steps) {
    if (s.contact) {
      for (const SurfacePair& p : s.contact->inclusions)
        check_pair(p.first, p.second, p.where, "*CONTACT INCLUSIONS");
    }
    for (const ContactPair& c : s.contact_pairs)
      check_pair(c.slave, c.master, c.where, "*CONTACT PAIR");
  }
  return out;
}

}  // namespace xpl::io

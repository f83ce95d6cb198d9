/// \file Post-read checks of the whole Model (moved from the solver, which used to run them in
/// the CLI after read_deck).

#include "io/deck/model_checks.hpp"

namespace xpl::io {

std::vector<std::string> unimplemented_kernels(const Model& /*model*/) {
  // Every element kernel runs every material of this version (C3D8R and S4R have their
  // plastic return mappings, issue 14): nothing to refuse. The hook stays for the next
  // material model that lands one element family at a time.
  return {};
}

std::vector<std::string> unsupported_features(const Model& model) {
  std::vector<std::string> out;
  auto refuse = [&](const SourceLocation& where, const std::string& keyword,
                    const std::string& what) {
    out.push_back(where.file + ":" + std::to_string(where.line) + ": " + keyword + ": " + what +
                  " is read but not run by this version of xpl yet; expected a model without it");
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
  return out;
}

}  // namespace xpl::io

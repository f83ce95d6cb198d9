/// \file *TIE, NAME=, POSITION TOLERANCE=, ADJUST=YES|NO (SPEC S6): read as model data, the
/// surfaces resolved and the nodes checked once the whole deck is read. Which slave nodes lie
/// within the tolerance is geometry: the solver finds them (solver/motion/ties.hpp).

#include <algorithm>
#include <cmath>
#include <map>
#include <span>
#include <utility>

#include "io/deck/deck_handlers.hpp"
#include "io/deck/deck_numbers.hpp"

namespace xpl::io {

void read_tie(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"NAME"}, {"POSITION TOLERANCE"}, {"ADJUST"}, {"TYPE"}});
  const std::optional<std::string> name = required_name(deck, keyword, "NAME");
  Tie tie;
  tie.where = keyword.where;
  bool ok = name.has_value();
  if (name) tie.name = *name;
  if (const DeckParameter* p = find_parameter(keyword, "POSITION TOLERANCE");
      p != nullptr && p->has_value) {
    const std::optional<Real> value = parse_real(p->value);
    if (!value || !(*value >= 0.0) || !std::isfinite(*value)) {
      error(deck, keyword.where, keyword, "bad POSITION TOLERANCE=" + p->value,
            "expected a distance >= 0, e.g. POSITION TOLERANCE=0.001");
      ok = false;
    } else {
      tie.tolerance = *value;
    }
  }
  const std::string adjust = optional_name(keyword, "ADJUST");
  if (adjust == "NO") {
    tie.adjust = false;
  } else if (!adjust.empty() && adjust != "YES") {
    error(deck, keyword.where, keyword, "bad ADJUST=" + adjust,
          "expected ADJUST=YES (default) or ADJUST=NO");
    ok = false;
  }
  const std::string type = optional_name(keyword, "TYPE");
  if (!type.empty() && type != "SURFACE TO SURFACE" && type != "NODE TO SURFACE") {
    error(deck, keyword.where, keyword, "bad TYPE=" + type,
          "expected TYPE=SURFACE TO SURFACE or NODE TO SURFACE (xpl ties node to surface)");
    ok = false;
  }
  if (name)
    for (const Tie& other : deck.model.ties)
      if (other.name == tie.name) {
        error(deck, keyword.where, keyword,
              "tie " + tie.name + " is already defined at " + location_text(other.where),
              "expected each *TIE NAME= once");
        ok = false;
      }
  if (block.data.size() != 1) {
    error(deck, keyword.where, keyword,
          "found " + std::to_string(block.data.size()) + " data lines",
          "expected one data line: slave surface, master surface");
    return;
  }
  const DeckDataLine& line = block.data.front();
  if (!check_field_count(deck, line, keyword, 2, "slave surface, master surface")) ok = false;
  if (!check_surface_pair(deck, line, keyword)) return;
  if (!ok) return;
  deck.model.ties.push_back(tie);
  deck.ties.push_back(
      {normalize_name(line.fields[0]), normalize_name(line.fields[1]), line.where()});
}

namespace {

const std::string TIE_KEYWORD = "*TIE";

/// One error per tie and cause: the first node, and how many more.
struct Conflict {
  std::vector<Index> nodes;
  std::string other;  ///< what the first node conflicts with
};

/// The slave and master surfaces of every tie; per tie, whether both are usable.
std::vector<char> resolve_tie_surfaces(DeckState& deck) {
  Model& model = deck.model;
  const std::string& keyword = TIE_KEYWORD;
  std::vector<char> valid(model.ties.size(), 1);
  for (std::size_t t = 0; t < model.ties.size(); ++t) {
    Tie& tie = model.ties[t];
    const PendingTie& pending = deck.ties[t];
    tie.slave = contact_surface(deck, pending.slave, pending.where, keyword);
    tie.master = contact_surface(deck, pending.master, pending.where, keyword);
    if (tie.slave == NO_INDEX || tie.master == NO_INDEX) {
      valid[t] = 0;
      continue;
    }
    if (model.surfaces[tie.master].type == Surface::Type::Node) {
      deck.errors.add(pending.where, keyword, "master surface " + pending.master + " is node-based",
                      "expected an element-based surface (*SURFACE, TYPE=ELEMENT) as the master");
      valid[t] = 0;
    }
    if (tie.slave == tie.master) {
      deck.errors.add(pending.where, keyword,
                      "surface " + pending.slave + " is both slave and master",
                      "expected two different surfaces: slave surface, master surface");
      valid[t] = 0;
    }
  }
  return valid;
}

/// Per node: `constrained` 1 with a translational BC in any step, 2 in a rigid body;
/// `rotation_bc` 1 with a BC on DOF 4-6 (a shell node's rotations).
struct NodeConstraints {
  std::vector<char> constrained;
  std::vector<char> rotation_bc;
};

NodeConstraints node_constraints(const Model& model) {
  const auto n = static_cast<std::size_t>(model.node_count());
  std::vector<char> constrained(n, 0), rotation_bc(n, 0);
  for (const Step& step : model.steps)
    for (const BoundaryCondition& bc : step.boundaries) {
      if (bc.node < 0 || bc.node >= model.node_count()) continue;
      if (bc.first_dof <= 3) constrained[bc.node] = 1;
      if (bc.last_dof >= 4) rotation_bc[bc.node] = 1;
    }
  for (const RigidBody& body : model.rigid_bodies) {
    std::vector<Index> members;
    if (body.element_set != NO_INDEX)
      for (Index e : model.element_sets[body.element_set].members) {
        const Index* en = model.nodes_of(e);
        members.insert(members.end(), en,
                       en + (model.element_offsets[e + 1] - model.element_offsets[e]));
      }
    for (Index set : {body.pin_node_set, body.tie_node_set})
      if (set != NO_INDEX)
        members.insert(members.end(), model.node_sets[set].members.begin(),
                       model.node_sets[set].members.end());
    if (body.reference_node != NO_INDEX) members.push_back(body.reference_node);
    for (Index i : members)
      if (i >= 0 && i < model.node_count()) constrained[i] = 2;
  }
  return {std::move(constrained), std::move(rotation_bc)};
}

/// The conflicts of the slave nodes of tie t, keyed by cause (ordered: a fixed message order);
/// marks its slaves in `slave_of`.
std::map<std::string, Conflict> tie_conflicts(const Model& model, std::size_t t,
                                              std::span<const Index> master_of,
                                              const NodeConstraints& nodes,
                                              std::vector<Index>& slave_of) {
  const Tie& tie = model.ties[t];
  const std::vector<char>& constrained = nodes.constrained;
  const std::vector<char>& rotation_bc = nodes.rotation_bc;
  std::map<std::string, Conflict> conflicts;
  // A shell master ties the rotations of shell slaves too (ties.hpp): a rotational BC on
  // such a slave would be overwritten by the tie.
  bool shell_master = false;
  for (const ElementFace& f : model.surfaces[tie.master].faces)
    if (f.element >= 0 && f.element < model.element_count() &&
        is_shell(model.element_types[f.element]))
      shell_master = true;
  for (Index i : model.surface_nodes(model.surfaces[tie.slave])) {
    if (master_of[i] == static_cast<Index>(t)) continue;  // on its own master: untied
    if (slave_of[i] != NO_INDEX) {
      Conflict& c = conflicts["1 slave"];
      if (c.nodes.empty()) c.other = model.ties[slave_of[i]].name;
      c.nodes.push_back(i);
      continue;
    }
    slave_of[i] = static_cast<Index>(t);
    if (master_of[i] != NO_INDEX) {
      Conflict& c = conflicts["2 master"];
      if (c.nodes.empty()) c.other = model.ties[master_of[i]].name;
      c.nodes.push_back(i);
    }
    if (constrained[i] == 1) conflicts["3 boundary"].nodes.push_back(i);
    if (constrained[i] == 2) conflicts["4 rigid"].nodes.push_back(i);
    if (shell_master && rotation_bc[i] && constrained[i] != 1)
      conflicts["5 rotation"].nodes.push_back(i);
  }
  return conflicts;
}

/// One error per cause of tie `tie`.
void report_conflicts(DeckState& deck, const Tie& tie,
                      const std::map<std::string, Conflict>& conflicts) {
  const Model& model = deck.model;
  const std::string& keyword = TIE_KEYWORD;
  for (const auto& [cause, c] : conflicts) {
    const std::string node =
        "node " + std::to_string(model.node_ids[c.nodes.front()]) +
        (c.nodes.size() > 1 ? " (and " + std::to_string(c.nodes.size() - 1) + " more)"
                            : std::string());
    const std::string which = "slave " + node + " of tie " + tie.name;
    if (cause[0] == '1')
      deck.errors.add(tie.where, keyword, which + " is also a slave of tie " + c.other,
                      "expected each node a slave of one tie at most");
    else if (cause[0] == '2')
      deck.errors.add(tie.where, keyword, which + " is also a master node of tie " + c.other,
                      "expected a slave node on no other tie's master surface (tie the parts "
                      "in a chain master to master, or merge the ties)");
    else if (cause[0] == '3')
      deck.errors.add(tie.where, keyword,
                      which + " has a boundary condition on a translational DOF",
                      "expected a tied slave node to follow its master; put the boundary "
                      "condition on the master surface's nodes");
    else if (cause[0] == '4')
      deck.errors.add(tie.where, keyword, which + " belongs to a rigid body",
                      "expected a deformable slave node (make the rigid part the master)");
    else
      deck.errors.add(tie.where, keyword,
                      which +
                          " has a boundary condition on a rotational DOF, and the shell "
                          "master surface " +
                          model.surfaces[tie.master].name + " ties its rotations",
                      "expected a tied slave node to follow its master; put the boundary "
                      "condition on the master surface's nodes");
  }
}

}  // namespace

void resolve_ties(DeckState& deck) {
  Model& model = deck.model;
  if (model.ties.empty()) return;
  const std::vector<char> valid = resolve_tie_surfaces(deck);

  // Node conflicts (checked on every node of the slave surface, within the tolerance or not):
  // a slave of two ties, a slave that is a master node of another tie, a slave with a
  // boundary condition on a translation, a slave in a rigid body. A slave node that is also a
  // master node of its own tie is not a conflict: it stays untied (ties.hpp).
  const auto n = static_cast<std::size_t>(model.node_count());
  std::vector<Index> slave_of(n, NO_INDEX), master_of(n, NO_INDEX);
  for (std::size_t t = 0; t < model.ties.size(); ++t) {
    if (!valid[t]) continue;
    for (Index i : model.surface_nodes(model.surfaces[model.ties[t].master]))
      if (master_of[i] == NO_INDEX) master_of[i] = static_cast<Index>(t);
  }
  const NodeConstraints constraints = node_constraints(model);
  for (std::size_t t = 0; t < model.ties.size(); ++t)
    if (valid[t])
      report_conflicts(deck, model.ties[t],
                       tie_conflicts(model, t, master_of, constraints, slave_of));
}

}  // namespace xpl::io

#include "solver/motion/ties.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "contact/closest_point.hpp"

namespace xpl {

namespace {

/// Corners of one master face, in face order (hex faces S1..S6; both sides of a shell are its
/// mid-surface).
struct MasterFace {
  std::array<Index, 4> corner{};
  bool shell = false;
  Eigen::Vector3d low, high;  ///< bounding box of the corners, m
  Real diagonal = 0.0;        ///< mean of the two diagonals, m: the size of its element
};

/// Slave nodes searched for the nearest distance of a tie that binds none (the search is
/// pruned only by that distance, so it is capped: a sample of this many, evenly spaced).
constexpr std::size_t NEAREST_SAMPLE = 1000;

/// Number of untied slave node ids listed in the .msg file.
constexpr std::size_t LISTED_IDS = 10;

/// What binding the slave nodes of one tie found.
struct TieOutcome {
  Index tied = 0;
  Real largest = 0.0;  ///< the largest distance of a tied slave node to its master point, m
  std::vector<Index> untied;
  // Slave nodes ADJUST=YES moves by more than the size of the face they bind to.
  Index far_moves = 0;
  Real far_move = 0.0, far_diagonal = 0.0;
  Index far_node = NO_INDEX;
};

Eigen::Vector3d point(const NodalVectors& x, Index i) {
  return {x(i, 0), x(i, 1), x(i, 2)};
}

std::string number(Real value) {
  std::ostringstream text;
  text.precision(4);
  text << value;
  return text.str();
}

/// Per node: 1 for a node of a shell element (its rotations can be tied).
std::vector<char> shell_nodes(const Model& model) {
  std::vector<char> shell_node(static_cast<std::size_t>(model.node_count()), 0);
  for (Index e = 0; e < model.element_count(); ++e)
    if (is_shell(model.element_types[e])) {
      const Index* en = model.nodes_of(e);
      for (int k = 0; k < 4; ++k) shell_node[en[k]] = 1;
    }
  return shell_node;
}

/// The master faces of `tie` on the reference positions, the sum of their diagonals added to
/// `diagonal_sum`; their corners marked in `on_master`.
std::vector<MasterFace> master_faces(const Model& model, const Tie& tie,
                                     const NodalVectors& reference, std::vector<char>& on_master,
                                     Real& diagonal_sum) {
  std::vector<MasterFace> faces;
  for (const ElementFace& f : model.surfaces[tie.master].faces) {
    MasterFace face;
    const Index* en = model.nodes_of(f.element);
    face.shell = is_shell(model.element_types[f.element]);
    for (int k = 0; k < 4; ++k) face.corner[k] = face.shell ? en[k] : en[HEX_FACE_NODES[f.face][k]];
    face.low = face.high = point(reference, face.corner[0]);
    for (Index c : face.corner) {
      face.low = face.low.cwiseMin(point(reference, c));
      face.high = face.high.cwiseMax(point(reference, c));
      on_master[c] = 1;
    }
    face.diagonal =
        0.5 * ((point(reference, face.corner[2]) - point(reference, face.corner[0])).norm() +
               (point(reference, face.corner[3]) - point(reference, face.corner[1])).norm());
    diagonal_sum += face.diagonal;
    faces.push_back(face);
  }
  return faces;
}

/// The closest point of node s on the master faces no farther than `limit`; best = +inf when
/// there is none.
void nearest(const std::vector<MasterFace>& faces, const NodalVectors& reference, Index s,
             Real limit, Real& best, contact::ClosestPoint& closest, std::size_t& best_face) {
  const Eigen::Vector3d p = point(reference, s);
  best = std::numeric_limits<Real>::infinity();
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const MasterFace& face = faces[k];
    // Distance to the bounding box: a lower bound of the distance to the face.
    const Eigen::Vector3d outside =
        (face.low - p).cwiseMax(p - face.high).cwiseMax(Eigen::Vector3d::Zero());
    if (outside.norm() > std::min(best, limit)) continue;
    contact::Vec3 corner[4];
    for (int c = 0; c < 4; ++c) corner[c] = point(reference, face.corner[c]);
    const contact::ClosestPoint cp = contact::closest_point_on_quad(corner, p);
    if (cp.distance < best) {
      best = cp.distance;
      closest = cp;
      best_face = k;
    }
  }
}

/// The .msg line of one tie: how many slave nodes it binds, how far they were, which stay free.
std::string tie_message(const Model& model, const Tie& tie, Real tolerance,
                        const TieOutcome& outcome) {
  std::string text = "tie " + tie.name + ": " + std::to_string(outcome.tied) +
                     " slave node(s) tied to surface " + model.surfaces[tie.master].name +
                     " (position tolerance " + number(tolerance) + " m" +
                     (tie.tolerance ? "" : ", the default 5 % of the mean master face diagonal") +
                     "); largest distance to the master " + number(outcome.largest) + " m" +
                     (tie.adjust ? ", removed by ADJUST=YES (strain free)" : ", kept (ADJUST=NO)");
  if (outcome.untied.empty()) {
    text += "; no slave node outside the tolerance";
  } else {
    text += "; " + std::to_string(outcome.untied.size()) +
            " slave node(s) farther than the tolerance stay free:";
    for (std::size_t k = 0; k < std::min(outcome.untied.size(), LISTED_IDS); ++k)
      text += (k == 0 ? " " : ", ") + std::to_string(model.node_ids[outcome.untied[k]]);
    if (outcome.untied.size() > LISTED_IDS) text += ", ...";
  }
  return text;
}

/// The warning of a tie that binds no node, with the nearest slave node anyway (a sample of a
/// large surface): the tolerance it needs.
std::string no_tie_warning(const Model& model, const Tie& tie, Real tolerance,
                           const std::vector<Index>& untied, const std::vector<MasterFace>& faces,
                           const NodalVectors& reference) {
  Real closest_distance = std::numeric_limits<Real>::infinity();
  const std::size_t stride = std::max<std::size_t>(1, untied.size() / NEAREST_SAMPLE);
  for (std::size_t k = 0; k < untied.size(); k += stride) {
    Real best = 0.0;
    contact::ClosestPoint closest;
    std::size_t best_face = 0;
    nearest(faces, reference, untied[k], closest_distance, best, closest, best_face);
    closest_distance = std::min(closest_distance, best);
  }
  std::string warning = "tie " + tie.name + " ties no node: ";
  if (untied.empty())
    warning += "every node of slave surface " + model.surfaces[tie.slave].name +
               " is a node of master surface " + model.surfaces[tie.master].name;
  else
    warning += "none of the " + std::to_string(untied.size()) + " slave node(s) of " +
               model.surfaces[tie.slave].name + " lies within the position tolerance " +
               number(tolerance) + " m of " + model.surfaces[tie.master].name + " (the nearest " +
               (stride > 1 ? "of a sample " : "") + "is " + number(closest_distance) + " m away)";
  return warning + "; the tie has no effect";
}

/// The warning of ADJUST=YES moving slave nodes farther than their master face is large.
std::string far_move_warning(const Model& model, const Tie& tie, Real tolerance,
                             const TieOutcome& outcome) {
  return "tie " + tie.name + ": ADJUST=YES moves " + std::to_string(outcome.far_moves) +
         " slave node(s) by more than the size of the master face they are tied to (node " +
         std::to_string(model.node_ids[outcome.far_node]) + " by " + number(outcome.far_move) +
         " m, its face's diagonal " + number(outcome.far_diagonal) + " m; position tolerance " +
         number(tolerance) + " m): check POSITION TOLERANCE=, or tie with ADJUST=NO";
}

}  // namespace

Ties::Ties(const Model& model, State& state) {
  if (model.ties.empty()) return;
  const Index n = model.node_count();
  const std::vector<char> shell_node = shell_nodes(model);
  m_tied.assign(static_cast<std::size_t>(n), 0);
  for (const Tie& tie : model.ties) bind(model, tie, shell_node, state);
  index_masters(n);
}

void Ties::bind(const Model& model, const Tie& tie, const std::vector<char>& shell_node,
                State& state) {
  // The master faces and the default tolerance (5 % of their mean diagonal).
  Real diagonal_sum = 0.0;
  std::vector<char> on_master(static_cast<std::size_t>(model.node_count()), 0);
  const std::vector<MasterFace> faces =
      master_faces(model, tie, state.reference, on_master, diagonal_sum);
  const Real tolerance = tie.tolerance ? *tie.tolerance
                                       : (faces.empty() ? 0.0
                                                        : TIE_DEFAULT_TOLERANCE * diagonal_sum /
                                                              static_cast<Real>(faces.size()));
  TieOutcome outcome;
  const std::vector<Index> slaves = model.surface_nodes(model.surfaces[tie.slave]);
  for (Index s : slaves) {
    if (on_master[s]) continue;  // a node of its own master surface stays untied
    Real best = 0.0;
    contact::ClosestPoint closest;
    std::size_t best_face = 0;
    nearest(faces, state.reference, s, tolerance, best, closest, best_face);
    if (!(best <= tolerance)) {
      outcome.untied.push_back(s);
      continue;
    }
    const MasterFace& face = faces[best_face];
    if (tie.adjust && best > face.diagonal) {
      ++outcome.far_moves;
      if (best > outcome.far_move) {
        outcome.far_move = best;
        outcome.far_diagonal = face.diagonal;
        outcome.far_node = s;
      }
    }
    Binding b;
    b.slave = s;
    b.corner = face.corner;
    b.weight = closest.weights;
    b.rotations = face.shell && shell_node[s] != 0;
    m_bindings.push_back(b);
    m_tied[s] = 1;
    for (Index c : face.corner) m_tied[c] = 1;
    ++outcome.tied;
    outcome.largest = std::max(outcome.largest, best);
    // Strain free, as the overclosure adjustment: the position moves, U shows the move, the
    // element formulations are incremental (an imported run puts its own positions over it).
    if (tie.adjust)
      for (int c = 0; c < 3; ++c) state.position(s, c) = closest.point[c];
  }
  m_messages.push_back(tie_message(model, tie, tolerance, outcome));
  if (outcome.tied == 0)
    m_warnings.push_back(
        no_tie_warning(model, tie, tolerance, outcome.untied, faces, state.reference));
  if (outcome.far_moves > 0) m_warnings.push_back(far_move_warning(model, tie, tolerance, outcome));
}

void Ties::index_masters(Index n) {
  // Per master node, its entries in binding order.
  std::vector<Index> count(static_cast<std::size_t>(n), 0);
  for (const Binding& b : m_bindings)
    for (Index c : b.corner) ++count[c];
  m_entry_offsets.push_back(0);
  std::vector<Index> slot(static_cast<std::size_t>(n), NO_INDEX);
  for (Index i = 0; i < n; ++i)
    if (count[i] > 0) {
      slot[i] = static_cast<Index>(m_master.size());
      m_master.push_back(i);
      m_entry_offsets.push_back(m_entry_offsets.back() + count[i]);
    }
  m_entries.resize(static_cast<std::size_t>(m_entry_offsets.back()));
  std::vector<Index> fill(m_entry_offsets.begin(), m_entry_offsets.end() - 1);
  for (std::size_t b = 0; b < m_bindings.size(); ++b)
    for (int k = 0; k < 4; ++k) {
      const Index c = m_bindings[b].corner[k];
      m_entries[fill[slot[c]]++] = {static_cast<Index>(b), k};
    }
}

std::vector<Index> Ties::changed_nodes() const {
  std::vector<Index> nodes = m_master;
  for (const Binding& b : m_bindings) nodes.push_back(b.slave);
  std::sort(nodes.begin(), nodes.end());
  return nodes;
}

void Ties::distribute_mass(State& state) const {
  const bool rotations = !state.rotary_inertia.empty();
  for (const Binding& b : m_bindings) {
    for (int k = 0; k < 4; ++k) state.mass[b.corner[k]] += b.weight[k] * state.mass[b.slave];
    state.mass[b.slave] = 0.0;
    if (rotations && b.rotations) {
      for (int k = 0; k < 4; ++k)
        state.rotary_inertia[b.corner[k]] += b.weight[k] * state.rotary_inertia[b.slave];
      state.rotary_inertia[b.slave] = 0.0;
    }
  }
  follow(state);
}

void Ties::set_local(const std::vector<unsigned char>& gathers,
                     const std::vector<unsigned char>& follows) {
  m_local = true;
  m_local_masters.clear();
  m_local_bindings.clear();
  for (std::size_t m = 0; m < m_master.size(); ++m)
    if (gathers[m_master[m]] != 0) m_local_masters.push_back(m);
  for (std::size_t b = 0; b < m_bindings.size(); ++b)
    if (follows[m_bindings[b].slave] != 0) m_local_bindings.push_back(b);
}

void Ties::gather(NodalVectors& force_internal, const NodalVectors* force_external,
                  NodalVectors* moment_internal) const {
  // Each master node's sum is its own (the slaves' forces are read, never written): visiting
  // some of them leaves the others' bits as they are.
  if (m_local) {
    for (const std::size_t m : m_local_masters)
      gather_master(m, force_internal, force_external, moment_internal);
    return;
  }
  for (std::size_t m = 0; m < m_master.size(); ++m)
    gather_master(m, force_internal, force_external, moment_internal);
}

void Ties::gather_master(std::size_t m, NodalVectors& force_internal,
                         const NodalVectors* force_external, NodalVectors* moment_internal) const {
  const Index i = m_master[m];
  for (Index e = m_entry_offsets[m]; e < m_entry_offsets[m + 1]; ++e) {
    const Binding& b = m_bindings[m_entries[e].first];
    const Real w = b.weight[m_entries[e].second];
    for (int c = 0; c < 3; ++c) {
      Real f = force_internal(b.slave, c);
      if (force_external != nullptr) f -= (*force_external)(b.slave, c);
      force_internal(i, c) += w * f;
    }
    if (moment_internal != nullptr && b.rotations)
      for (int c = 0; c < 3; ++c) (*moment_internal)(i, c) += w * (*moment_internal)(b.slave, c);
  }
}

void Ties::follow(State& state) const {
  const bool rotations = state.angular_velocity_half.rows() > 0;
  if (m_local) {
    for (const std::size_t b : m_local_bindings) follow_binding(m_bindings[b], state, rotations);
    return;
  }
  for (const Binding& b : m_bindings) follow_binding(b, state, rotations);
}

void Ties::follow_binding(const Binding& b, State& state, bool rotations) const {
  for (int c = 0; c < 3; ++c) {
    Real v_half = 0.0, v = 0.0, a = 0.0;
    for (int k = 0; k < 4; ++k) {
      v_half += b.weight[k] * state.velocity_half(b.corner[k], c);
      v += b.weight[k] * state.velocity(b.corner[k], c);
      a += b.weight[k] * state.acceleration(b.corner[k], c);
    }
    state.velocity_half(b.slave, c) = v_half;
    state.velocity(b.slave, c) = v;
    state.acceleration(b.slave, c) = a;
  }
  if (!rotations || !b.rotations) return;
  for (int c = 0; c < 3; ++c) {
    Real w_half = 0.0, w = 0.0;
    for (int k = 0; k < 4; ++k) {
      w_half += b.weight[k] * state.angular_velocity_half(b.corner[k], c);
      w += b.weight[k] * state.angular_velocity(b.corner[k], c);
    }
    state.angular_velocity_half(b.slave, c) = w_half;
    state.angular_velocity(b.slave, c) = w;
  }
}

}  // namespace xpl

#include "solver/motion/rigid_bodies.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "common/error.hpp"

namespace xpl {

namespace {

using Vector6 = Eigen::Matrix<Real, 6, 1>;
using Matrix6 = Eigen::Matrix<Real, 6, 6>;

Eigen::Vector3d row(const NodalVectors& v, Index i) {
  return {v(i, 0), v(i, 1), v(i, 2)};
}

Eigen::Matrix3d skew(const Eigen::Vector3d& r) {
  Eigen::Matrix3d s;
  s << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return s;
}

/// Inertia of a point mass m at offset r: m (|r|² I − r rᵀ).
Eigen::Matrix3d point_inertia(Real m, const Eigen::Vector3d& r) {
  return m * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
}

/// Free rows of M a = rhs: M_FF a_F = b_F − M_FP a_P, solved with the prescribed rows
/// (`fixed`) made trivial; returns every row's acceleration for the prescribed ones `acc_p`.
Vector6 solve_free_rows(const Matrix6& mass_matrix, const Vector6& rhs,
                        const std::array<bool, 6>& fixed, const Vector6& acc_p) {
  Matrix6 system = mass_matrix;
  Vector6 b = rhs - mass_matrix * acc_p;
  for (int k = 0; k < 6; ++k)
    if (fixed[k]) {
      system.row(k).setZero();
      system.col(k).setZero();
      system(k, k) = 1.0;
      b[k] = 0.0;
    }
  const Vector6 free_acc = system.ldlt().solve(b);
  Vector6 all = acc_p;
  for (int k = 0; k < 6; ++k)
    if (!fixed[k]) all[k] = free_acc[k];
  return all;
}

/// The exact rotation by the rotation vector θ as a unit quaternion.
Eigen::Quaterniond rotation_quaternion(const Eigen::Vector3d& theta) {
  const Real angle = theta.norm();
  if (angle < 1e-300) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, theta / angle));
}

}  // namespace

RigidBodies::RigidBodies(const Model& model) {
  if (model.rigid_bodies.empty()) return;
  m_element_body.assign(static_cast<std::size_t>(model.element_count()), NO_INDEX);
  m_node_body.assign(static_cast<std::size_t>(model.node_count()), NO_INDEX);
  for (std::size_t b = 0; b < model.rigid_bodies.size(); ++b) {
    const RigidBody& def = model.rigid_bodies[b];
    const auto id = static_cast<Index>(b);
    Body body;
    body.reference = def.reference_node;
    std::vector<Index> nodes;
    if (def.element_set != NO_INDEX)
      for (Index e : model.element_sets[def.element_set].members) {
        m_element_body[e] = id;
        const Index* en = model.nodes_of(e);
        nodes.insert(nodes.end(), en,
                     en + (model.element_offsets[e + 1] - model.element_offsets[e]));
      }
    for (Index set : {def.pin_node_set, def.tie_node_set})
      if (set != NO_INDEX)
        nodes.insert(nodes.end(), model.node_sets[set].members.begin(),
                     model.node_sets[set].members.end());
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    for (Index i : nodes) {
      if (i == body.reference) continue;
      if (m_node_body[i] != NO_INDEX && m_node_body[i] != id)
        throw SolverError(def.where.file + ":" + std::to_string(def.where.line) +
                              ": *RIGID BODY: node " + std::to_string(model.node_ids[i]) +
                              " also belongs to an earlier rigid body; expected each node in one "
                              "body at most",
                          0, 0, 0.0);
      m_node_body[i] = id;
      body.members.push_back(i);
    }
    m_node_body[body.reference] = id;
    m_bodies.push_back(std::move(body));
  }
}

std::vector<std::string> RigidBodies::setup(const Model& model, const std::vector<Real>& mass,
                                            State& state) {
  std::vector<std::string> messages;
  for (std::size_t b = 0; b < m_bodies.size(); ++b) {
    Body& body = m_bodies[b];
    const Eigen::Vector3d x_ref = row(state.reference, body.reference);
    Real m = mass[body.reference];
    Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
    for (Index i : body.members) {
      m += mass[i];
      first_moment += mass[i] * (row(state.reference, i) - x_ref);
    }
    body.mass = m;
    body.centre_offset = m > 0.0 ? Eigen::Vector3d(first_moment / m) : Eigen::Vector3d::Zero();
    Eigen::Matrix3d j = point_inertia(mass[body.reference], -body.centre_offset);
    for (Index i : body.members)
      j += point_inertia(mass[i], row(state.reference, i) - x_ref - body.centre_offset);
    for (const PointInertia& p : model.point_inertias) {
      if (p.node != body.reference) continue;
      Eigen::Matrix3d given;
      given << p.inertia[0], p.inertia[3], p.inertia[4], p.inertia[3], p.inertia[1], p.inertia[5],
          p.inertia[4], p.inertia[5], p.inertia[2];
      j += given;
    }
    // A body whose masses lie on a line has no inertia about it; a trace-relative floor keeps
    // the 6×6 system regular without changing any other motion measurably.
    j += 1e-9 * std::max(j.trace(), 0.0) * Eigen::Matrix3d::Identity();
    body.inertia = j;

    // Members start with the reference node's velocity.
    for (Index i : body.members)
      for (int c = 0; c < 3; ++c) {
        state.velocity(i, c) = state.velocity(body.reference, c);
        state.velocity_half(i, c) = state.velocity(body.reference, c);
      }
    std::ostringstream text;
    text.precision(6);
    text << "rigid body " << b + 1 << " (reference node " << model.node_ids[body.reference]
         << "): " << body.members.size() << " member nodes, mass " << m << " kg, centre of mass "
         << (x_ref + body.centre_offset).transpose() << ", principal inertias "
         << Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(j).eigenvalues().transpose() << " kg·m²";
    messages.push_back(text.str());
  }
  return messages;
}

std::vector<std::array<Real, 3>> RigidBodies::translation_mass() const {
  std::vector<std::array<Real, 3>> out(m_bodies.size());
  for (std::size_t b = 0; b < m_bodies.size(); ++b) {
    out[b].fill(m_bodies[b].mass);
    for (const PrescribedDof& d : m_bodies[b].prescribed)
      if (d.component < 3) out[b][d.component] = std::numeric_limits<Real>::infinity();
  }
  return out;
}

Index RigidBodies::begin_step(std::vector<PrescribedDof>& prescribed) {
  for (Body& body : m_bodies) body.prescribed.clear();
  Index dropped = 0;
  std::vector<PrescribedDof> kept;
  kept.reserve(prescribed.size());
  for (const PrescribedDof& d : prescribed) {
    const Index b = m_node_body.empty() ? NO_INDEX : m_node_body[d.node];
    if (b == NO_INDEX) {
      kept.push_back(d);
    } else if (m_bodies[b].reference == d.node) {
      m_bodies[b].prescribed.push_back(d);
    } else {
      ++dropped;
    }
  }
  prescribed.swap(kept);
  for (Body& body : m_bodies) body.previous_reaction.fill(0.0);
  return dropped;
}

/// One body's Newton–Euler system at t_n about its reference node (rigid_bodies.hpp).
struct RigidBodies::BodySystem {
  Eigen::Vector3d x_r;    ///< position of the reference node, m
  Eigen::Vector3d v_old;  ///< v(n−½) of the reference node, m/s
  Eigen::Vector3d w_old;  ///< ω(n−½), rad/s
  Matrix6 mass_matrix;
  Vector6 rhs;
  Real counted = 0.0;  ///< Σ m v² of the body's nodes: a quarter of what the free update summed
};

RigidUpdate RigidBodies::update(const PrescribedMotion& motion, State& state,
                                const NodalVectors& force_internal,
                                const NodalVectors* force_external, const NodalIncrement& inc) {
  RigidUpdate result;
  for (Body& body : m_bodies)
    fold(body, update_body(body, motion, state, force_internal, force_external, inc), inc, result);
  return result;
}

void RigidBodies::fold(const Body& body, const BodyTerms& t, const NodalIncrement& inc,
                       RigidUpdate& result) {
  for (std::size_t j = 0; j < body.prescribed.size(); ++j)
    result.work +=
        0.5 * (t.reaction_before[j] + t.reaction_now[j]) * inc.dt_prev * t.velocity_old[j];
  RigidJumps& jumps = result.jumps;
  if (t.jumped > 0) {
    result.work += t.kinetic - t.before;
    jumps.pending += t.after - t.kinetic;
    jumps.energy += t.after - t.before;
    jumps.dofs += t.jumped;
    jumps.largest = std::max(jumps.largest, t.largest);
  }
  result.kinetic.centred += t.centred - 4.0 * t.counted;
  result.kinetic.spread += t.spread;
  if (t.jumped > 0) jumps.spread += t.spread;
}

RigidBodies::BodySystem RigidBodies::system_at(Body& body, const State& state,
                                               const NodalVectors& force_internal,
                                               const NodalVectors* force_external, Real dt_prev) {
  BodySystem s;
  const Index r = body.reference;
  s.x_r = row(state.position, r);
  // Forces on the body and their moment about the reference node; the kinetic sums the free
  // update counted for these nodes (v⁻ = v⁺ = v_{n-1/2}, their inverse mass being 0).
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
  Real counted = 0.0;  // Σ m v², a quarter of their centred sum
  auto gather = [&](Index i) {
    Eigen::Vector3d f = -row(force_internal, i);
    if (force_external != nullptr) f += row(*force_external, i);
    force += f;
    moment += (row(state.position, i) - s.x_r).cross(f);
    counted += state.mass[i] * row(state.velocity, i).squaredNorm();
  };
  gather(r);
  for (Index i : body.members) gather(i);
  s.counted = counted;

  const Eigen::Matrix3d rot = body.orientation.toRotationMatrix();
  const Eigen::Vector3d c = rot * body.centre_offset;
  const Eigen::Matrix3d j_ref = rot * body.inertia * rot.transpose() + point_inertia(body.mass, c);
  s.v_old = row(state.velocity_half, r);
  s.w_old = body.omega_half;
  body.rotation += dt_prev * s.w_old;  // rotation vector at t_n
  // Fixed-size blocks, not the comma initialiser: its run-time-sized blocks make GCC 12 warn
  // (-Warray-bounds) about AVX loads Eigen never executes for a 3-vector.
  s.mass_matrix.topLeftCorner<3, 3>() = body.mass * Eigen::Matrix3d::Identity();
  s.mass_matrix.topRightCorner<3, 3>() = -body.mass * skew(c);
  s.mass_matrix.bottomLeftCorner<3, 3>() = body.mass * skew(c);
  s.mass_matrix.bottomRightCorner<3, 3>() = j_ref;
  s.rhs.head<3>() = force - body.mass * s.w_old.cross(s.w_old.cross(c));
  s.rhs.tail<3>() = moment - s.w_old.cross(j_ref * s.w_old);
  return s;
}

RigidBodies::BodyTerms RigidBodies::update_body(Body& body, const PrescribedMotion& motion,
                                                State& state, const NodalVectors& force_internal,
                                                const NodalVectors* force_external,
                                                const NodalIncrement& inc) {
  BodyTerms t;
  const Real dt_prev = inc.dt_prev, dt_avg = inc.dt_avg;
  const Real w_new = inc.w_new, w_before = inc.w_before;
  const Index r = body.reference;
  const BodySystem s = system_at(body, state, force_internal, force_external, dt_prev);
  const Matrix6& mass_matrix = s.mass_matrix;
  const Eigen::Vector3d &v_old = s.v_old, &w_old = s.w_old;

  // Prescribed DOFs: their new velocity, hence their acceleration.
  Vector6 acc = Vector6::Zero();
  std::array<bool, 6> fixed{};
  std::array<Real, 6> v_target{};
  for (const PrescribedDof& d : body.prescribed) {
    const int k = d.component;
    const Real old = k < 3 ? v_old[k] : w_old[k - 3];
    Real current = 0.0;
    if (d.type != BoundaryType::Velocity)
      current = k < 3 ? state.displacement(r, k) : body.rotation[k - 3];
    const Real v_new = motion.velocity_half(d, current, inc);
    fixed[k] = true;
    v_target[k] = v_new;
    acc[k] = dt_avg > 0.0 ? (v_new - old) / dt_avg : 0.0;
  }
  auto solve = [&](const Vector6& acc_p) {
    return solve_free_rows(mass_matrix, s.rhs, fixed, acc_p);
  };
  acc = solve(acc);
  const Vector6 reaction = mass_matrix * acc - s.rhs;
  // A jump of the prescribed motion: the reactions' smooth part (the body held at zero
  // prescribed acceleration) carries on in the trapezoidal rule; the impulse is booked apart.
  Index jumped = 0;
  Real largest_jump = 0.0;
  if (motion.first_update())
    for (const PrescribedDof& d : body.prescribed) {
      const int k = d.component;
      const Real old = k < 3 ? v_old[k] : w_old[k - 3];
      if (v_target[k] != old && motion.is_jump(d, inc, old, v_target[k])) {
        ++jumped;
        largest_jump = std::max(largest_jump, std::abs(v_target[k] - old));
      }
    }
  const Vector6 reaction_kept =
      jumped > 0 ? Vector6(mass_matrix * solve(Vector6::Zero()) - s.rhs) : reaction;

  Eigen::Vector3d v_new, w_new_half;
  for (int k = 0; k < 3; ++k) {
    v_new[k] = fixed[k] ? v_target[k] : v_old[k] + dt_avg * acc[k];
    w_new_half[k] = fixed[k + 3] ? v_target[k + 3] : w_old[k] + dt_avg * acc[k + 3];
  }
  for (std::size_t j = 0; j < body.prescribed.size(); ++j) {
    const int k = body.prescribed[j].component;
    t.reaction_before[j] = body.previous_reaction[k];
    t.reaction_now[j] = reaction_kept[k];
    t.velocity_old[j] = k < 3 ? v_old[k] : w_old[k - 3];
    body.previous_reaction[k] = reaction_kept[k];
    if (k < 3)
      state.reaction(r, k) = reaction[k];
    else if (state.reaction_moment.rows() > 0)
      state.reaction_moment(r, k - 3) = reaction[k];
  }

  // Whole-step velocities, the reference node; the kinetic energy ½ v_before·M·v_{n+1/2}
  // with the 6×6 matrix at t_n, as for the free DOFs (NodalIncrement).
  const Eigen::Vector3d v_whole = v_old + w_new * (v_new - v_old);
  const Eigen::Vector3d w_whole = w_old + w_new * (w_new_half - w_old);
  Vector6 v_after, v_before;
  v_after.head<3>() = v_new;
  v_after.tail<3>() = w_new_half;
  v_before.head<3>() = v_old + w_before * (v_new - v_old);
  v_before.tail<3>() = w_old + w_before * (w_new_half - w_old);
  Vector6 v_pair = v_after;  // what ALLKE pairs with v_before
  if (jumped > 0) {
    // The state before the jump paired with the one after it (at t = 0 the state before it
    // alone), as for a free DOF; the impulse's work is split at that energy (fold()).
    v_before.head<3>() = v_old;
    v_before.tail<3>() = w_old;
    if (!(dt_prev > 0.0)) v_pair = v_before;
    t.before = 0.5 * v_before.dot(mass_matrix * v_before);
    t.after = 0.5 * v_after.dot(mass_matrix * v_after);
    t.kinetic = 0.5 * v_before.dot(mass_matrix * v_pair);
    t.jumped = jumped;
    t.largest = largest_jump;
  }
  const Vector6 sum = v_before + v_pair, difference = v_pair - v_before;
  t.spread = difference.dot(mass_matrix * difference);
  t.centred = sum.dot(mass_matrix * sum);
  t.counted = s.counted;
  for (int k = 0; k < 3; ++k) {
    state.velocity_half(r, k) = v_new[k];
    state.velocity(r, k) = v_whole[k];
    state.acceleration(r, k) = acc[k];
  }
  if (state.angular_velocity_half.rows() > 0) {
    for (int k = 0; k < 3; ++k) {
      state.angular_velocity_half(r, k) = w_new_half[k];
      state.angular_velocity(r, k) = w_whole[k];
      state.rotation(r, k) = body.rotation[k];
    }
  }
  body.omega_half = w_new_half;
  place_members(body, state, s.x_r, v_new, v_whole, w_whole, inc);
  return t;
}

void RigidBodies::place_members(Body& body, State& state, const Eigen::Vector3d& x_r,
                                const Eigen::Vector3d& v_new, const Eigen::Vector3d& v_whole,
                                const Eigen::Vector3d& w_whole, const NodalIncrement& inc) {
  // Advance the orientation over dt_next and place every member exactly.
  const Real dt_next = inc.dt_next, dt_avg = inc.dt_avg;
  if (!(dt_next > 0.0)) return;
  const Eigen::Quaterniond q_next =
      (rotation_quaternion(dt_next * body.omega_half) * body.orientation).normalized();
  const Eigen::Matrix3d rot_next = q_next.toRotationMatrix();
  const Eigen::Vector3d x_r_next = x_r + dt_next * v_new;
  const Eigen::Vector3d x_ref0 = row(state.reference, body.reference);
  for (Index i : body.members) {
    // As the member's reference position plus the body's motion, so that a body at rest and
    // unrotated (a held die, a fixed plate) keeps its members exactly where they are.
    const Eigen::Vector3d arm0 = row(state.reference, i) - x_ref0;
    const Eigen::Vector3d target = row(state.reference, i) + (x_r_next - x_ref0) +
                                   (rot_next - Eigen::Matrix3d::Identity()) * arm0;
    const Eigen::Vector3d v_i = (target - row(state.position, i)) / dt_next;
    const Eigen::Vector3d arm = row(state.position, i) - x_r;
    const Eigen::Vector3d v_i_whole = v_whole + w_whole.cross(arm);
    for (int k = 0; k < 3; ++k) {
      state.acceleration(i, k) = dt_avg > 0.0 ? (v_i[k] - state.velocity_half(i, k)) / dt_avg : 0.0;
      state.velocity_half(i, k) = v_i[k];
      state.velocity(i, k) = v_i_whole[k];
    }
  }
  body.orientation = q_next;
}

}  // namespace xpl

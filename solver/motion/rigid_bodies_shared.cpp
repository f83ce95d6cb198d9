// The rigid bodies of a distributed run (rigid_bodies.hpp, docs/dev/mpi.md): each body is
// updated by its owner, whose rows carry the body's terms of the sums and its reference
// node's motion to every rank; the ranks that move the body's nodes place its members as the
// owner did.
#include <algorithm>

#include "common/error.hpp"
#include "solver/motion/rigid_bodies.hpp"

namespace xpl {

namespace {

/// Values a body's rows carry: its terms of the sums, then the reference node's motion.
constexpr int PAYLOAD = PrescribedMotion::FOLD_WIDTH - 1;
constexpr int MOTION = 24;

void put_row(std::vector<Real>& out, const NodalVectors& rows, Index i) {
  for (int c = 0; c < 3; ++c) out.push_back(rows.rows() > 0 ? rows(i, c) : 0.0);
}

void take_row(const Real*& in, NodalVectors& rows, Index i) {
  for (int c = 0; c < 3; ++c, ++in)
    if (rows.rows() > 0) rows(i, c) = *in;
}

}  // namespace

std::vector<Index> RigidBodies::body_nodes(Index b) const {
  std::vector<Index> nodes{m_bodies[b].reference};
  nodes.insert(nodes.end(), m_bodies[b].members.begin(), m_bodies[b].members.end());
  return nodes;
}

void RigidBodies::update_owned(const PrescribedMotion& motion, State& state,
                               const NodalVectors& force_internal,
                               const NodalVectors* force_external, const NodalIncrement& inc,
                               std::vector<Real>& rows) {
  static_assert(BODY_ROWS * PAYLOAD >= BodyTerms::WIDTH + MOTION);
  std::vector<Real> payload;
  for (std::size_t b = 0; b < m_bodies.size(); ++b) {
    if (m_roles[b] != 1) continue;
    Body& body = m_bodies[b];
    const BodyTerms t = update_body(body, motion, state, force_internal, force_external, inc);
    payload.assign({t.centred, t.counted, t.spread, static_cast<Real>(t.jumped), t.largest,
                    t.kinetic, t.before, t.after});
    for (const auto* a : {&t.reaction_before, &t.reaction_now, &t.velocity_old})
      payload.insert(payload.end(), a->begin(), a->end());
    // The reference node's motion as update_body() wrote it (the model has the rotation rows:
    // ExplicitSolver::Impl::set_up_rigid_bodies()).
    const Index r = body.reference;
    for (const NodalVectors* m : {&state.velocity_half, &state.velocity, &state.acceleration})
      put_row(payload, *m, r);
    payload.insert(payload.end(), body.omega_half.data(), body.omega_half.data() + 3);
    for (const NodalVectors* m :
         {&state.angular_velocity, &state.rotation, &state.reaction, &state.reaction_moment})
      put_row(payload, *m, r);
    payload.resize(static_cast<std::size_t>(BODY_ROWS * PAYLOAD), 0.0);
    for (int j = 0; j < BODY_ROWS; ++j) {
      rows.push_back(-1.0 - static_cast<Real>(static_cast<Index>(b) * BODY_ROWS + j));
      rows.insert(rows.end(), payload.begin() + j * PAYLOAD, payload.begin() + (j + 1) * PAYLOAD);
    }
  }
}

RigidUpdate RigidBodies::take_shared(std::vector<Real>& all, State& state,
                                     const NodalIncrement& inc) {
  // Each body's payload out of the rows (whatever rank sent them), the others kept in order.
  constexpr std::size_t WIDTH = PrescribedMotion::FOLD_WIDTH;
  std::vector<Real> payload(m_bodies.size() * BODY_ROWS * PAYLOAD);
  std::vector<unsigned char> arrived(m_bodies.size(), 0);
  std::size_t kept = 0;
  for (std::size_t at = 0; at + WIDTH <= all.size(); at += WIDTH) {
    if (all[at] >= 0.0) {
      std::copy(all.begin() + static_cast<std::ptrdiff_t>(at),
                all.begin() + static_cast<std::ptrdiff_t>(at + WIDTH),
                all.begin() + static_cast<std::ptrdiff_t>(kept));
      kept += WIDTH;
      continue;
    }
    const auto row = static_cast<std::size_t>(-1.0 - all[at]);
    arrived[row / BODY_ROWS] = 1;
    std::copy(all.begin() + static_cast<std::ptrdiff_t>(at + 1),
              all.begin() + static_cast<std::ptrdiff_t>(at + WIDTH),
              payload.begin() + static_cast<std::ptrdiff_t>(row * PAYLOAD));
  }
  all.resize(kept);

  RigidUpdate result;
  for (std::size_t b = 0; b < m_bodies.size(); ++b) {
    if (arrived[b] == 0)
      throw SolverError(
          "distributed run: no rank sent the update of rigid body " + std::to_string(b + 1), 0, 0,
          0.0);
    Body& body = m_bodies[b];
    const Real* in = payload.data() + b * BODY_ROWS * PAYLOAD;
    BodyTerms t;
    t.centred = in[0];
    t.counted = in[1];
    t.spread = in[2];
    t.jumped = static_cast<Index>(in[3]);
    t.largest = in[4];
    t.kinetic = in[5];
    t.before = in[6];
    t.after = in[7];
    in += 8;
    for (auto* a : {&t.reaction_before, &t.reaction_now, &t.velocity_old}) {
      std::copy(in, in + 6, a->begin());
      in += 6;
    }
    if (m_roles[b] == 2) {
      // The owner's motion of the reference node, then the members placed from it.
      const Index r = body.reference;
      const Eigen::Vector3d x_r(state.position(r, 0), state.position(r, 1), state.position(r, 2));
      take_row(in, state.velocity_half, r);
      take_row(in, state.velocity, r);
      take_row(in, state.acceleration, r);
      body.omega_half = Eigen::Vector3d(in[0], in[1], in[2]);
      in += 3;
      const Eigen::Vector3d w_whole(in[0], in[1], in[2]);
      take_row(in, state.angular_velocity, r);
      take_row(in, state.rotation, r);
      take_row(in, state.reaction, r);
      take_row(in, state.reaction_moment, r);
      if (state.angular_velocity_half.rows() > 0)
        for (int c = 0; c < 3; ++c) state.angular_velocity_half(r, c) = body.omega_half[c];
      const Eigen::Vector3d v_new(state.velocity_half(r, 0), state.velocity_half(r, 1),
                                  state.velocity_half(r, 2));
      const Eigen::Vector3d v_whole(state.velocity(r, 0), state.velocity(r, 1),
                                    state.velocity(r, 2));
      place_members(body, state, x_r, v_new, v_whole, w_whole, inc);
    }
    fold(body, t, inc, result);
  }
  return result;
}

}  // namespace xpl

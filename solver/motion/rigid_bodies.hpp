#pragma once
/// \file Rigid bodies (`*RIGID BODY, REF NODE=, ELSET=[, PIN NSET=][, TIE NSET=]`, S6).
///
/// A body's elements are taken out of the element loops; their lumped masses, the nodes' own
/// `*MASS` and the reference node's `*MASS`/`*ROTARY INERTIA` make the body's mass, centre of
/// mass and inertia. The body moves as six DOFs at its reference node: with r the vector from
/// the reference node to the centre of mass, J_ref the inertia about the reference node and ω
/// the angular velocity, Newton–Euler about the reference node reads
///
///   [ m I      −m [r]× ] [a]   [F − m ω × (ω × r)   ]
///   [ m [r]×   J_ref   ] [α] = [M_ref − ω × (J_ref ω)]
///
/// with F and M_ref the sum of the nodal forces on the body (loads, contact, gravity) and their
/// moment about the reference node. DOFs of the reference node with a boundary condition have
/// known accelerations; the other rows are solved for, and the prescribed rows give the
/// reactions (RF at the reference node, and RM in models that carry rotations). Velocities are
/// integrated by central differences like every other DOF; the orientation is a quaternion
/// advanced by the exact rotation of ω_{n+1/2} Δt, and every member node is placed exactly at
/// x_ref + R (X − X_ref) by giving it the half-step velocity that lands it there, so the
/// body never deforms. The members' inverse mass is 0 in the nodal update; the kinetic sums of
/// a body (kinetic_sums.hpp) are those of v⁻ and v_{n+1/2} with the 6×6 matrix above (ALLKE,
/// ALLKD, docs/theory/energy.md).
///
/// PIN and TIE nodes join the body with their translations; a TIE node's rotations (shells)
/// are not coupled yet and keep their own dynamics (said in the .msg file).

#include <array>
#include <vector>

#include <Eigen/Geometry>

#include "common/types.hpp"
#include "solver/loads/boundary_state.hpp"
#include "solver/model/model.hpp"
#include "solver/model/state.hpp"
#include "solver/motion/kinetic_sums.hpp"
#include "solver/motion/nodal_increment.hpp"
#include "solver/motion/prescribed_motion.hpp"

namespace xpl {

/// The jumps of prescribed motion the bodies met at one update.
struct RigidJumps {
  Index dofs = 0;      ///< prescribed DOFs whose velocity jumped
  Real energy = 0.0;   ///< ½ V_bᵀ M V_b − ½ V_aᵀ M V_a of the bodies that jumped, J
  Real largest = 0.0;  ///< largest |v_b − v_a| of a jumping DOF, m/s or rad/s
  Real pending = 0.0;  ///< the part of `energy` that falls in the next increment, J
  Real spread = 0.0;   ///< the kinetic spread (kinetic_sums.hpp) of the bodies that jumped
};

/// What one update of the bodies adds to the nodal update.
struct RigidUpdate {
  /// The correction of the kinetic sums: the bodies' minus what the free update counted for
  /// their nodes.
  KineticSums kinetic;
  Real work = 0.0;   ///< the work of the reactions at the reference nodes (and impulses), J
  RigidJumps jumps;  ///< the jumps of prescribed motion the bodies met
};

/// All rigid bodies of a model.
class RigidBodies {
 public:
  RigidBodies() = default;
  /// Assigns elements and nodes to bodies. A node in two bodies is an input error that
  /// io::unsupported_features() (io/deck/model_checks.hpp) reports before anything is written;
  /// here it throws SolverError.
  explicit RigidBodies(const Model& model);

  bool empty() const { return m_bodies.empty(); }
  /// Body of each element (n_elements), NO_INDEX for deformable ones; empty when no bodies.
  const std::vector<Index>& element_body() const { return m_element_body; }
  /// Whether node i moves with a body (member or reference node).
  bool is_rigid_node(Index i) const { return !m_node_body.empty() && m_node_body[i] != NO_INDEX; }
  /// Body of each node (n_nodes, NO_INDEX for deformable ones); empty when no bodies.
  const std::vector<Index>& node_body() const { return m_node_body; }
  /// Per body, its mass for each translation in the current step (kg, after setup()): +inf
  /// where begin_step() took a prescribed translation of its reference node.
  std::vector<std::array<Real, 3>> translation_mass() const;

  /// Mass, centre of mass and inertia of every body from the nodal masses `mass` (n_nodes, kg,
  /// rigid elements' lumped mass and `*MASS` included) and the reference nodes' rotary inertia;
  /// sets the member nodes' initial velocity to that of the reference node. Returns one
  /// message per body for the .msg file.
  std::vector<std::string> setup(const Model& model, const std::vector<Real>& mass, State& state);

  /// Takes the prescribed DOFs of reference nodes out of `prescribed` (they drive the bodies)
  /// and drops those on member nodes; returns how many member-node DOFs were dropped.
  Index begin_step(std::vector<PrescribedDof>& prescribed);

  /// One central-difference update of every body over `inc`, called after the free nodal
  /// update with the forces at t_n (internal n_nodes × 3, N; external may be null). The
  /// reference nodes' prescribed DOFs take their v(n+½) from `motion`
  /// (PrescribedMotion::velocity_half), as free DOFs do. Writes velocities (half and whole
  /// step), accelerations, reactions and the reference node rotation into `state`; returns
  /// the correction of the kinetic sums and the reactions' work. A body whose prescribed
  /// velocity jumps at the first update of a step (PrescribedMotion::is_jump) takes the jump
  /// as an impulse, as a free DOF does (PrescribedMotion::count_jump_work): its work
  /// ½ V_bᵀ M V_b − ½ V_aᵀ M V_a is split at the kinetic energy ½ V_aᵀ M V_b at t_n (at t = 0
  /// the state before the jump, ½ V_aᵀ M V_a), the part of the next increment in
  /// `jumps.pending`; the reactions keep their smooth part for the trapezoidal rule.
  RigidUpdate update(const PrescribedMotion& motion, State& state,
                     const NodalVectors& force_internal, const NodalVectors* force_external,
                     const NodalIncrement& inc);

  /// \name Distributed runs (docs/dev/mpi.md): each body is updated by one rank, its owner,
  /// from its nodes' forces (which the owner has received from the ranks integrating them);
  /// the owner's rows (BODY_ROWS rows of PrescribedMotion::FOLD_WIDTH values per body, marked
  /// by a negative first value) carry the body's terms of the sums and the motion of its
  /// reference node to every rank with the prescribed DOFs' rows. Every other rank that moves
  /// a node of the body replays it: places the members exactly as the owner did.
  /// Per body: 1 if this rank owns it, 2 if it replays its motion, 0 if it does neither.
  void set_roles(std::vector<unsigned char> roles) { m_roles = std::move(roles); }
  /// The nodes of body `b`, the reference node first, then the members (ascending).
  std::vector<Index> body_nodes(Index b) const;
  Index body_count() const { return static_cast<Index>(m_bodies.size()); }
  static constexpr int BODY_ROWS = 5;
  /// update() of the bodies this rank owns; appends their rows to `rows`.
  void update_owned(const PrescribedMotion& motion, State& state,
                    const NodalVectors& force_internal, const NodalVectors* force_external,
                    const NodalIncrement& inc, std::vector<Real>& rows);
  /// Takes the bodies' rows out of `all` (every rank's rows), moves the reference nodes and
  /// members of the bodies this rank replays, and returns what update() returns, folded in
  /// body order by the one-rank expressions.
  RigidUpdate take_shared(std::vector<Real>& all, State& state, const NodalIncrement& inc);

 private:
  struct Body {
    Index reference = NO_INDEX;
    std::vector<Index> members;  ///< nodes other than the reference node
    Real mass = 0.0;
    Eigen::Vector3d centre_offset = Eigen::Vector3d::Zero();  ///< X_c − X_ref, reference frame
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();        ///< J about the centre, ref. frame
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
    Eigen::Vector3d omega_half = Eigen::Vector3d::Zero();  ///< ω_{n+1/2}, rad/s
    Eigen::Vector3d rotation = Eigen::Vector3d::Zero();    ///< Σ ω Δt (exact about a fixed axis)
    std::vector<PrescribedDof> prescribed;                 ///< DOFs of the reference node
    std::array<Real, 6> previous_reaction{};               ///< for the trapezoidal work
  };
  struct BodySystem;
  /// What one body's update adds to the sums, kept as the operands of the one-rank
  /// expressions (fold()), so that a sum over the bodies folded elsewhere has the same bits.
  struct BodyTerms {
    Real centred = 0.0;  ///< V·M·V of the sum of the velocities before and after
    Real counted = 0.0;  ///< Σ m v² the free update counted for the body's nodes
    Real spread = 0.0;
    Index jumped = 0;  ///< prescribed DOFs whose velocity jumped
    Real largest = 0.0, kinetic = 0.0, before = 0.0, after = 0.0;  ///< of the jump
    /// Per prescribed DOF (in the body's order): the reactions before and now, v(n−½).
    std::array<Real, 6> reaction_before{}, reaction_now{}, velocity_old{};
    static constexpr int WIDTH = 8 + 18;
  };
  /// One central-difference update of `body` (update() for each body): writes the state,
  /// returns the body's terms of the sums.
  static BodyTerms update_body(Body& body, const PrescribedMotion& motion, State& state,
                               const NodalVectors& force_internal,
                               const NodalVectors* force_external, const NodalIncrement& inc);
  /// Adds the terms `t` of `body` to `result` as one rank's update adds them.
  static void fold(const Body& body, const BodyTerms& t, const NodalIncrement& inc,
                   RigidUpdate& result);
  /// The Newton–Euler system of `body` at t_n from the forces on its nodes (internal and
  /// external, n_nodes × 3, N); advances its rotation vector over dt_prev to t_n.
  static BodySystem system_at(Body& body, const State& state, const NodalVectors& force_internal,
                              const NodalVectors* force_external, Real dt_prev);
  /// Advances the orientation of `body` by ω(n+½) over dt_next and gives every member the
  /// half-step velocity that lands it exactly at x_ref + R (X − X_ref) (`x_r`, `v_new`: the
  /// reference node at t_n and its v(n+½); `v_whole`, `w_whole`: the body's whole-step
  /// velocities).
  static void place_members(Body& body, State& state, const Eigen::Vector3d& x_r,
                            const Eigen::Vector3d& v_new, const Eigen::Vector3d& v_whole,
                            const Eigen::Vector3d& w_whole, const NodalIncrement& inc);
  std::vector<Body> m_bodies;
  std::vector<unsigned char> m_roles;  ///< set_roles()
  std::vector<Index> m_element_body;
  std::vector<Index> m_node_body;
};

}  // namespace xpl

#pragma once
/// \file General contact, one increment at a time: search (broad phase when due, closest
/// face of every slave node), penalty and friction forces, assembly onto the nodes, energy.
///
/// The rules of the search (which faces a node may touch), the onset of a touch, contact at
/// speed, pinched nodes and several springs on one node: docs/theory/contact.md.
///
/// Force: f = w·k·max(0, d − d0) along the contact normal with w the view weight (½ for each
/// view of a balanced pair) and k the penalty stiffness: k = slope·A (tributary area A) for a
/// LINEAR pressure–overclosure slope, else the default k = ½·s·m_eff/Δt² (penalty.hpp), which
/// is tied to the current increment so that contact never lowers it. Coulomb friction by the
/// stick-spring return map of penalty.hpp with k_t = w·k. The slave node gets f, the face
/// nodes −N_I f (force_assembly.hpp).
///
/// Determinism: search and force loops are parallel over slave nodes and write only their own
/// slot; assembly and every sum run over slots in order, so results do not depend on the
/// number of threads.
///
/// Quiet slots: a slot whose last visit found no touch on either side, no release, pass-through
/// or behind depth, kept no warm start and has no ramp is quiet: its constraints are open, its
/// springs and forces zero, and every pass would write over it what it holds. An update visits
/// only the slots that may not be quiet (those with listed faces, whose search may find a touch,
/// and those whose last visit left one of the above), in slot order, so every sum and every
/// state is that of a visit of all slots, to the bit; the others cost nothing per increment.
/// Sleeping slots, far from every listed face, are not searched: slot_sleep.hpp (why it is sound).

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "common/timer.hpp"
#include "contact/broad_phase.hpp"
#include "contact/closest_point.hpp"
#include "contact/contact_domain.hpp"
#include "contact/contact_options.hpp"
#include "contact/face_bounds.hpp"
#include "contact/force_assembly.hpp"
#include "contact/penalty.hpp"
#include "contact/penalty_increment.hpp"
#include "contact/slot_sharing.hpp"
#include "contact/slot_sleep.hpp"

namespace xpl::contact {

/// A slave node's contact status for output (CSTATUS): open, slipping or sticking.
enum class OutputStatus : std::uint8_t { Open = 0, Slip = 1, Stick = 2 };

/// General contact of one step.
class ContactEngine {
 public:
  /// `laws` is indexed by the domain's interaction numbers; NO_INDEX means frictionless
  /// default penalty.
  ContactEngine(ContactDomain domain, std::vector<InteractionLaw> laws, ContactOptions options,
                const NodalVectors& position, std::span<const Real> node_thickness);

  /// One increment at the new positions x_{n+1} (n_nodes × 3, m), with the velocities of the
  /// increment just taken v_{n+1/2} (m/s) and its length dt (s; 0 at t = 0: no work, no
  /// slip), the increment the penalty stiffness is tied to (s; the stable increment about to
  /// be taken at t = 0), shell node thickness (n_nodes, m, or empty), nodal masses (kg) and
  /// inverse masses (1/kg, 0 for rigid body nodes).
  /// Subtracts the contact forces from `force_internal` (n_nodes × 3, N) and times the search
  /// and force phases into `timers`.
  ContactTotals update(const NodalVectors& position, const NodalVectors& velocity_half, Real dt,
                       Real dt_penalty, std::span<const Real> node_thickness,
                       std::span<const Real> mass, std::span<const Real> inverse_mass,
                       NodalVectors& force_internal, PhaseTimers& timers);

  /// Search only (no forces, no state change besides the broad phase and the node areas and
  /// normals): the nearest admissible face of every slave node at `position`, then in touch().
  /// The initial-overclosure pass uses it on the configuration it is adjusting. Returns
  /// whether the broad phase was rebuilt.
  bool probe(const NodalVectors& position, std::span<const Real> node_thickness);
  /// Every admissible face of slave slot s whose contact surface the node penetrates (gap
  /// below −tolerance, m), nearest first; for the pinched-node test. Uses the broad-phase
  /// lists of the last probe() or update().
  std::vector<SlaveTouch> penetrated_faces(Index s, const NodalVectors& position,
                                           std::span<const Real> node_thickness,
                                           Real tolerance) const;
  /// The result of the last search for slave slot s.
  const SlaveTouch& touch(Index s) const { return m_touch[s]; }

  const ContactDomain& domain() const { return m_domain; }
  const ContactOptions& options() const { return m_options; }
  const std::vector<ContactConstraint>& constraints() const { return m_constraints; }
  /// Mutable: a constraint set through it may not be quiet (build_visits()), so the next
  /// update() visits every slot.
  std::vector<ContactConstraint>& constraints() {
    m_visit_all = true;
    return m_constraints;
  }
  /// Normal force of the slave node's own constraint (weight included), N; per slave slot.
  Real normal_force(Index s) const { return m_normal_force[s]; }
  /// The touch on the other side of slave slot s (a pinched node; face NO_INDEX: none) and
  /// its normal force (weight included), N.
  const SlaveTouch& second_touch(Index s) const { return m_second_touch[s]; }
  Real second_normal_force(Index s) const { return m_second_normal_force[s]; }
  /// Total contact force on the node of slave slot s (as slave and as face corner), N.
  Vec3 nodal_force(Index s) const { return m_assembly.nodal_force(s); }
  OutputStatus output_status(Index s) const { return m_output_status[s]; }
  /// Per included pair: sum of normal force magnitudes (N) and of friction force magnitudes
  /// (N) over the slave nodes touching through that pair, at the last update.
  const std::vector<Real>& pair_normal_force() const { return m_assembly.pair_normal_force(); }
  const std::vector<Real>& pair_friction_force() const { return m_assembly.pair_friction_force(); }
  const BroadPhase& broad_phase() const { return m_broad; }
  /// The stiffest node of the user-stiffness springs (LINEAR laws) at the last update: those
  /// closed or closing within PENALTY_LOOKAHEAD_INCREMENTS (penalty_increment.hpp); empty
  /// (omega_sq 0) when none acts or every law is the default penalty.
  const PenaltyLimit& penalty_limit() const { return m_penalty_limit; }
  /// Before any contact (`xpl check`): the stiffest node the user-stiffness springs could
  /// make, every slave node taken as pressed by each LINEAR interaction that may apply to it
  /// with its tributary area, on a master of its own kind (row sum 2k/m); nodal masses as
  /// inverse masses (n_nodes, 1/kg).
  PenaltyLimit estimate_penalty_limit(std::span<const Real> inverse_mass) const;
  /// The rigid bodies the default springs may push (cap_default_springs): the body of each
  /// node (n_nodes, NO_INDEX for deformable nodes; empty: none) and, per body, its mass for
  /// each translation (kg; +inf where the current step prescribes that translation of its
  /// reference node). Set at the start of every step.
  void set_rigid_bodies(std::vector<Index> node_body,
                        std::vector<std::array<Real, 3>> body_translation_mass);
  /// Widens the search margin by `extra` (m, > 0) for contact surfaces moved out towards the
  /// slave nodes by negative permanent offsets (clearances); the next search rebuilds the lists.
  void widen_search(Real extra);
  /// Interference fit of slave slot s (SPEC C15): its offset is `base` + `amount`·r(t), r
  /// ramping linearly from 1 at step time 0 to 0 at step time `duration` (s, > 0), so the
  /// penalty pushes the surfaces apart with a force that grows from zero. The offset is
  /// permanent while it ramps (the C3 rule does not shrink it) and afterwards when `base` ≠ 0
  /// (what an interference distance left of a clearance violation); an offset of zero after the
  /// ramp leaves the plain penalty. Sets the offset for step time 0.
  void set_interference(Index s, Real amount, Real base, Real duration);
  /// The step time (s) of the next update(), for the interference ramp.
  void set_step_time(Real step_time) { m_step_time = step_time; }
  /// Whether some slave slot's interference is still ramping.
  bool interference_ramping() const { return m_ramping > 0; }
  /// Distributed runs (slot_sharing.hpp, docs/dev/mpi.md): from the next update() on, process
  /// `process` searches and computes the springs of its slots (`slot_process`, n_slave) only
  /// and takes the others' results from their owners through `sharing` (outliving the
  /// engine); a slot's state and its node's velocity (the work terms) are its owner's.
  void share_slots(std::vector<int> slot_process, int process, SlotSharing* sharing);
  /// Distributed runs, after an update() of shared slots (contact_reads.cpp): marks (n_nodes)
  /// the nodes this process's search and springs read until the next build. False when a
  /// whole pass reads more (a law of its own stiffness: every node area).
  bool mark_read_nodes(std::vector<char>& mark) const;
  /// Distributed runs: node velocities received with the slot forces since share_slots().
  double received_velocities() const { return m_received_velocities; }
  /// Distributed runs, for the next update() of shared slots only: whether the broad phase is
  /// to be built (the max over the processes of each one's largest motion of the nodes it
  /// integrates: exact, so the one-process decision) and the max of their
  /// step motions (m², the sleeping slots' path, slot_sleep.hpp); update() then measures
  /// neither on its copies.
  void decide_rebuild(bool due, Real step_motion_sq) {
    m_rebuild_decision = due ? 1 : 0;
    m_sleep.step_decision = step_motion_sq;
  }
  /// Distributed runs: the largest squared motion since the build of the contact nodes
  /// `node_mask` marks, and in `step_sq` their step motion (one walk, BroadPhase::motions_sq).
  Real measure_motions(const NodalVectors& position, std::span<const char> node_mask,
                       Real& step_sq);
  const SleepCounts& sleep_counts() const { return m_sleep.counts; }  ///< slot_sleep.hpp
  /// Distributed runs, when the processes decided to build (collective): builds the broad
  /// phase now on `position`, current only for the faces `faces_held` marks (n_faces: the
  /// ghost faces, every face whose box may hold a slot of this process) and this process's
  /// slots, and lists the slots' faces; the caller brings the rows the new lists read and
  /// decides no rebuild for the update(), which reports this build (ContactTotals::rebuilt).
  void build_shared_broad_phase(const NodalVectors& position, std::span<const Real> node_thickness,
                                std::span<const char> faces_held);

 private:
  /// Whether this process computes slot s in the current update() (share_slots()).
  bool owned(Index s) const { return !m_shared_pass || m_owned[s] != 0; }
  /// After a shared pass's broad-phase build (share_slots()): marks in m_active_slot the
  /// slots with candidates that the other processes found (one exchange, at rebuilds only).
  void share_active_slots();
  /// After prepare_springs() (share_slots()): every slot's touches, release and pass-through
  /// depths and counted default springs from its owner (contact_slot_rows.cpp).
  void share_springs();
  /// After spring_forces(): every slot's forces, energies, status and friction forces from
  /// its owner, all the assembly and the sums read, and into m_work_velocity the velocity
  /// (`velocity_half`, n_nodes × 3, current for this process's slots) of every slot whose
  /// node may carry a force now or carried one before (the work terms).
  void share_forces(const NodalVectors& velocity_half);
  /// Into m_force_slot (n_slave): the slots whose node may carry a contact force in this
  /// update() or carried one in the last (share_forces()).
  void mark_force_slots();
  /// The releases, pass-throughs and nodes behind a held shell's mid-surface into `totals`,
  /// each counted and its deepest kept (the first in slot order on a tie).
  void count_events(ContactTotals& totals) const;
  /// The slots this update() visits (m_live, m_visit; file comment "Quiet slots"): this
  /// process's slots with listed faces and those m_held keeps, or every slot after construction,
  /// probe(), a mutable constraints(), set_interference() or share_slots().
  void build_visits();
  /// After the passes: m_held, the slots of m_live that are not quiet.
  void keep_held();
  /// The slots the passes over every slot (events, the cap's sums, assembly, energy) read: the
  /// live ones, or every slot in a shared pass (the other processes' come as rows).
  std::span<const Index> visits() const {
    return m_shared_pass ? std::span<const Index>(m_all_slots) : std::span<const Index>(m_live);
  }
  /// Closest admissible face of every slave node of m_live (parallel over slots); a slot
  /// without candidate faces has none, without a look at the node.
  void search(const NodalVectors& position, std::span<const Real> node_thickness);
  /// Rebuilds the broad phase when due (then also the lists of slots with candidates and of
  /// their faces); returns whether it did.
  bool refresh_broad_phase(const NodalVectors& position, std::span<const Real> node_thickness,
                           Real* step_sq = nullptr);
  /// What admissible() derives from face f's nodes alone: its corners (a shell face's on its
  /// side, offset by half the thickness), the normal of their diagonals (unnormalised, m²), its
  /// length and direction, a shell face's depth limit (m) and the largest half thickness of its
  /// corners (m); when first read (face_bounds()), the bounds of its corners and of a shell
  /// face's mid-surface corners along that direction.
  struct FaceGeometry {
    Vec3 corner[4];
    Vec3 normal = Vec3::Zero();
    Real normal_len = 0.0;
    Vec3 unit = Vec3::Zero();
    Real shell_depth = 0.0;
    Real round = 0.0;
    bool bounds_ready = false;
    CornerBounds bounds, mid_bounds;  // mid_bounds: shell faces only
    Vec3 mid[4];                      // shell faces: the mid-surface corners, m
  };
  /// The geometry of the faces one thread of a search has evaluated (search(): a face is a
  /// candidate of several slots): valid where `stamp` equals `current`, the number of that search.
  struct FaceCache {
    std::vector<FaceGeometry> geometry;
    std::vector<std::uint32_t> stamp;
    std::uint32_t current = 0;
  };
  /// Face f's geometry at `position`: from `cache` when it holds it (and into it when not),
  /// else computed into `local`.
  FaceGeometry& face_geometry(Index f, const NodalVectors& position,
                              std::span<const Real> node_thickness, FaceCache* cache,
                              FaceGeometry& local) const;
  /// The bounds of `g` (face f's geometry), worked out on the first call.
  void face_bounds(Index f, FaceGeometry& g) const;
  /// What the admissibility test needs of a slave node, gathered once per node and search
  /// (not once per candidate face): position, normal, sidedness, half thickness, and the shell
  /// face it is held on (side memory) or null.
  struct SlaveView {
    Index slot = NO_INDEX;
    Index node = NO_INDEX;
    Vec3 point = Vec3::Zero();
    Vec3 normal = Vec3::Zero();
    bool double_sided = false;
    bool free_edge = false;
    bool point_node = false;  ///< a point node (ContactDomain::slave_point): any face orientation
    Real half_t = 0.0;
    /// A positive permanent offset (a clearance) lets the node that much deeper.
    Real allowance = 0.0;
    /// Shell nodes: the distinct nodes of the faces around the node (its own elements), for
    /// the "next to its own shell" test; `own_count` < 0 when there are more than fit.
    std::array<Index, 16> own{};
    int own_count = 0;
    const ContactFace* held = nullptr;
    /// The solid face the node was pressed on last increment (NO_INDEX: none): it stays
    /// admissible down to the whole element behind it (file comment, contact at speed).
    Index continuing = NO_INDEX;
    /// The faces come from listed_faces(): never_admissible() has been tried on them.
    bool listed = false;
    /// Last increment's closest points of this slot (search(); null: none, five starts), and
    /// where this search keeps its own for the next.
    const WarmStarts* warm = nullptr;
    WarmStarts* next = nullptr;
    /// The face geometry of a search on the calling thread (null: computed per face).
    FaceCache* faces = nullptr;
  };
  /// `all_faces` false: the view of a search over listed_faces(s) only, which never_admissible()
  /// has sifted (no own nodes gathered).
  SlaveView slave_view(Index s, const NodalVectors& position, std::span<const Real> node_thickness,
                       bool all_faces = true) const;
  /// Whether admissible() rejects face f for the node of `v` whatever the positions: a face of
  /// its own hex, a shell face next to its own shell, or no pair includes the two.
  bool never_admissible(const SlaveView& v, Index f) const;
  /// Slot s's broad-phase candidates that never_admissible() leaves (refresh_broad_phase).
  std::span<const Index> listed_faces(Index s) const {
    return {m_listed.data() + m_listed_offset[s],
            static_cast<std::size_t>(m_listed_offset[s + 1] - m_listed_offset[s])};
  }
  /// How deep (m) the node of view `v` lies behind the solid face it was pressed on last
  /// increment, when it lies behind its interior deeper than the whole element behind it
  /// (released: file comment); else 0.
  Real released_depth(const SlaveView& v, const NodalVectors& position) const;
  /// How far (m) the node of view `v`, held on a side of a shell last increment, lies behind
  /// the mid-surface of that wall (the held face, or the next elements continuing it) over its
  /// interior, when the search found it no pressed touch (`touch`) but on the wall's other side:
  /// it has passed through the shell. Else 0.
  Real passed_depth(const SlaveView& v, const SlaveTouch& touch, const NodalVectors& pos) const;
  /// The search's choice `best` for the node of view `v`, given `held` (its touch pressed into
  /// the held shell face over its interior, or none): `held` replaces an open touch, none, or a
  /// touch of the held wall's other side.
  void keep_held_side(const SlaveView& v, const SlaveTouch& held, const NodalVectors& position,
                      SlaveTouch& best) const;
  /// How far (m) the node of view `v`, still held on the side of the shell it was pressed on
  /// (`touch` on that element), lies behind the shell's mid-surface over the face's interior:
  /// deeper than half the thickness, about to pass through. On a solid face, the overlap (−gap
  /// less a clearance's allowance) where it exceeds ContactDomain::face_depth. Else 0.
  Real behind_depth(const SlaveView& v, const SlaveTouch& touch,
                    std::span<const Real> node_thickness) const;
  /// What the force pass needs of one spring (a side of a slave slot), from the pass before
  /// it: stiffness (N/m, view weight included; capped by cap_default_springs), the interaction
  /// and its law, the relative velocity of the node to the face point (m/s), whether the spring
  /// is loaded beyond its offset, and the normal force it gave (N).
  struct Spring {
    Real k = 0.0;
    Index interaction = NO_INDEX;
    InteractionLaw law;
    Vec3 v_rel = Vec3::Zero();
    bool acts = false;
    Real fn = 0.0;
  };
  /// The springs' memory and stiffness, both sides of every slot (after the search; parallel
  /// over slots): which constraint follows which touch, the interference ramp's offset, and
  /// prepare_spring of each side.
  void prepare_springs(const NodalVectors& position, const NodalVectors& velocity_half, Real dt,
                       Real dt_penalty, std::span<const Real> mass,
                       std::span<const Real> inverse_mass);
  /// The force of every slot's springs (spring_force, parallel over slots) into the per-slot
  /// forces, normal forces, energies and statuses, with the interference ramp's work.
  void spring_forces(Real dt, Real dt_penalty);
  /// The onset offset, memory (gap, normal) and stiffness of the spring of slot s on touch
  /// `t` (none: the constraint becomes inactive), into `spring`.
  void prepare_spring(Index s, ContactConstraint& c, const SlaveTouch& t, Spring& spring,
                      const NodalVectors& position, const NodalVectors& velocity_half, Real dt,
                      Real dt_penalty, std::span<const Real> mass,
                      std::span<const Real> inverse_mass) const;
  /// Scales the default-penalty springs down where the springs on one node together would
  /// exceed DEFAULT_PENALTY_NODE_BUDGET (file comment), in slot order.
  void cap_default_springs(Real dt_penalty, std::span<const Real> mass,
                           std::span<const Real> inverse_mass);
  /// Normal law, friction and energies of side `side` (0, 1) of slot s; returns the force on
  /// the slave node (N) and raises `status` to what the spring does.
  Vec3 spring_force(Index s, int side, ContactConstraint& c, const SlaveTouch& t, Real dt,
                    Real dt_penalty, OutputStatus& status);
  /// Whether face f is admissible for the slave node `v` at `position` (file comment); if so,
  /// the touch is written to `out` and its distance to the closest point to `distance`.
  /// A face that is certainly farther than `nearer_than` (m) and cannot be penetrated
  /// admissibly is rejected without its closest point (what the search does with such a face
  /// is nothing: it is neither the nearest nor a penetrated one).
  bool admissible(const SlaveView& v, Index f, const NodalVectors& position,
                  std::span<const Real> node_thickness, SlaveTouch& out, Real& distance,
                  Real nearer_than = std::numeric_limits<Real>::infinity()) const;
  /// Whether `point`, whose closest point on hex face f is `cp` beside f's edge or corner
  /// (`lateral` beyond it, m), is
  /// not f's to touch there: the surface goes on flat into its next face (which takes the
  /// point), or turns away convex and the point is outside the body in front of the next face.
  /// `corner` and `n_f`: f's corners and its (unnormalised) normal, as admissible() has them.
  bool beside_next_face(Index f, const Vec3 (&corner)[4], const Vec3& n_f, const ClosestPoint& cp,
                        const Vec3& point, Real lateral, const NodalVectors& position,
                        std::span<const Real> node_thickness) const;
  void record_sleep(const SlaveView& v, const SlaveTouch& best, const SlaveTouch& second,
                    const NodalVectors& position, std::span<const Real> node_thickness);
  void put_to_sleep(Index s, bool searched);

  ContactDomain m_domain;
  std::vector<InteractionLaw> m_laws;
  ContactOptions m_options;
  BroadPhase m_broad;
  std::vector<ContactConstraint> m_constraints;
  std::vector<SlaveTouch> m_touch;  // per slave slot, written by search()
  // Per slave slot, written by search(): how deep (m) the node went behind the solid face it
  // was pressed on last increment when that was deeper than the element behind the face (it
  // was released there: file comment), else 0.
  std::vector<Real> m_lost_depth;
  std::vector<Real> m_passed_depth;  ///< per slave slot: passed_depth() of the last search
  std::vector<Real> m_behind_depth;  ///< per slave slot: behind_depth() of the last search
  // The other side of a pinched node (file comment): its constraint, touch, force on the
  // slave node (n_slave × 3, N) and normal force (N), per slot.
  std::vector<ContactConstraint> m_second;
  std::vector<SlaveTouch> m_second_touch;
  // Per slave slot, written by search(): the closest points its search evaluated, Newton's
  // starts in the next search (SlaveView::warm).
  std::vector<WarmStarts> m_warm;
  std::vector<FaceCache> m_face_caches;  // search(): one per thread of its team
  std::vector<Real> m_second_force;
  std::vector<Real> m_second_normal_force;
  std::vector<Real> m_second_dissipation;
  std::vector<Spring> m_spring;       // (2 n_slave): side 0 at 2s, side 1 at 2s + 1
  PenaltyStiffnessSum m_default_sum;  // row sums of the default springs (cap_default_springs)
  std::vector<Index> m_node_body;     // set_rigid_bodies
  std::vector<std::array<Real, 3>> m_body_mass;
  std::vector<std::array<Real, 3>> m_body_row;  // (n_bodies) per translation, N/m
  std::vector<Real> m_body_factor;              // (n_bodies) scale of the springs on it
  std::vector<Real> m_normal_force;             // (n_slave)
  std::vector<Real> m_slave_force;              // (n_slave × 3): force on the slave node itself
  std::vector<Real> m_dissipation;              // (n_slave)
  std::vector<Real> m_stored;                   // (n_slave): energy in the slot's springs, J
  std::vector<OutputStatus> m_output_status;
  ForceAssembly m_assembly;       // nodal forces and pair sums (stage 5)
  bool m_user_stiffness = false;  // some law has its own stiffness (a LINEAR slope)
  std::vector<Real> m_user_k;     // (2 n_slave) user-stiffness springs counted this update, N/m
  std::vector<Index> m_user_law;  // (2 n_slave) their interaction
  bool m_updated = false;         // an update() has run: constraints hold last increment's touches
  // Interference fits (set_interference): per slave slot (empty when none) the ramp, and the
  // offset before this update's ramp step with the energy that step put in (J).
  struct Interference {
    Real amount = 0.0, base = 0.0, duration = 0.0;
  };
  std::vector<Interference> m_interference;
  std::vector<Real> m_ramp_before;
  std::vector<Real> m_ramp_work;
  Index m_ramping = 0;  // slots still ramping
  Real m_step_time = 0.0;
  // Slots with candidate faces at the last broad-phase build (n_slave) and the faces around
  // them (n_faces): update() refreshes the areas and normals of these slots only, the only
  // ones its search reads; probe() refreshes all. Scratch masks for the force-carrying corners
  // outside them.
  std::vector<char> m_active_slot, m_active_face;
  // listed_faces(): CSR offsets (n_slave + 1) into the faces.
  std::vector<Index> m_listed_offset, m_listed;
  // Quiet slots (file comment): at broad-phase builds, this process's slots with listed faces
  // (ascending); after each update the live slots that are not quiet (m_held); the slots this
  // update visits (build_visits()); and 0 … n_slave − 1.
  std::vector<Index> m_listed_slots;
  std::vector<Index> m_held, m_live, m_all_slots;
  bool m_visit_all = true;  // the next update() visits every slot (build_visits())
  SlotSleep m_sleep;        // sleeping slots (slot_sleep.hpp)
  // Whether some face's depth is below the search margin at the last broad-phase build: only
  // then can admissible() skip a closest point by its box (penetration reach), and only then
  // does the search evaluate last increment's face first.
  bool m_try_skip = false;
  std::vector<char> m_extra_slot, m_extra_face;
  PenaltyStiffnessSum m_penalty_sum;
  PenaltyLimit m_penalty_limit;
  // Per slave slot: the face a node released or passed through was pressed on, as the search
  // found it (count_events()), NO_INDEX otherwise.
  std::vector<Index> m_event_face;
  // share_slots(): the slots this process computes, the exchange, whether the running
  // update() shares, and the other processes' slots the last exchanges set here (reset to
  // "nothing" before the next ones).
  std::vector<char> m_owned;
  std::vector<int> m_slot_process;  ///< the process of each slot (share_slots())
  int m_process = 0;                ///< this process (share_slots())
  /// (n_slave × 3) the velocity of each slot's node that may carry a force (share_forces();
  /// empty outside a shared pass: the assembly reads the velocities it is given).
  std::vector<Real> m_work_velocity;
  std::vector<char> m_force_slot;      ///< share_forces(): the slots whose velocity travels
  double m_received_velocities = 0.0;  ///< received_velocities()
  SlotSharing* m_sharing = nullptr;
  bool m_shared_pass = false;
  bool m_broad_owned_only = false;      ///< the last broad-phase build scanned m_owned's slots only
  signed char m_rebuild_decision = -1;  ///< decide_rebuild() for the next update(); -1: none
  std::span<const char> m_faces_held;   ///< build_shared_broad_phase()'s, while it builds
  bool m_built_ahead = false;           ///< build_shared_broad_phase() before this update()
  std::vector<Index> m_received_springs, m_received_forces;
  std::vector<Index> m_sent;  ///< the slots whose rows share_springs() sent
  std::vector<int> m_counts;  ///< values each process sent in the last exchange
};

}  // namespace xpl::contact

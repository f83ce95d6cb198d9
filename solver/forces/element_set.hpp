#pragma once
/// \file The deformable elements of a model as one set: one block per element kind
/// (element_kinds.hpp: C3D8R, C3D8, S4R), folded over at compile time; the lumped nodal masses
/// and rotary inertias they make, their internal forces and the stable increment they allow.

#include <limits>
#include <memory>
#include <span>
#include <tuple>
#include <utility>
#include <vector>

#include "common/timer.hpp"
#include "contact/contact_faces.hpp"
#include "elements/increment_limit.hpp"
#include "partition/mesh_partition.hpp"
#include "solver/forces/element_kinds.hpp"
#include "solver/increment/global_increment.hpp"
#include "solver/increment/increment_control.hpp"
#include "solver/increment/mass_scaling.hpp"
#include "solver/model/model.hpp"
#include "solver/model/state.hpp"
#include "solver/motion/rigid_bodies.hpp"
#include "solver/output/output_sink.hpp"

namespace xpl {

class DistributedRun;

/// Element totals of one internal-force pass over all blocks (energy increments in J, the
/// stable increment and the critical and failed elements).
struct ElementTotals : elements::IncrementLimit {
  Real strain_energy_increment = 0.0;
  Real hourglass_energy_increment = 0.0;
  Real viscous_energy_increment = 0.0;
  Real plastic_energy_increment = 0.0;  ///< ΔALLPD: plastic dissipation of the pass

  /// Adds one block's totals (strain and hourglass energy, plastic dissipation and viscous
  /// energy where the block's totals have them, increment limit).
  template <class BlockTotals>
  void add(const BlockTotals& t) {
    strain_energy_increment += t.strain_energy_increment;
    hourglass_energy_increment += t.hourglass_energy_increment;
    if constexpr (requires { t.plastic_energy_increment; })
      plastic_energy_increment += t.plastic_energy_increment;
    merge(t);
    if constexpr (requires { t.viscous_energy_increment; })
      viscous_energy_increment += t.viscous_energy_increment;
  }
};

/// The deformable elements (those of no rigid body), their nodal forces and masses.
/// The nodal force arrays accumulate over one increment (elements, then contact) and are
/// zeroed by clear_forces() once the nodal update has used them.
class ElementSet {
 public:
  /// Builds the blocks and lumps the masses into `state` (state.reference set, state.mass zero,
  /// n_nodes): state.mass gets the element masses, the rigid elements' masses and the `*MASS`
  /// point masses; on shell models the rotational fields of `state` (n_nodes × 3) are
  /// allocated at zero and state.rotary_inertia is filled. `model` and `timers` must outlive
  /// the set.
  ElementSet(const Model& model, const RigidBodies& rigid, State& state, PhaseTimers& timers);

  /// Whether the model has S4R elements (and so nodes with rotational DOFs); in a distributed
  /// run the whole model's answer on every rank, whatever this rank's batches hold.
  bool has_shells() const;
  /// Number of deformable elements (the element cycles of the run summary), of every rank in
  /// a distributed run.
  Index size() const;

  /// The setup messages, in this order: fixed mass scaling (also a .sta note), nodes without
  /// mass, the C3D8R block, the C3D8 block, the S4R block,
  /// its warped elements (measured on `reference`, n_nodes × 3) and section-control notes.
  void report_setup(const NodalVectors& reference, OutputSink& sink) const;

  /// Sets imported element stresses (n_elements × 6 each, Pa): the solids' stress, the
  /// shells' middle, bottom and top section stresses in the output axes on `position`.
  void set_stress(const NodalVectors& position, std::span<const Real> middle,
                  std::span<const Real> bottom, std::span<const Real> top);

  /// Sets imported equivalent plastic strains of the plastic elements: the solids' from `peeq`,
  /// the shells' from their middle, bottom and top section points (n_elements each, -; between
  /// them interpolated through the thickness, Shell4rBlock::set_plastic_strain). An empty
  /// `peeq` leaves the solids alone, an empty `middle` the shells.
  void set_plastic_strain(std::span<const Real> peeq, std::span<const Real> middle,
                          std::span<const Real> bottom, std::span<const Real> top);

  /// Whether the model's elements carry hourglass state (C3D8R or S4R elements: their
  /// accumulated hourglass resultants), written with S and restored by set_hourglass_state.
  bool has_hourglass_state() const;
  /// Sets imported hourglass state (n_elements × elements::HOURGLASS_STATE_WIDTH, the rows
  /// gather_output writes into FrameFields::hourglass_state).
  void set_hourglass_state(std::span<const Real> rows);
  /// Sets the imported current thickness of the shells (STH, n_elements, m).
  void set_shell_thickness(std::span<const Real> thickness);

  /// Starts a step: the global frequency estimate is made anew at the next force pass.
  void begin_step() { m_global.begin_step(); }
  /// The global estimate made since the last call, as a note in `sink` (nothing otherwise).
  void report_increment_limit(OutputSink& sink);

  /// Internal forces of every block at the state's positions and half-step velocities over
  /// the increment `dt` (s; 0: no rate terms), added to force_internal() and
  /// moment_internal(); energies and the element-by-element estimate go into `totals`.
  void compute_forces(const State& state, Real dt, ElementTotals& totals);
  /// The elements' part of the increment after the force pass that made `totals` at the
  /// state's positions: the element estimate and its critical element, and the factor the
  /// global estimate (GlobalIncrementLimit, made anew when due) puts on it in the state's step.
  ElementEstimate increment_estimate(const State& state, const ElementTotals& totals);
  /// increment_estimate() of a force pass at the state's positions that leaves no forces.
  ElementEstimate increment_estimate(const State& state);

  /// Element output requested by `what` (stress, section stresses, volume, thickness, PEEQ) into
  /// `state`; the arrays are allocated on first use (n_elements rows).
  void gather_output(const State& state, const FrameRequest& what, FrameFields& frame) const;
  /// gather_output() of this rank's elements only (the rows of the others' elements left at
  /// their initial 0 or NaN): what a rank writes when every rank writes its rows of a frame.
  void gather_local_output(const State& state, const FrameRequest& what, FrameFields& frame) const;
  /// Whether fill_output can make a frame's element fields one at a time: runs in one
  /// process. A distributed run gathers them all to rank 0 at once (gather_output), since
  /// every rank takes part in each gather.
  bool fills_fields_alone() const { return m_run == nullptr; }
  /// PEEQ of `what` into `frame` (gather_output without the element fields of
  /// ElementField).
  void gather_plastic_strain(const FrameRequest& what, FrameFields& frame) const;
  /// `field` of every element at `state` into `rows`, laid out as the FrameFields member of
  /// that name and with the values gather_output gives it; empty where gather_output leaves
  /// the member empty. The field alone: a frame written field by field holds one at a time.
  void fill_output(const State& state, ElementField field, std::vector<Real>& rows) const;

  /// Internal nodal forces of the increment (n_nodes × 3), N; contact adds its forces here.
  NodalVectors& force_internal() { return m_force_internal; }
  const NodalVectors& force_internal() const { return m_force_internal; }
  /// Internal nodal moments (n_nodes × 3), N·m; 0 rows without shells.
  const NodalVectors& moment_internal() const { return m_moment_internal; }
  NodalVectors& moment_internal() { return m_moment_internal; }
  /// Zeroes the nodal forces and moments once they have been used.
  void clear_forces();

  /// Inverse lumped mass (n_nodes), 1/kg; 0 for nodes without mass and rigid-body nodes.
  const std::vector<Real>& inverse_mass() const { return m_inverse_mass; }
  /// Inverse rotary inertia (n_nodes), 1/(kg·m²); empty without shells.
  const std::vector<Real>& inverse_inertia() const { return m_inverse_inertia; }
  /// Recomputes the inverse mass (and inverse rotary inertia) of `nodes` from `state` after
  /// the ties moved mass between them (Ties::distribute_mass); rigid-body nodes keep 0.
  void update_inverse_mass(const std::vector<Index>& nodes, const State& state,
                           const RigidBodies& rigid);
  /// Shell thickness at each node for contact (n_nodes, m), or empty without shells.
  const std::vector<Real>& node_thickness() const { return m_node_thickness; }
  /// \name Distributed runs (distributed_run.hpp).
  /// The partition of the SIMD batches of the layout into `parts` with `method` (each batch
  /// a vertex of the graph, with the nodes and the cost of its lanes: a batch's lanes are
  /// one colour, spread along the mesh, so that an element partition rounded to batches
  /// would be badly balanced), and the part of each element (that of its batch) in
  /// `element_part` (n_elements; elements of no block: part 0). Each (node, element) of
  /// `node_element_pairs` adds an edge between the first batch holding the node and the batch
  /// of the element (the t = 0 contact candidate pairs); `node_node_pairs` one between the
  /// first batches holding each of the two nodes (a tie's slave node and master corners).
  partition::MeshPartition partition_batches(
      int parts, partition::Method method, std::vector<int>& element_part,
      const std::vector<std::pair<Index, Index>>& node_element_pairs = {},
      const std::vector<std::pair<Index, Index>>& node_node_pairs = {}) const;
  /// The position of each element in the one-rank order of the nodal sums (block in force
  /// pass order, batch, lane); elements of no block NO_INDEX.
  std::vector<Index> element_order() const;
  /// Keeps the elements of this rank's batches (run.element_part(), from batch_partition())
  /// for the force pass; the whole blocks stay for the global increment estimate and the
  /// reductions. From here on compute_forces() exchanges the interface forces and reduces
  /// the totals over the ranks of `run` (which must outlive the set).
  void distribute(DistributedRun& run);

  /// \name
  /// Kind of each element for the contact domain (n_elements).
  const std::vector<contact::ElementKind>& element_kinds() const { return m_element_kinds; }

 private:
  /// Builds the block of kind K (none without elements of its types) and lumps its masses.
  template <class K>
  void build_block(const RigidBodies& rigid, State& state);
  /// Allocates the rotational fields of `state` at zero (models with rotational DOFs, P2).
  void add_rotations(State& state);
  /// The `*FIXED MASS SCALING` factor of element e (1 without scaling).
  Real mass_factor(Index e) const;
  /// Calls `f(block)` for the block of every kind present, in ElementKinds order or in the
  /// order of the kind indices `I...`.
  template <class F>
  void for_each_block(F&& f) const;
  template <class F>
  void for_each_block(F&& f);
  template <std::size_t... I, class F>
  void for_each_block(std::index_sequence<I...>, F&& f);
  /// The S4R block (this rank's batches in a distributed run), or nullptr: nullptr on a rank
  /// whose part holds no shell even when the model has shells (has_shells()).
  const elements::Shell4rBlock* shells() const {
    return std::get<std::unique_ptr<elements::Shell4rBlock>>(m_blocks).get();
  }
  /// Masses of the rigid elements and point masses into state.mass.
  void add_other_masses(const RigidBodies& rigid, State& state) const;
  void set_node_thickness(const RigidBodies& rigid, const NodalVectors& reference);
  void set_inverse_mass(const RigidBodies& rigid, const std::vector<Real>& mass);
  void report_warped_shells(const NodalVectors& reference, OutputSink& sink) const;
  /// Splits the blocks into `parts` per-thread parts for the force pass, unless they are.
  void use_partition(int parts);
  /// Distributed runs: marks the batches with a corner at an interface node (phase 0, the
  /// first of the force pass) and the others (phase 1) in every block, and SHARED in
  /// `node_part` the interface nodes and the nodes batches of both phases touch (their
  /// corners then go to slots, summed in batch order whichever phase ran first).
  void mark_batch_phases(std::vector<Index>& node_part);
  /// Distributed runs: the values of the corner slots of the rank's interface nodes after
  /// the pass of phase 0, sent to the neighbours.
  void send_interface_forces();
  /// Distributed runs: once the neighbours' values are in, the interface nodes' forces folded
  /// in the one-rank order.
  void combine_interface_forces();
  /// The value of component c of the corner slot `source` (m_slot_source).
  Real slot_value(Index source, int c) const;
  /// The values of the corner slot `source`, and how many it has (3: a hex's force, 6: a
  /// shell's force and moment).
  const Real* slot_values(Index source, int& count) const;
  /// Distributed runs: post_totals() sends the rank's batch totals to every rank
  /// (DistributedRun::post_allgather(), returns at once); reduce_totals() waits for every
  /// rank's, puts them into the whole blocks and reduces them as one rank does into `totals`.
  void post_totals();
  void reduce_totals(ElementTotals& totals);
  template <std::size_t... I>
  void distribute_blocks(std::index_sequence<I...>);
  template <class K>
  void distribute_block(std::unique_ptr<K>& block, std::unique_ptr<K>& whole);
  /// Calls `f(block)` for the whole blocks of a distributed run (for_each_block otherwise).
  template <class F>
  void for_each_whole_block(F&& f) const;

  const Model& m_model;
  PhaseTimers& m_timers;
  /// One block per kind (nullptr: the model has no such elements), in ElementKinds order.
  std::tuple<std::unique_ptr<elements::Hex8rBlock>, std::unique_ptr<elements::Hex8Block>,
             std::unique_ptr<elements::Shell4rBlock>>
      m_blocks;
  NodalVectors m_force_internal;   ///< (n_nodes × 3), zeroed after each use
  NodalVectors m_moment_internal;  ///< (n_nodes × 3) on shell models, else 0 rows
  std::vector<Real> m_inverse_mass;
  std::vector<Real> m_inverse_inertia;
  std::vector<Real> m_node_thickness;
  std::vector<contact::ElementKind> m_element_kinds;
  Index m_massless = 0;                 ///< nodes that belong to no element and have no mass
  GlobalIncrementLimit m_global;        ///< bound on the element estimate from ω_max
  int m_parts = 0;                      ///< parts of the blocks' partition (0: none yet)
  std::vector<Index> m_boundary_nodes;  ///< nodes two parts share (thread_partition.hpp)
  bool m_rotations = false;             ///< nodes have rotational DOFs (a kind with ROTATIONS)
  MassScalingReport m_mass_scaling;     ///< `*FIXED MASS SCALING` done in the constructor
  /// Distributed runs: the whole blocks (m_blocks then holds this rank's batches), the run,
  /// the global batch of each local batch per kind, and where each model slot (corner) of
  /// this rank at an interface node has its value: kind × 2^29 + corner slot of its block.
  std::tuple<std::unique_ptr<elements::Hex8rBlock>, std::unique_ptr<elements::Hex8Block>,
             std::unique_ptr<elements::Shell4rBlock>>
      m_whole;
  DistributedRun* m_run = nullptr;
  std::vector<std::vector<Index>> m_rank_batches[3];  ///< [kind][rank]: its batches
  std::vector<Real> m_totals_mine;  ///< post_totals(): this rank's batch totals (a kept buffer)
  std::vector<Index> m_slot_source;
  int m_slot_parts = 0;           ///< m_parts when m_slot_source was made
  NodalVectors m_whole_position;  ///< positions of every node for the global estimate
  /// [kind]: 1 for the whole block's batches this rank multiplies in the global estimate's
  /// stiffness products (distribute()).
  std::vector<char> m_product_batches[3];
};

}  // namespace xpl

#include "solver/explicit_solver.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "contact/contact_engine.hpp"
#include "contact/initial_overclosure.hpp"
#include "elements/hex8r.hpp"
#include "elements/shell4r.hpp"
#include "solver/boundary_state.hpp"
#include "solver/gravity_loads.hpp"
#include "solver/node_rotations.hpp"
#include "solver/output_schedule.hpp"
#include "solver/overclosure_report.hpp"
#include "solver/pressure_loads.hpp"
#include "solver/rigid_bodies.hpp"

namespace xpl {

namespace {

/// Nodes per chunk of the nodal loops; partial sums per chunk are added in chunk order so
/// that energies do not depend on the thread count.
constexpr Index NODE_CHUNK = 2048;

/// Increments at the start of each step before the energy balance is checked (check_health).
constexpr long BALANCE_WARMUP = 10;

elements::HexMaterial hex_material(const Model& model, Index element) {
  const SolidSection& section = model.solid_sections[model.element_section[element]];
  const Material& m = model.materials[section.material];
  elements::HexMaterial h;
  h.density = m.density;
  h.young = m.young;
  h.poisson = m.poisson;
  if (section.controls != NO_INDEX) {
    const SectionControls& c = model.section_controls[section.controls];
    h.hourglass = c.hourglass == HourglassType::Viscous ? elements::HourglassForm::Viscous
                                                        : elements::HourglassForm::Stiffness;
    h.hourglass_scale =
        h.hourglass == elements::HourglassForm::Viscous ? c.viscous_scale : c.stiffness_scale;
  }
  return h;
}

elements::ShellProperties shell_properties(const Model& model, Index element) {
  const ShellSection& section = model.shell_sections[model.element_section[element]];
  const Material& m = model.materials[section.material];
  elements::ShellProperties p;
  p.density = m.density;
  p.young = m.young;
  p.poisson = m.poisson;
  p.thickness = section.thickness;
  p.integration_points = section.integration_points;
  p.offset = section.offset;
  if (section.controls != NO_INDEX)
    p.hourglass_scale = model.section_controls[section.controls].stiffness_scale;
  return p;
}

/// Element totals of one internal-force pass over all blocks.
struct ElementTotals : elements::IncrementLimit {
  Real strain_energy_increment = 0.0;
  Real hourglass_energy_increment = 0.0;
  Real viscous_energy_increment = 0.0;

  template <class BlockTotals>
  void add(const BlockTotals& t) {
    strain_energy_increment += t.strain_energy_increment;
    hourglass_energy_increment += t.hourglass_energy_increment;
    merge(t);
  }
};

std::string format_real(Real v) {
  std::ostringstream out;
  out.precision(4);
  out << v;
  return out.str();
}

}  // namespace

struct ExplicitSolver::Impl {
  const Model& model;
  OutputSink& sink;
  SolverOptions options;
  State state;
  std::unique_ptr<elements::Hex8rBlock> hex;
  std::unique_ptr<elements::Shell4rBlock> shell;
  BoundaryState boundary;
  PressureLoads pressures;
  GravityLoads gravity;
  NodeRotations rotations;
  RigidBodies rigid;
  /// General contact of the current step; null when the step has none (P2).
  std::unique_ptr<contact::ContactEngine> contact;
  std::vector<Real> node_thickness;  ///< shell node thickness for contact (n_nodes), or empty
  std::vector<contact::ElementKind> element_kinds;  ///< (n_elements), for the contact domain
  /// Contact pair names, in the engine's pair order (history output).
  std::vector<std::string> contact_pair_names;
  /// Shell models only (else 0 rows / empty): internal moments (n_nodes × 3), inverse rotary
  /// inertia, and the moments of the previous increment at prescribed rotations (work).
  NodalVectors moment_internal;
  std::vector<Real> inverse_inertia;
  NodalVectors previous_moment;
  bool rotation_synced = true;  ///< state.rotation matches `rotations`
  OutputSchedule schedule;
  PhaseTimers timers;
  NodalVectors force_internal;  ///< (n_nodes × 3), zeroed after each use
  /// (n_nodes × 3), non-zero only on loaded DOFs; allocated only when a step has loads (P2).
  NodalVectors force_external;
  std::vector<Real> inverse_mass;  ///< 0 for nodes without mass (no element)
  std::vector<Real> chunk_sums;
  std::vector<Real> history_row;
  NodalVectors previous_force;            ///< f_ext + reaction at the previous increment (work)
  std::vector<LoadedDof> free_loads;      ///< loaded DOFs that are not prescribed
  std::vector<LoadedDof> loaded_dofs;     ///< every DOF with a load (CLOAD or pressure)
  std::vector<PrescribedDof> prescribed;  ///< the step's prescribed DOFs that exist
  std::vector<Real> prescribed_value;     ///< current value of each prescribed DOF
  std::vector<Real> v_old_prescribed, v_old_loaded;
  Real dt_half = 0.0;     ///< dt_{n+1/2}: the increment about to be taken
  Real dt_first = 0.0;    ///< first stable increment (for the collapse check)
  Real max_energy = 0.0;  ///< running maximum of the energy scales (instability check)
  Real initial_total = 0.0;
  ExternalId critical_id = 0;
  long loop_increments = 0;
  long step_first_increment = 0;  ///< state.increment at the start of the current step
  double loop_seconds = 0.0;
  bool started = false;

  Impl(const Model& m, OutputSink& s, SolverOptions o) : model(m), sink(s), options(o) {}

  void setup();
  /// Puts an imported state (positions, velocities, rotations, stresses) into place.
  void apply_initial_state(const InitialState& imported);
  void report_warped_shells();
  void begin_step(int step);
  /// Builds (or keeps) the contact engine of `step`.
  void begin_contact(int step);
  /// Initial overclosures of a newly built contact engine (SPEC C2–C6): adjusts (step 1) or
  /// stores offsets (later step, import); with an engine of an earlier step, carries its
  /// offsets over instead.
  void resolve_overclosures(int step, const contact::ContactEngine* previous);
  /// The clearance views of the assignments given with the step's *CONTACT (and their names
  /// for the reports); empty when there are none.
  std::vector<contact::ClearanceView> clearance_views(int step,
                                                      std::vector<ClearanceViewNames>& names) const;
  /// Stable increment of the elements at the current positions (no state change), s.
  Real stable_increment(int step);
  /// Contact forces at the current positions into force_internal, energies into the state.
  void apply_contact(Real dt_taken, Real dt_penalty);
  void compute_forces(Real dt, ElementTotals& totals);
  /// The increment the elements allow (deck scale factor and safety applied, or the fixed
  /// increment), before it is shortened to land on the end of the step; +inf without elements.
  Real stable_step(const ElementTotals& totals, int step) const;
  Real next_increment(const ElementTotals& totals, Real remaining, int step) const;
  /// Central-difference update of the free DOFs of a field; returns its kinetic energy
  /// (summed per chunk in chunk order: independent of the thread count).
  Real free_update(const DofPointers& d, Real dt_avg, Real w_new, Real* sums);
  void update_nodes(Real dt_prev, Real dt_next, Real t_next_half, Real t_next_end);
  void apply_loads(Real step_time, Real total_time);
  void write_frame(const FrameRequest& what);
  /// Per-node contact pressure, status and forces into the state (for a frame).
  void fill_contact_output();
  void write_history();
  void write_status();
  void sync_rotation();
  void check_health(const ElementTotals& totals);
  void run_step(int step);
  RunSummary summary() const;
};

void ExplicitSolver::Impl::setup() {
  ScopedTimer timer(timers, Phase::Setup);
  if (options.threads > 0) omp_set_num_threads(options.threads);
  const Index n = model.node_count();
  state.reference = model.coordinates;
  state.position = model.coordinates;
  state.velocity =
      model.initial_velocity.rows() == n ? model.initial_velocity : NodalVectors::Zero(n, 3);
  state.velocity_half = state.velocity;
  state.acceleration = NodalVectors::Zero(n, 3);
  state.reaction = NodalVectors::Zero(n, 3);
  state.mass.assign(n, 0.0);
  force_internal = NodalVectors::Zero(n, 3);

  rigid = RigidBodies(model);
  auto deformable = [&](Index e) {
    return rigid.element_body().empty() || rigid.element_body()[e] == NO_INDEX;
  };
  std::vector<Index> hex_elements;
  std::vector<Index> connectivity;
  std::vector<elements::HexMaterial> materials;
  for (Index e = 0; e < model.element_count(); ++e) {
    if (model.element_types[e] != ElementType::C3D8R || !deformable(e)) continue;
    hex_elements.push_back(e);
    const Index* nodes = model.nodes_of(e);
    connectivity.insert(connectivity.end(), nodes, nodes + 8);
    materials.push_back(hex_material(model, e));
  }
  if (!hex_elements.empty()) {
    hex = std::make_unique<elements::Hex8rBlock>(hex_elements, connectivity, materials, n);
    hex->add_lumped_mass(state.reference, state.mass);
  }
  std::vector<Index> shell_elements;
  std::vector<elements::ShellProperties> shell_props;
  connectivity.clear();
  for (Index e = 0; e < model.element_count(); ++e) {
    if (!is_shell(model.element_types[e]) || !deformable(e)) continue;
    shell_elements.push_back(e);
    const Index* nodes = model.nodes_of(e);
    connectivity.insert(connectivity.end(), nodes, nodes + 4);
    shell_props.push_back(shell_properties(model, e));
  }
  if (!shell_elements.empty()) {
    // Rotational DOFs exist only in shell models (P2).
    shell = std::make_unique<elements::Shell4rBlock>(shell_elements, connectivity, shell_props, n);
    state.rotation = NodalVectors::Zero(n, 3);
    state.angular_velocity = NodalVectors::Zero(n, 3);
    state.angular_velocity_half = NodalVectors::Zero(n, 3);
    state.reaction_moment = NodalVectors::Zero(n, 3);
    state.rotary_inertia.assign(n, 0.0);
    moment_internal = NodalVectors::Zero(n, 3);
    shell->add_lumped_mass(state.reference, state.mass, state.rotary_inertia);
    inverse_inertia.assign(n, 0.0);
    for (Index i = 0; i < n; ++i)
      if (state.rotary_inertia[i] > 0.0) inverse_inertia[i] = 1.0 / state.rotary_inertia[i];
    rotations = NodeRotations(n);
  }
  // Rigid elements: their lumped mass joins the body; point masses join their node.
  for (Index e = 0; e < model.element_count(); ++e) {
    if (deformable(e)) continue;
    const Real m = element_node_mass(model, e, state.reference);
    const Index* nodes = model.nodes_of(e);
    for (int a = 0; a < nodes_per_element(model.element_types[e]); ++a) state.mass[nodes[a]] += m;
  }
  for (const PointInertia& p : model.point_inertias) state.mass[p.node] += p.mass;
  element_kinds.resize(static_cast<std::size_t>(model.element_count()));
  for (Index e = 0; e < model.element_count(); ++e)
    element_kinds[e] = model.element_types[e] == ElementType::C3D8R ? contact::ElementKind::Hex
                       : is_shell(model.element_types[e])           ? contact::ElementKind::Shell
                                                                    : contact::ElementKind::Other;
  std::vector<std::string> rigid_messages;
  if (!rigid.empty()) {
    if (!shell) {
      // The reference nodes carry rotations (UR, VR, RM) even without shells.
      state.rotation = NodalVectors::Zero(n, 3);
      state.angular_velocity = NodalVectors::Zero(n, 3);
      state.angular_velocity_half = NodalVectors::Zero(n, 3);
      state.reaction_moment = NodalVectors::Zero(n, 3);
    }
    rigid_messages = rigid.setup(model, state.mass, state);
  }
  if (shell) node_thickness = shell->node_thickness(state.reference, n);
  for (Index e = 0; e < model.element_count(); ++e) {
    if (deformable(e) || !is_shell(model.element_types[e])) continue;
    if (node_thickness.empty()) node_thickness.assign(n, 0.0);
    const Real t = model.shell_sections[model.element_section[e]].thickness;
    const Index* nodes = model.nodes_of(e);
    for (int a = 0; a < 4; ++a) node_thickness[nodes[a]] = std::max(node_thickness[nodes[a]], t);
  }
  inverse_mass.assign(n, 0.0);
  Index massless = 0;
  for (Index i = 0; i < n; ++i) {
    if (rigid.is_rigid_node(i)) continue;  // moved by its body
    if (state.mass[i] > 0.0)
      inverse_mass[i] = 1.0 / state.mass[i];
    else
      ++massless;
  }
  chunk_sums.assign(static_cast<std::size_t>((n + NODE_CHUNK - 1) / NODE_CHUNK) * 2, 0.0);

  if (options.initial_state != nullptr) apply_initial_state(*options.initial_state);

  sink.begin_run(model);
  if (options.initial_state != nullptr)
    sink.message(Severity::Info,
                 "the run starts from the imported state of " + options.initial_state->source +
                     " (positions, velocities" +
                     (options.initial_state->stress.empty() ? "" : ", element stresses") +
                     "); time starts at 0. Hourglass forces and contact state start at zero; "
                     "ALLSE counts the strain energy from here on");
  for (const DeckMessage& m : model.deck_messages)
    sink.message(m.warning ? Severity::Warning : Severity::Note, m.text);
  for (const SectionControls& c : model.section_controls)
    if (c.hourglass == HourglassType::RelaxStiffness)
      sink.message(Severity::Note, "section controls " + c.name +
                                       ": HOURGLASS=RELAX STIFFNESS is run as STIFFNESS "
                                       "(Flanagan-Belytschko stiffness form)");
  for (const std::string& m : rigid_messages) sink.message(Severity::Info, m);
  if (massless > 0)
    sink.message(Severity::Warning, std::to_string(massless) +
                                        " node(s) belong to no element and have no mass; "
                                        "they keep their initial velocity");
  if (hex)
    sink.message(Severity::Info, "C3D8R elements: " + std::to_string(hex->size()) + " in " +
                                     std::to_string(hex->color_count()) +
                                     " colours (race-free parallel assembly)");
  if (shell) {
    sink.message(Severity::Info,
                 "S4R elements: " + std::to_string(shell->size()) + " in " +
                     std::to_string(shell->color_count()) +
                     " colours; rotary inertia scaled to (m/4)·max(t²/12, A/8) per node so "
                     "that the membrane wave sets the stable increment");
    report_warped_shells();
    for (const SectionControls& c : model.section_controls)
      if (c.hourglass == HourglassType::Viscous)
        sink.message(Severity::Note, "section controls " + c.name +
                                         ": S4R elements use the stiffness hourglass form "
                                         "(HOURGLASS=VISCOUS applies to C3D8R only)");
  }
}

void ExplicitSolver::Impl::apply_initial_state(const InitialState& imported) {
  const Index n = model.node_count();
  if (imported.displacement.rows() != n || imported.velocity.rows() != n)
    throw std::invalid_argument("imported state: U and V must have one row per node");
  state.position = state.reference + imported.displacement;
  state.velocity = imported.velocity;
  state.velocity_half = imported.velocity;
  if (shell && imported.rotation.rows() == n) {
    rotations.set(imported.rotation);
    state.rotation = imported.rotation;
    rotation_synced = true;
    if (imported.angular_velocity.rows() == n) {
      state.angular_velocity = imported.angular_velocity;
      state.angular_velocity_half = imported.angular_velocity;
    }
  }
  if (!imported.stress.empty()) {
    if (hex) hex->set_stress(imported.stress);
    if (shell)
      shell->set_output_stress(
          state.position, imported.stress,
          imported.stress_bottom.empty() ? imported.stress : imported.stress_bottom,
          imported.stress_top.empty() ? imported.stress : imported.stress_top);
  }
}

void ExplicitSolver::Impl::report_warped_shells() {
  // Warped elements are evaluated on their projected plane with rigid links to the nodes
  // (accurate for moderate warping); strongly warped ones deserve the user's attention.
  constexpr Real WARN_DEGREES = 10.0;
  constexpr int MAX_LISTED = 20;
  int warped = 0;
  Real worst = 0.0;
  for (Index i = 0; i < shell->size(); ++i) {
    const Real angle = shell->warp_angle(state.reference, i);
    worst = std::max(worst, angle);
    if (angle <= WARN_DEGREES) continue;
    if (++warped > MAX_LISTED) continue;
    const Index e = shell->element_index(i);
    const SourceLocation where = model.element_where(e);
    sink.message(Severity::Warning,
                 where.file + ":" + std::to_string(where.line) + ": *ELEMENT: S4R element " +
                     std::to_string(model.element_ids[e]) + " is warped by " + format_real(angle) +
                     " degrees (more than " + format_real(WARN_DEGREES) +
                     "); refine the mesh where the surface is curved");
  }
  if (warped > MAX_LISTED)
    sink.message(Severity::Warning,
                 std::to_string(warped) + " S4R elements are warped by more than " +
                     format_real(WARN_DEGREES) + " degrees (worst " + format_real(worst) +
                     "); the first " + std::to_string(MAX_LISTED) + " are listed above");
}

void ExplicitSolver::Impl::begin_step(int step) {
  const NodalVectors displacement = state.position - state.reference;
  sync_rotation();
  boundary.begin_step(model, step, displacement, state.velocity, state.rotation,
                      state.angular_velocity);
  pressures.begin_step(model, step);
  gravity.begin_step(model, step, state.reference, state.mass);
  schedule.begin_step(model, step);
  state.reaction.setZero();
  if (shell) state.reaction_moment.setZero();
  // Reference nodes of rigid bodies drive their body; members cannot be prescribed.
  std::vector<PrescribedDof> active = boundary.prescribed();
  const Index dropped_members = rigid.empty() ? 0 : rigid.begin_step(active);
  // Rotations prescribed on nodes that belong to no shell have nothing to act on.
  prescribed.clear();
  bool dropped_rotations = boundary.has_rotational_dofs();
  for (const PrescribedDof& d : active) {
    if (d.component >= 3 && (state.rotary_inertia.empty() || state.rotary_inertia[d.node] <= 0.0)) {
      dropped_rotations = true;
      continue;
    }
    prescribed.push_back(d);
  }
  v_old_prescribed.assign(prescribed.size(), 0.0);
  prescribed_value.resize(prescribed.size());
  for (std::size_t k = 0; k < prescribed.size(); ++k)
    prescribed_value[k] = prescribed[k].component >= 3
                              ? state.rotation(prescribed[k].node, prescribed[k].component - 3)
                              : 0.0;
  const auto n = static_cast<std::size_t>(model.node_count());
  std::vector<char> is_prescribed(n * 6, 0);
  for (const PrescribedDof& d : prescribed) is_prescribed[d.component * n + d.node] = 1;
  // Loaded DOFs: CLOADs and the three components of every node under pressure or gravity.
  loaded_dofs = boundary.loads();
  std::vector<char> is_loaded(n * 3, 0);
  for (const LoadedDof& l : loaded_dofs) is_loaded[l.component * n + l.node] = 1;
  for (const std::vector<Index>* nodes : {&pressures.nodes(), &gravity.nodes()})
    for (Index node : *nodes)
      for (int c = 0; c < 3; ++c)
        if (!is_loaded[c * n + node]) {
          is_loaded[c * n + node] = 1;
          loaded_dofs.push_back({node, c, 0.0, NO_INDEX});
        }
  free_loads.clear();
  for (const LoadedDof& l : loaded_dofs)
    if (!is_prescribed[l.component * n + l.node]) free_loads.push_back(l);
  v_old_loaded.assign(free_loads.size(), 0.0);
  if (previous_force.rows() == 0 && (!prescribed.empty() || !free_loads.empty()))
    previous_force = NodalVectors::Zero(model.node_count(), 3);
  if (shell && previous_moment.rows() == 0 && !prescribed.empty())
    previous_moment = NodalVectors::Zero(model.node_count(), 3);
  state.step = step;
  state.step_time = 0.0;
  sink.begin_step(model, step);
  if (dropped_rotations)
    sink.message(Severity::Note, "step " + model.steps[step].name +
                                     ": boundary conditions on DOFs 4-6 of nodes that belong "
                                     "to no shell are ignored (solid element nodes have no "
                                     "rotations)");
  if (dropped_members > 0)
    sink.message(Severity::Warning,
                 "step " + model.steps[step].name + ": " + std::to_string(dropped_members) +
                     " boundary condition(s) on member nodes of rigid bodies are ignored; "
                     "prescribe the motion on the REF NODE");
  begin_contact(step);
  if (schedule.has_history()) {
    std::vector<HistorySeries> series = schedule.series();
    if (contact)
      for (const std::string& name : contact_pair_names)
        for (const char* v : {"CFN", "CFS"}) series.push_back({"contact/" + name + "/" + v, 1, {}});
    sink.declare_history(series);
  }
}

void ExplicitSolver::Impl::begin_contact(int step) {
  // The definition in force: the latest *CONTACT up to this step, and every *CONTACT PAIR.
  const Step& s = model.steps[step];
  const bool changed = step == 0 || s.contact || !s.contact_pairs.empty();
  if (!changed) return;
  const GeneralContact* general = nullptr;
  for (int k = step; k >= 0 && general == nullptr; --k)
    if (model.steps[k].contact) general = &*model.steps[k].contact;
  std::vector<ContactPair> pairs = model.contact_pairs;
  for (int k = 0; k <= step; ++k)
    pairs.insert(pairs.end(), model.steps[k].contact_pairs.begin(),
                 model.steps[k].contact_pairs.end());
  std::unique_ptr<contact::ContactEngine> previous = std::move(contact);
  contact_pair_names.clear();
  const bool has_general =
      general != nullptr && (general->all_exterior || !general->inclusions.empty());
  if (!has_general && pairs.empty()) return;

  contact::DomainSpec spec;
  std::vector<Index> domain_surface(model.surfaces.size(), NO_INDEX);
  Index all_exterior = NO_INDEX;
  auto surface = [&](Index model_surface) -> Index {
    if (model_surface == NO_INDEX) {
      if (all_exterior == NO_INDEX) {
        all_exterior = static_cast<Index>(spec.surfaces.size());
        spec.surfaces.push_back({"ALL_EXTERIOR", true, {}});
      }
      return all_exterior;
    }
    Index& k = domain_surface[model_surface];
    if (k == NO_INDEX) {
      k = static_cast<Index>(spec.surfaces.size());
      contact::DomainSurface d;
      d.name = model.surfaces[model_surface].name;
      for (const ElementFace& f : model.surfaces[model_surface].faces)
        d.faces.push_back({f.element, f.face});
      spec.surfaces.push_back(std::move(d));
    }
    return k;
  };
  auto name_of = [&](Index a, Index b) {
    return spec.surfaces[a].name + (a == b ? "" : "-" + spec.surfaces[b].name);
  };
  if (has_general) {
    if (general->all_exterior) {
      const Index k = surface(NO_INDEX);
      spec.inclusions.push_back({k, k, false});
      contact_pair_names.push_back(name_of(k, k));
    }
    for (const SurfacePair& p : general->inclusions) {
      const Index a = surface(p.first), b = surface(p.second);
      spec.inclusions.push_back({a, b, false});
      contact_pair_names.push_back(name_of(a, b));
    }
    for (const SurfacePair& p : general->exclusions)
      spec.exclusions.push_back({surface(p.first), surface(p.second), false});
    for (const auto& [p, interaction] : general->properties) {
      if (p.first == NO_INDEX && p.second == NO_INDEX)
        spec.default_interaction = interaction;
      else
        spec.interactions.push_back({{surface(p.first), surface(p.second), false}, interaction});
    }
  }
  for (const ContactPair& p : pairs) {
    const Index a = surface(p.slave), b = surface(p.master);
    spec.inclusions.push_back({a, b, true});
    spec.interactions.push_back({{a, b, true}, p.interaction});
    contact_pair_names.push_back(name_of(a, b));
  }
  spec.element_body = rigid.element_body();
  std::vector<contact::InteractionLaw> laws;
  for (const SurfaceInteraction& i : model.surface_interactions)
    laws.push_back({i.friction, i.linear ? i.linear_slope : 0.0});
  contact::ContactOptions options;
  if (has_general) options.penalty_scale = general->penalty_scale;
  const contact::ElementTopology topology{model.element_offsets, model.element_nodes,
                                          element_kinds};
  contact::ContactDomain domain(spec, topology, state.position);
  const std::size_t n_faces = domain.faces().size();
  const Index n_slaves = domain.slaves().size();
  contact = std::make_unique<contact::ContactEngine>(std::move(domain), std::move(laws), options,
                                                     state.position, node_thickness);
  sink.message(Severity::Info, "step " + s.name + ": contact domain of " + std::to_string(n_faces) +
                                   " faces and " + std::to_string(n_slaves) +
                                   " slave nodes, search margin " +
                                   format_real(contact->broad_phase().margin()) + " m");
  resolve_overclosures(step, previous.get());
}

void ExplicitSolver::Impl::resolve_overclosures(int step, const contact::ContactEngine* previous) {
  const Step& s = model.steps[step];
  if (previous != nullptr) {
    contact::carry_offsets(*previous, *contact);
    sink.message(Severity::Note,
                 "step " + s.name +
                     ": the contact domain changes; slave nodes of the earlier domain keep their "
                     "contact offsets, new interactions get plain penalty forces from the first "
                     "increment (no adjustment, no overclosure or crossed-surface diagnostics "
                     "for them, as Abaqus/Explicit)");
    return;
  }
  const Diagnostics& diagnostics = model.diagnostics_of(step);
  contact::OverclosureSettings settings;
  settings.adjust = step == 0 && options.initial_state == nullptr;
  settings.offset_reason =
      step == 0 ? contact::OffsetReason::Import : contact::OffsetReason::LaterStep;
  settings.detect_crossed = diagnostics.detect_crossed_surfaces;
  const Index n = model.node_count();
  std::vector<std::uint8_t> lock(static_cast<std::size_t>(n), 0);
  for (const PrescribedDof& d : prescribed)
    if (d.component < 3) lock[d.node] |= static_cast<std::uint8_t>(1u << d.component);
  for (Index i = 0; i < n; ++i)
    if (rigid.is_rigid_node(i)) lock[i] |= contact::LOCK_RIGID;
  NodalVectors as_read;
  if (settings.adjust) as_read = state.position;
  const contact::ElementTopology topology{model.element_offsets, model.element_nodes,
                                          element_kinds};
  // Clearances first (C7–C10); the automatic pass then leaves their nodes alone.
  std::vector<ClearanceViewNames> view_names;
  const std::vector<contact::ClearanceView> views = clearance_views(step, view_names);
  contact::ClearanceReport clearances;
  contact::OverclosureReport report;
  {
    ScopedTimer timer(timers, Phase::ContactSearch);
    if (!views.empty()) {
      clearances = contact::apply_clearances(*contact, topology, state.position, node_thickness,
                                             lock, views, settings.adjust);
      settings.exclude = clearances.handled;
    }
    report = contact::resolve_initial_overclosures(*contact, topology, state.position,
                                                   node_thickness, lock, settings);
  }
  const bool clearance_moved =
      std::any_of(clearances.nodes.begin(), clearances.nodes.end(),
                  [](const contact::ClearedNode& c) { return c.distance > 0.0; });
  AdjustmentEffect effect;
  if (!report.adjusted.empty() || clearance_moved) {
    effect.dt_after = stable_increment(step);
    state.position.swap(as_read);
    effect.dt_before = stable_increment(step);
    state.position.swap(as_read);
  }
  if (!settings.adjust)
    sink.message(Severity::Info,
                 "step " + s.name +
                     (step == 0 ? ": the run starts from an imported state"
                                : ": contact is first defined in this step") +
                     ": initial penetrations become temporary offsets without force; no node "
                     "moves (C6)");
  if (!views.empty())
    report_clearances(clearances, view_names, *contact, model, step, diagnostics, sink);
  report_overclosures(report, *contact, model, step, diagnostics, effect, sink);
}

std::vector<contact::ClearanceView> ExplicitSolver::Impl::clearance_views(
    int step, std::vector<ClearanceViewNames>& names) const {
  std::vector<contact::ClearanceView> views;
  const Step& s = model.steps[step];
  if (!s.contact) return views;
  auto faces_of = [&](Index surface) {
    std::vector<contact::FaceRef> refs;
    for (const ElementFace& f : model.surfaces[surface].faces) refs.push_back({f.element, f.face});
    return refs;
  };
  const std::vector<ClearanceAssignment>& assignments = s.contact->clearances;
  for (std::size_t a = 0; a < assignments.size(); ++a) {
    const ClearanceAssignment& assignment = assignments[a];
    const ContactClearance& definition = model.contact_clearances[assignment.clearance];
    contact::ClearanceView view;
    view.assignment = static_cast<Index>(a);
    view.adjust = definition.adjust;
    view.value = definition.value;
    if (definition.distribution != NO_INDEX)
      view.nodal_values = model.distributions[definition.distribution].values;
    if (definition.search_above) view.search_above = *definition.search_above;
    if (definition.search_below) view.search_below = *definition.search_below;
    auto add = [&](Index slave, Index master) {
      contact::ClearanceView v = view;
      v.slave_surface = slave;
      v.master_surface = master;
      v.slave_faces = faces_of(slave);
      v.master_faces = faces_of(master);
      views.push_back(std::move(v));
      names.push_back({definition.name, model.surfaces[slave].name, model.surfaces[master].name});
    };
    // MASTER: surf1 is the master (only surf2's nodes move); SLAVE: surf1 is the slave.
    if (assignment.view != ClearanceAssignment::View::Master)
      add(assignment.first, assignment.second);
    if (assignment.view != ClearanceAssignment::View::Slave)
      add(assignment.second, assignment.first);
  }
  return views;
}

Real ExplicitSolver::Impl::stable_increment(int step) {
  ElementTotals totals;
  compute_forces(0.0, totals);
  force_internal.setZero();
  if (shell) moment_internal.setZero();
  return stable_step(totals, step);
}

void ExplicitSolver::Impl::apply_contact(Real dt_taken, Real dt_penalty) {
  if (!contact) return;
  const contact::ContactTotals t =
      contact->update(state.position, state.velocity_half, dt_taken, dt_penalty, node_thickness,
                      state.mass, inverse_mass, force_internal, timers);
  state.energies.friction += t.friction_dissipation;
  state.energies.contact += -t.work - t.friction_dissipation;
}

void ExplicitSolver::Impl::compute_forces(Real dt, ElementTotals& totals) {
  ScopedTimer timer(timers, Phase::InternalForce);
  const Step& s = model.steps[state.step];
  if (hex) {
    elements::HexStepTotals t;
    hex->internal_forces(state.position, state.velocity_half, dt, s.bulk_linear, s.bulk_quadratic,
                         force_internal, t);
    totals.add(t);
    totals.viscous_energy_increment += t.viscous_energy_increment;
  }
  if (shell) {
    elements::ShellStepTotals t;
    shell->internal_forces(state.position, state.velocity_half, state.angular_velocity_half, dt,
                           force_internal, moment_internal, t);
    totals.add(t);
  }
}

void ExplicitSolver::Impl::apply_loads(Real step_time, Real total_time) {
  if (loaded_dofs.empty()) return;
  // External forces are part of the nodal update: timed with it, so the phases add up.
  ScopedTimer timer(timers, Phase::Integration);
  if (force_external.rows() == 0) force_external = NodalVectors::Zero(model.node_count(), 3);
  for (const LoadedDof& l : loaded_dofs) force_external(l.node, l.component) = 0.0;
  for (const LoadedDof& l : boundary.loads())
    force_external(l.node, l.component) +=
        l.value * boundary.factor(model, l.amplitude, step_time, total_time);
  if (!pressures.empty())
    pressures.add_forces(model, boundary, state.position, step_time, total_time, force_external);
  if (!gravity.empty()) gravity.add_forces(model, boundary, step_time, total_time, force_external);
}

Real ExplicitSolver::Impl::stable_step(const ElementTotals& totals, int step) const {
  const Step& s = model.steps[step];
  return s.fixed_increment ? *s.fixed_increment
                           : totals.stable_dt * s.time_scale_factor * options.dt_safety;
}

Real ExplicitSolver::Impl::next_increment(const ElementTotals& totals, Real remaining,
                                          int step) const {
  Real dt = stable_step(totals, step);
  if (!std::isfinite(dt)) dt = remaining;  // no elements: one increment to the end
  // Land exactly on the end of the step; avoid a sliver increment just before it.
  if (dt >= remaining || remaining - dt < 1e-3 * dt) dt = remaining;
  return dt;
}

namespace {

/// The free central-difference update of nodes [first, last) of one field component block;
/// returns Σ m v². Accelerations are stored only where the field keeps them.
template <bool STORE_ACCELERATION>
Real update_range(const ExplicitSolver::DofPointers& d, Index off, Index first, Index last,
                  Real dt_avg, Real w_new) {
  Real* v = d.velocity_half + off;
  Real* vw = d.velocity + off;
  Real* a = STORE_ACCELERATION ? d.acceleration + off : nullptr;
  const Real* fi = d.force_internal + off;
  const Real* fe = d.force_external + off;
  const Real scale = d.external_scale;
  Real ke = 0.0;
#pragma omp simd reduction(+ : ke)
  for (Index i = first; i < last; ++i) {
    const Real acc = (scale * fe[i] - fi[i]) * d.inverse_mass[i];
    const Real v_new = v[i] + dt_avg * acc;
    const Real v_whole = v[i] + w_new * (v_new - v[i]);
    ke += d.mass[i] * v_whole * v_whole;
    if constexpr (STORE_ACCELERATION) a[i] = acc;
    v[i] = v_new;
    vw[i] = v_whole;
  }
  return ke;
}

}  // namespace

Real ExplicitSolver::Impl::free_update(const DofPointers& d, Real dt_avg, Real w_new, Real* sums) {
  const Index n = model.node_count();
  const Index n_chunks = (n + NODE_CHUNK - 1) / NODE_CHUNK;
#pragma omp parallel for schedule(static) if (n_chunks > 1)
  for (Index chunk = 0; chunk < n_chunks; ++chunk) {
    const Index first = chunk * NODE_CHUNK, last = std::min(n, first + NODE_CHUNK);
    Real ke = 0.0;
    for (int c = 0; c < 3; ++c)
      ke += d.acceleration ? update_range<true>(d, c * n, first, last, dt_avg, w_new)
                           : update_range<false>(d, c * n, first, last, dt_avg, w_new);
    sums[chunk] = 0.5 * ke;
  }
  Real ke = 0.0;
  for (Index chunk = 0; chunk < n_chunks; ++chunk) ke += sums[chunk];
  return ke;
}

void ExplicitSolver::Impl::update_nodes(Real dt_prev, Real dt_next, Real t_next_half,
                                        Real t_next_end) {
  ScopedTimer timer(timers, Phase::Integration);
  const Index n = model.node_count();
  const Real dt_avg = 0.5 * (dt_prev + dt_next);
  // At t = 0 the whole-step velocity is the initial velocity itself.
  const Real w_new = dt_prev > 0.0 ? 0.5 : 0.0;
  const Index n_chunks = (n + NODE_CHUNK - 1) / NODE_CHUNK;
  // No loads in the model: the external force array does not exist and is not read.
  const bool loaded = force_external.rows() > 0;
  DofPointers translation{state.velocity_half.data(),
                          state.velocity.data(),
                          state.acceleration.data(),
                          force_internal.data(),
                          loaded ? force_external.data() : force_internal.data(),
                          loaded ? 1.0 : 0.0,
                          inverse_mass.data(),
                          state.mass.data()};
  // Rotations carry no external moments.
  DofPointers rotation{};
  if (shell)
    rotation = {state.angular_velocity_half.data(),
                state.angular_velocity.data(),
                nullptr,
                moment_internal.data(),
                moment_internal.data(),
                0.0,
                inverse_inertia.data(),
                state.rotary_inertia.data()};

  // Prescribed and loaded DOFs keep their velocity at n-1/2 for the work and reaction terms.
  auto field_of = [&](int component) -> const DofPointers& {
    return component < 3 ? translation : rotation;
  };
  for (std::size_t k = 0; k < prescribed.size(); ++k) {
    const PrescribedDof& d = prescribed[k];
    v_old_prescribed[k] = field_of(d.component).velocity_half[(d.component % 3) * n + d.node];
  }
  for (std::size_t k = 0; k < free_loads.size(); ++k)
    v_old_loaded[k] = state.velocity_half(free_loads[k].node, free_loads[k].component);

  Real ke = free_update(translation, dt_avg, w_new, chunk_sums.data());
  if (shell) ke += free_update(rotation, dt_avg, w_new, chunk_sums.data() + n_chunks);
  Real work = 0.0;
  if (!rigid.empty())
    ke += rigid.update(
        model, boundary, state, force_internal, loaded ? &force_external : nullptr, dt_prev,
        dt_next, w_new,
        {state.step_time + 0.5 * dt_next, t_next_half, state.step_time + dt_next, t_next_end},
        work);

  // Prescribed DOFs: velocity from the BC, reaction = m a - (f_ext - f_int).
  // External work by the trapezoidal rule over [t_{n-1}, t_n]: exact for constant forces.
  Real ke_fix = 0.0;
  const Real step_next_half = state.step_time + 0.5 * dt_next;
  const Real step_next_end = state.step_time + dt_next;
  for (std::size_t k = 0; k < prescribed.size(); ++k) {
    const PrescribedDof& d = prescribed[k];
    const bool turn = d.component >= 3;
    const int c = d.component % 3;
    const DofPointers& field = field_of(d.component);
    const Index i = d.node, at = c * n + i;
    const Real v_old = v_old_prescribed[k];
    Real v_new = 0.0;
    if (d.type == BoundaryType::Velocity) {
      v_new = boundary.target(model, d, step_next_half, t_next_half);
    } else {
      // Translations correct against the actual position; rotations against the prescribed
      // value carried along (components of the rotation vector, exact about a fixed axis).
      Real& current = prescribed_value[k];
      current = turn ? current + dt_prev * v_old : state.displacement(i, c);
      if (dt_next > 0.0)
        v_new = (boundary.target(model, d, step_next_end, t_next_end) - current) / dt_next;
    }
    const Real m = field.mass[i];
    const Real wrong = field.velocity[at];  // what the free update counted
    const Real right = v_old + w_new * (v_new - v_old);
    ke_fix += 0.5 * m * (right * right - wrong * wrong);
    const Real acc = dt_avg > 0.0 ? (v_new - v_old) / dt_avg : 0.0;
    const Real f_ext = field.external_scale * field.force_external[at];
    const Real r = m * acc - (f_ext - field.force_internal[at]);
    (turn ? state.reaction_moment : state.reaction)(i, c) = r;
    if (field.acceleration) field.acceleration[at] = acc;
    field.velocity_half[at] = v_new;
    field.velocity[at] = right;
    const Real f_now = f_ext + r;
    Real& f_before = (turn ? previous_moment : previous_force)(i, c);
    work += 0.5 * (f_before + f_now) * dt_prev * v_old;
    f_before = f_now;
  }
  for (std::size_t k = 0; k < free_loads.size(); ++k) {
    const Index i = free_loads[k].node;
    const int c = free_loads[k].component;
    const Real f_now = force_external(i, c);
    work += 0.5 * (previous_force(i, c) + f_now) * dt_prev * v_old_loaded[k];
    previous_force(i, c) = f_now;
  }
  state.energies.kinetic = ke + ke_fix;
  state.energies.external_work += work;
  force_internal.setZero();
  if (shell) moment_internal.setZero();
}

void ExplicitSolver::Impl::write_frame(const FrameRequest& what) {
  ScopedTimer timer(timers, Phase::Output);
  const auto n_elements = static_cast<std::size_t>(model.element_count());
  if (what.stress || what.volume || what.thickness) {
    // Element output arrays exist only in runs that write element output (P2).
    state.stress.resize(n_elements * 6, 0.0);
    state.volume.resize(n_elements, 0.0);
    if (hex) hex->gather_output(state.stress, state.volume);
    if (shell) {
      const Real nan = std::numeric_limits<Real>::quiet_NaN();
      state.stress_bottom.resize(n_elements * 6, nan);
      state.stress_top.resize(n_elements * 6, nan);
      state.thickness.resize(n_elements, nan);
      shell->gather_output(state.position, state.stress, state.stress_bottom, state.stress_top,
                           state.thickness);
    }
  }
  if (what.contact_stress || what.contact_status || what.contact_force) fill_contact_output();
  sync_rotation();
  sink.write_frame(model, state, what);
}

void ExplicitSolver::Impl::fill_contact_output() {
  const Index n = model.node_count();
  state.contact_pressure.assign(n, 0.0);
  state.contact_status.assign(n, 0.0);
  state.contact_shear = NodalVectors::Zero(n, 3);
  state.contact_normal_force = NodalVectors::Zero(n, 3);
  state.contact_shear_force = NodalVectors::Zero(n, 3);
  if (!contact) return;
  const contact::SlaveNodes& slaves = contact->domain().slaves();
  for (Index s = 0; s < slaves.size(); ++s) {
    const contact::Vec3 f = contact->nodal_force(s);
    if (f.dot(f) == 0.0) continue;
    const Index i = slaves.nodes()[s];
    const contact::Vec3 normal = slaves.normal(s);
    const Real along = f.dot(normal);
    const contact::Vec3 fn = along * normal, ft = f - fn;
    const Real area = slaves.areas()[s];
    const bool shell_node = contact->domain().slave_double_sided(s);
    const Real pressure = shell_node ? std::abs(along) : -along;
    if (area > 0.0) state.contact_pressure[i] = pressure / area;
    const auto own = contact->output_status(s);
    state.contact_status[i] =
        own == contact::OutputStatus::Open ? 1.0 : static_cast<Real>(static_cast<int>(own));
    for (int c = 0; c < 3; ++c) {
      if (area > 0.0) state.contact_shear(i, c) = ft[c] / area;
      state.contact_normal_force(i, c) = fn[c];
      state.contact_shear_force(i, c) = ft[c];
    }
  }
}

void ExplicitSolver::Impl::sync_rotation() {
  if (!shell || rotation_synced) return;
  rotations.rotation_vectors(state.rotation);
  rotation_synced = true;
}

void ExplicitSolver::Impl::write_history() {
  ScopedTimer timer(timers, Phase::Output);
  sync_rotation();
  schedule.history_row(state, history_row);
  if (contact) {
    for (std::size_t k = 0; k < contact_pair_names.size(); ++k) {
      history_row.push_back(contact->pair_normal_force()[k]);
      history_row.push_back(contact->pair_friction_force()[k]);
    }
  }
  sink.append_history(state.time, history_row);
}

void ExplicitSolver::Impl::write_status() {
  ScopedTimer timer(timers, Phase::Output);
  StatusLine line;
  line.increment = state.increment;
  line.step_time = state.step_time;
  line.total_time = state.time;
  line.dt = dt_half;
  line.critical_element = critical_id;
  line.energies = state.energies;
  sink.status(line);
}

void ExplicitSolver::Impl::check_health(const ElementTotals& totals) {
  if (totals.failed_element != NO_INDEX) {
    const ExternalId id = model.element_ids[totals.failed_element];
    throw SolverError(
        "NaN/instability at increment " + std::to_string(state.increment) + ", element " +
            std::to_string(id) +
            ": non-positive or undefined volume or area (element inverted or collapsed)",
        id, state.increment, state.time);
  }
  const Energies& e = state.energies;
  if (!std::isfinite(e.kinetic) || !std::isfinite(e.total())) {
    throw SolverError("NaN/instability at increment " + std::to_string(state.increment) +
                          ", element " + std::to_string(critical_id) + ": energy is not finite",
                      critical_id, state.increment, state.time);
  }
  max_energy = std::max({max_energy, e.kinetic, e.internal(), std::abs(e.external_work)});
  const Real drift = std::abs(e.total() - initial_total);
  // The first increments of a step are skipped: a prescribed motion that starts from rest
  // leaves an O(Δt) mismatch between the work and the kinetic energy that is of the order of
  // these tiny energies themselves; a true instability keeps growing and is caught later.
  const bool settled = state.increment - step_first_increment >= BALANCE_WARMUP;
  if (settled && max_energy > 0.0 && drift > 0.5 * max_energy && drift > 1e-12) {
    throw SolverError("NaN/instability at increment " + std::to_string(state.increment) +
                          ", element " + std::to_string(critical_id) +
                          ": energy balance lost (ETOTAL drift " + format_real(drift) +
                          " J against energies up to " + format_real(max_energy) + " J)",
                      critical_id, state.increment, state.time);
  }
  if (dt_half < options.dt_floor_ratio * dt_first && !model.steps[state.step].fixed_increment) {
    throw SolverError("NaN/instability at increment " + std::to_string(state.increment) +
                          ", element " + std::to_string(critical_id) +
                          ": stable increment collapsed to " + format_real(dt_half) + " s",
                      critical_id, state.increment, state.time);
  }
}

void ExplicitSolver::Impl::run_step(int step) {
  begin_step(step);
  step_first_increment = state.increment;
  const Real period = model.steps[step].time_period;
  const Real step_start = state.time;
  ElementTotals totals;

  if (!started) {
    // t = 0: forces on the initial geometry, first increment, half-step velocity.
    compute_forces(0.0, totals);
    state.energies.strain += totals.strain_energy_increment;
    apply_loads(0.0, 0.0);
    dt_half = next_increment(totals, period, step);
    // The penalty is tied to the increment the elements allow, not to one shortened to land
    // on the end of a step: a short last increment must not stiffen the springs.
    const Real dt_stable = stable_step(totals, step);
    apply_contact(0.0, std::isfinite(dt_stable) ? dt_stable : dt_half);
    dt_first = dt_half;
    critical_id =
        totals.critical_element != NO_INDEX ? model.element_ids[totals.critical_element] : 0;
    update_nodes(0.0, dt_half, 0.5 * dt_half, dt_half);
    initial_total = state.energies.total();
    started = true;
    if (schedule.has_field()) write_frame(schedule.field_all());
  } else {
    dt_half = std::min(dt_half, period);
  }
  if (schedule.has_history()) write_history();
  write_status();

  const auto loop_start = std::chrono::steady_clock::now();
  Real next_status = 0.01 * period;
  while (state.step_time < period) {
    // x_{n+1} = x_n + dt_{n+1/2} v_{n+1/2}.
    {
      ScopedTimer timer(timers, Phase::Integration);
      state.position += dt_half * state.velocity_half;
      if (shell) {
        rotations.advance(state.angular_velocity_half, dt_half);
        rotation_synced = false;
      }
    }
    const Real dt_prev = dt_half;
    state.time += dt_prev;
    state.step_time = state.time - step_start;
    const bool last = state.step_time >= period * (1.0 - 1e-12);
    if (last) state.step_time = period;
    ++state.increment;
    state.dt = dt_prev;

    totals = ElementTotals{};
    compute_forces(dt_prev, totals);
    state.energies.strain += totals.strain_energy_increment;
    state.energies.artificial += totals.hourglass_energy_increment;
    state.energies.viscous += totals.viscous_energy_increment;
    if (totals.critical_element != NO_INDEX)
      critical_id = model.element_ids[totals.critical_element];
    apply_loads(state.step_time, state.time);
    const Real dt_stable = stable_step(totals, step);
    apply_contact(dt_prev, std::isfinite(dt_stable) ? dt_stable : dt_prev);

    dt_half = last ? dt_prev : next_increment(totals, period - state.step_time, step);
    update_nodes(dt_prev, dt_half, state.time + 0.5 * dt_half, state.time + dt_half);
    check_health(totals);

    const FrameRequest frame = schedule.field_due(state.step_time, last);
    if (frame.any()) write_frame(frame);
    if (schedule.has_history() && schedule.history_due(state.step_time, last)) write_history();
    if (state.step_time >= next_status || last) {
      write_status();
      next_status = (std::floor(state.step_time / (0.01 * period)) + 1.0) * 0.01 * period;
    }
    if (last) break;
  }
  loop_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - loop_start).count();
}

RunSummary ExplicitSolver::Impl::summary() const {
  RunSummary s;
  s.increments = state.increment;
  s.final_time = state.time;
  const double elements = (hex ? hex->size() : 0) + (shell ? shell->size() : 0);
  const double cycles = elements * state.increment;
  s.element_cycles_per_second = loop_seconds > 0.0 ? cycles / loop_seconds : 0.0;
  s.timers = timers;
  s.energies = state.energies;
  return s;
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

ExplicitSolver::ExplicitSolver(const Model& model, OutputSink& sink, SolverOptions options)
    : m_impl(std::make_unique<Impl>(model, sink, options)) {
  m_impl->setup();
}

ExplicitSolver::~ExplicitSolver() = default;

const State& ExplicitSolver::state() const {
  return m_impl->state;
}

RunSummary ExplicitSolver::run() {
  Impl& s = *m_impl;
  try {
    for (int step = 0; step < static_cast<int>(s.model.steps.size()); ++step) s.run_step(step);
  } catch (const SolverError& e) {
    // end_run records the error in every log; no separate message (it would repeat).
    const RunSummary summary = s.summary();
    s.sink.end_run(RunStatus::Failed, e.what(), summary.timers, summary.element_cycles_per_second);
    throw;
  }
  const RunSummary summary = s.summary();
  s.sink.end_run(RunStatus::Completed, "", summary.timers, summary.element_cycles_per_second);
  return summary;
}

RunSummary ExplicitSolver::check() {
  Impl& s = *m_impl;
  if (!s.model.steps.empty()) {
    s.begin_step(0);
    ElementTotals totals;
    s.compute_forces(0.0, totals);
    s.force_internal.setZero();
    if (s.shell) s.moment_internal.setZero();
    s.dt_half = s.next_increment(totals, s.model.steps[0].time_period, 0);
    if (totals.critical_element != NO_INDEX)
      s.critical_id = s.model.element_ids[totals.critical_element];
    s.sink.message(Severity::Info, "initial stable increment " + format_real(s.dt_half) +
                                       " s (element " + std::to_string(s.critical_id) + ")");
    Real kinetic = 0.0;
    for (Index i = 0; i < s.model.node_count(); ++i)
      for (int c = 0; c < 3; ++c)
        kinetic += 0.5 * s.state.mass[i] * s.state.velocity(i, c) * s.state.velocity(i, c);
    s.state.energies.kinetic = kinetic;
    FrameRequest all;
    all.displacement = all.velocity = all.acceleration = all.reaction = all.stress = true;
    s.write_frame(all);
    s.write_status();
  }
  const RunSummary summary = s.summary();
  s.sink.end_run(RunStatus::Checked, "", summary.timers, 0.0);
  return summary;
}

}  // namespace xpl

#include "solver/forces/contact_stage.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "contact/initial_overclosure.hpp"
#include "solver/distributed_run.hpp"
#include "solver/message_text.hpp"
#include "solver/output/output_variables.hpp"

namespace xpl {

ContactStage::ContactStage(const Model& model, OutputSink& sink, PhaseTimers& timers,
                           const IncrementControl& control, bool imported_start)
    : m_model(model),
      m_sink(sink),
      m_timers(timers),
      m_control(control),
      m_imported_start(imported_start),
      m_penalty(model, sink, control) {}

void ContactStage::begin_step(int step, State& state, ElementSet& elements,
                              const RigidBodies& rigid,
                              const std::vector<PrescribedDof>& prescribed) {
  // The masses contact reads for tie slaves (set_tie_slaves()): the nodal masses are set once,
  // at set-up (elements, point masses, ties, rigid bodies), so once a step is enough.
  if (!m_tie_slaves.empty()) contact_masses(elements.inverse_mass(), state.mass);
  // The definition in force: the latest *CONTACT up to this step, and every *CONTACT PAIR.
  const Step& s = m_model.steps[step];
  const bool changed = step == 0 || s.contact || !s.contact_pairs.empty();
  if (!changed) {
    set_rigid_bodies(rigid);
    return;
  }
  std::unique_ptr<contact::ContactEngine> previous = std::move(m_engine);
  // Distributed runs after t = 0: a rank's rows of the nodes it does not integrate are
  // stale; the engine is built on the run's positions of every node (once per such step).
  const bool gathered = m_run != nullptr && step > 0 && defines_contact(step);
  if (gathered) {
    std::vector<Index> all(static_cast<std::size_t>(m_model.node_count()));
    for (Index i = 0; i < m_model.node_count(); ++i) all[i] = i;
    m_position = state.position;
    m_run->share_rows(all, {&state.position}, {&m_position});
    state.position.swap(m_position);
  }
  m_engine = build_engine(step, state.position, elements, rigid);
  if (!m_engine) {
    if (gathered) state.position.swap(m_position);
    return;
  }
  const std::size_t n_faces = m_engine->domain().faces().size();
  const Index n_slaves = m_engine->domain().slaves().size();
  m_sink.message(Severity::Info, "step " + s.name + ": contact domain of " +
                                     std::to_string(n_faces) + " faces and " +
                                     std::to_string(n_slaves) + " slave nodes, search margin " +
                                     format_real(m_engine->broad_phase().margin()) + " m");
  set_rigid_bodies(rigid);
  resolve_overclosures(step, previous.get(), state, elements, rigid, prescribed);
  if (gathered) state.position.swap(m_position);
  if (m_run != nullptr) {
    m_shared_nodes = m_engine->domain().slaves().nodes();
    std::sort(m_shared_nodes.begin(), m_shared_nodes.end());
    m_shared_nodes.erase(std::unique(m_shared_nodes.begin(), m_shared_nodes.end()),
                         m_shared_nodes.end());
    m_position = state.position;
    m_velocity = state.velocity_half;
    share_slots();
    m_rows_shared = m_shared && m_run->size() > 1;
    if (m_rows_shared)
      m_rows.reset(*m_run, *m_engine, m_shared_nodes, m_model.node_count(), m_root_writes);
  }
}

void ContactStage::resolve_overclosures(int step, const contact::ContactEngine* previous,
                                        State& state, ElementSet& elements,
                                        const RigidBodies& rigid,
                                        const std::vector<PrescribedDof>& prescribed) {
  const Step& s = m_model.steps[step];
  if (previous != nullptr) {
    contact::carry_offsets(*previous, *m_engine);
    m_sink.message(Severity::Note,
                   "step " + s.name +
                       ": the contact domain changes; slave nodes of the earlier domain keep "
                       "their contact offsets, new interactions get plain penalty forces from the "
                       "first increment (no adjustment, no overclosure or crossed-surface "
                       "diagnostics for them, as Abaqus/Explicit)");
    return;
  }
  const Diagnostics& diagnostics = m_model.diagnostics_of(step);
  contact::OverclosureSettings settings;
  settings.adjust = step == 0 && !m_imported_start;
  settings.offset_reason =
      step == 0 ? contact::OffsetReason::Import : contact::OffsetReason::LaterStep;
  settings.detect_crossed = diagnostics.detect_crossed_surfaces;
  const Index n = m_model.node_count();
  std::vector<std::uint8_t> lock(static_cast<std::size_t>(n), 0);
  for (const PrescribedDof& d : prescribed)
    if (d.component < 3) lock[d.node] |= static_cast<std::uint8_t>(1u << d.component);
  for (Index i = 0; i < n; ++i)
    if (rigid.is_rigid_node(i)) lock[i] |= contact::LOCK_RIGID;
  if (!m_tied.empty())
    for (Index i = 0; i < n; ++i)
      if (m_tied[i] != 0) lock[i] |= contact::LOCK_TIE;
  NodalVectors as_read;
  if (settings.adjust) as_read = state.position;
  const contact::ElementTopology topology{m_model.element_offsets, m_model.element_nodes,
                                          elements.element_kinds()};
  // Clearances first (C7–C10); the automatic pass then leaves their nodes alone.
  std::vector<ClearanceViewNames> view_names;
  const std::vector<contact::ClearanceView> views = clearance_views(step, view_names);
  contact::ClearanceReport clearances;
  contact::OverclosureReport report;
  {
    ScopedTimer timer(m_timers, Phase::ContactSearch);
    if (!views.empty()) {
      clearances =
          contact::apply_clearances(*m_engine, topology, state.position, elements.node_thickness(),
                                    lock, views, settings.adjust);
      settings.exclude = clearances.handled;
    }
    report = contact::resolve_initial_overclosures(*m_engine, topology, state.position,
                                                   elements.node_thickness(), lock, settings);
  }
  const bool clearance_moved =
      std::any_of(clearances.nodes.begin(), clearances.nodes.end(),
                  [](const contact::ClearedNode& c) { return c.distance > 0.0; });
  AdjustmentEffect effect;
  if (!report.adjusted.empty() || clearance_moved) {
    effect.dt_after = m_control.elements(step, elements.increment_estimate(state)).dt;
    state.position.swap(as_read);
    effect.dt_before = m_control.elements(step, elements.increment_estimate(state)).dt;
    state.position.swap(as_read);
  }
  if (!settings.adjust)
    m_sink.message(Severity::Info,
                   "step " + s.name +
                       (step == 0 ? ": the run starts from an imported state"
                                  : ": contact is first defined in this step") +
                       ": initial penetrations become temporary offsets without force; no node "
                       "moves (C6)");
  if (!views.empty())
    report_clearances(clearances, view_names, *m_engine, m_model, step, diagnostics, m_sink);
  // A tie slave and a master corner it is bound to are joined (Ties::slave_points()).
  std::vector<Index> point_of;
  if (!m_tie_slaves.empty() && !report.ignored.empty()) {
    point_of.assign(static_cast<std::size_t>(m_model.node_count()), NO_INDEX);
    for (std::size_t k = 0; k < m_tie_slaves.size(); ++k)
      point_of[m_tie_slaves[k].slave] = static_cast<Index>(k);
  }
  const auto bound = [&](Index slave, Index corner) {
    const Index k = point_of[slave];
    if (k == NO_INDEX) return false;
    const auto& corners = m_tie_slaves[k].corner;
    return std::find(corners.begin(), corners.end(), corner) != corners.end();
  };
  const auto tie_joined = [&](Index node, Index face) {
    if (point_of.empty()) return false;
    for (const Index c : m_engine->domain().faces()[face].nodes)
      if (c != NO_INDEX && (bound(node, c) || bound(c, node))) return true;
    return false;
  };
  report_overclosures(report, *m_engine, m_model, step, diagnostics, effect, m_sink, tie_joined);
}

std::vector<contact::ClearanceView> ContactStage::clearance_views(
    int step, std::vector<ClearanceViewNames>& names) const {
  std::vector<contact::ClearanceView> views;
  const Step& s = m_model.steps[step];
  if (!s.contact) return views;
  auto faces_of = [&](Index surface) {
    std::vector<contact::FaceRef> refs;
    for (const ElementFace& f : m_model.surfaces[surface].faces)
      refs.push_back({f.element, f.face});
    return refs;
  };
  const std::vector<ClearanceAssignment>& assignments = s.contact->clearances;
  for (std::size_t a = 0; a < assignments.size(); ++a) {
    const ClearanceAssignment& assignment = assignments[a];
    const ContactClearance& definition = m_model.contact_clearances[assignment.clearance];
    contact::ClearanceView view;
    view.assignment = static_cast<Index>(a);
    view.adjust = definition.adjust;
    view.value = definition.value;
    if (definition.distribution != NO_INDEX)
      view.nodal_values = m_model.distributions[definition.distribution].values;
    if (definition.search_above) view.search_above = *definition.search_above;
    if (definition.search_below) view.search_below = *definition.search_below;
    view.interference = definition.interference;
    if (definition.interference_distance)
      view.interference_distance = *definition.interference_distance;
    view.ramp_time = definition.step_fraction * s.time_period;
    auto add = [&](Index slave, Index master) {
      // A node-based surface has no faces to be a master (SPEC C13): of its pair only the view
      // with its nodes as the slaves exists (the deck reader refuses a view word against it).
      if (m_model.surfaces[master].type == Surface::Type::Node) return;
      contact::ClearanceView v = view;
      v.slave_surface = slave;
      v.master_surface = master;
      v.slave_faces = faces_of(slave);
      v.slave_nodes = m_model.surfaces[slave].nodes;
      v.master_faces = faces_of(master);
      views.push_back(std::move(v));
      names.push_back({definition.name, m_model.surfaces[slave].name, m_model.surfaces[master].name,
                       definition.initialization, definition.interference,
                       definition.step_fraction});
    };
    // MASTER: surf1 is the master (only surf2's nodes move); SLAVE: surf1 is the slave.
    if (assignment.view != ClearanceAssignment::View::Master)
      add(assignment.first, assignment.second);
    if (assignment.view != ClearanceAssignment::View::Slave)
      add(assignment.second, assignment.first);
  }
  return views;
}

void ContactStage::set_rigid_bodies(const RigidBodies& rigid) {
  if (m_engine && !rigid.empty())
    m_engine->set_rigid_bodies(rigid.node_body(), rigid.translation_mass());
}

void ContactStage::apply(State& state, ElementSet& elements, Real dt_taken, Real dt_penalty) {
  m_stored_energy = 0.0;
  if (!m_engine) return;
  if (m_engine->interference_ramping()) m_engine->set_step_time(state.step_time);
  if (m_rows_shared) {
    if (m_rows.gather(*m_engine, state, m_position, m_velocity)) {
      // The ranks' build of the broad phase on ghost faces: search time, as the engine's own
      // builds (update() then builds nothing).
      ScopedTimer timer(m_timers, Phase::ContactSearch);
      m_rows.build_ghosts(*m_engine, state, elements.node_thickness(), m_position, m_velocity);
    }
  } else if (m_run != nullptr)
    m_run->share_rows(m_shared_nodes, {&state.position, &state.velocity_half},
                      {&m_position, &m_velocity});
  const bool tied = !m_tie_slaves.empty();
  const contact::ContactTotals t = m_engine->update(
      m_run != nullptr ? m_position : state.position,
      m_run != nullptr ? m_velocity : state.velocity_half, dt_taken, dt_penalty,
      elements.node_thickness(), tied ? m_contact_mass : state.mass,
      tied ? m_contact_inverse : elements.inverse_mass(), elements.force_internal(), m_timers);
  if (m_rows_shared) m_rows.update_lists(*m_engine, t.rebuilt);
  state.energies.friction += t.friction_dissipation;
  // The interference ramp's energy is an input, as the work of a load: in ALLWK, and in
  // ALLPW, which then holds what the springs hold (ContactEnergyCheck).
  state.energies.contact += -t.work - t.friction_dissipation + t.interference_work;
  state.energies.external_work += t.interference_work;
  m_stored_energy = t.stored_energy;
  if (t.passed > 0) {
    // A result with bodies passed through each other is wrong however balanced: the run ends.
    const ExternalId element = m_model.element_ids[t.passed_element];
    throw SolverError(
        "contact lost at increment " + std::to_string(state.increment) + ", element " +
            std::to_string(element) + ": node " + std::to_string(m_model.node_ids[t.passed_node]) +
            " passed through the shell of element " + std::to_string(element) +
            ": pressed on one side of it last increment, it is now " + format_real(t.passed_depth) +
            " m behind its mid-surface" +
            (t.passed > 1 ? " (with " + std::to_string(t.passed - 1) + " more nodes)" : "") +
            ". The penalty could not stop it within half the shell's thickness: refine the "
            "mesh where it hits (a corner or edge pressing between a coarse shell's nodes), "
            "raise the penalty scale factor (*CONTACT CONTROLS ASSIGNMENT), or lower the time "
            "scale factor",
        element, state.increment, state.time);
  }
  if (t.behind > 0) {
    if (m_behind_increments == 0) {
      const std::string element = std::to_string(m_model.element_ids[t.behind_element]);
      const std::string more =
          t.behind > 1 ? " (with " + std::to_string(t.behind - 1) + " more nodes)" : "";
      const std::string where =
          t.behind_element_depth > 0.0
              ? " m into the solid behind the face of element " + element +
                    " it is pressed on, more than half that element's depth (" +
                    format_real(t.behind_element_depth) + " m)" + more +
                    ": the bodies overlap by more than the mesh resolves, and the results "
                    "there are not to be trusted."
              : " m behind the mid-surface of the shell of element " + element +
                    " it is pressed on, deeper than half its thickness" + more +
                    ": the bodies overlap by more than the shell and may pass through.";
      m_sink.message(Severity::Warning,
                     "increment " + std::to_string(state.increment) +
                         ", t = " + format_real(state.time) + " s: contact too soft: node " +
                         std::to_string(m_model.node_ids[t.behind_node]) + " is " +
                         format_real(t.behind_depth) + where +
                         " Refine the mesh where it hits, raise the penalty scale factor "
                         "(*CONTACT CONTROLS ASSIGNMENT), or lower the time scale factor");
    }
    ++m_behind_increments;
    m_behind_deepest = std::max(m_behind_deepest, t.behind_depth);
  }
  if (t.lost == 0) return;
  if (m_lost == 0)
    m_sink.message(
        Severity::Warning,
        "increment " + std::to_string(state.increment) + ", t = " + format_real(state.time) +
            " s: contact lost at speed: node " + std::to_string(m_model.node_ids[t.lost_node]) +
            " went " + format_real(t.lost_depth) + " m behind the face of element " +
            std::to_string(m_model.element_ids[t.lost_element]) +
            ", deeper than the element behind it (" + format_real(t.lost_element_depth) +
            " m), and was released inside it" +
            (t.lost > 1 ? " (with " + std::to_string(t.lost - 1) + " more nodes)" : "") +
            ": the bodies may pass through each other. The penalty stops a node within about "
            "v*dt of its approach: refine the mesh where it hits, or lower the time scale "
            "factor" +
            (m_engine->options().penalty_scale < contact::DEFAULT_PENALTY_SCALE
                 ? ", or raise the penalty scale factor (" +
                       format_real(m_engine->options().penalty_scale) + ", below the default " +
                       format_real(contact::DEFAULT_PENALTY_SCALE) + ")"
                 : std::string()));
  m_lost += t.lost;
  ++m_lost_increments;
}

void ContactStage::end_step() {
  m_penalty.end_span();
  if (m_lost > 1)
    m_sink.message(Severity::Warning,
                   "contact lost at speed: " + std::to_string(m_lost) + " releases of nodes " +
                       "deeper than the element behind their face, in " +
                       std::to_string(m_lost_increments) + " increments of the step");
  m_lost = 0;
  m_lost_increments = 0;
  if (m_behind_increments > 1)
    m_sink.message(Severity::Warning,
                   "contact too soft: nodes behind the mid-surface of the shell they are pressed "
                   "on, or deeper than half the solid element behind their face, in " +
                       std::to_string(m_behind_increments) +
                       " increments of the step, the deepest " + format_real(m_behind_deepest) +
                       " m");
  m_behind_increments = 0;
  m_behind_deepest = 0.0;
}

ContactIncrement ContactStage::penalty_increment(const ElementIncrement& elements, int step,
                                                 const State& state) {
  const contact::PenaltyLimit none;
  return m_penalty.apply(m_engine ? m_engine->penalty_limit() : none, elements, step, state.time,
                         state.increment);
}

void ContactStage::set_tie_slaves(std::vector<Ties::SlavePoint> points) {
  m_tie_slaves = std::move(points);
  m_tie_corner_weight.assign(static_cast<std::size_t>(m_model.node_count()), 0.0);
  for (const Ties::SlavePoint& p : m_tie_slaves)
    for (int k = 0; k < 4; ++k)
      if (p.corner[k] != NO_INDEX) m_tie_corner_weight[p.corner[k]] += std::max(0.0, p.weight[k]);
}

void ContactStage::contact_masses(const std::vector<Real>& inverse_mass,
                                  const std::vector<Real>& mass) {
  m_contact_inverse = inverse_mass;
  m_contact_mass = mass;
  for (const Ties::SlavePoint& p : m_tie_slaves) {
    // m* = Σ_I N_I (N_I m_I / W_I): each corner's mass shared among the slaves bound to it in
    // proportion to their weights (W_I = Σ N_I over them).
    Real share = 0.0;
    bool rigid = false;
    for (int k = 0; k < 4; ++k) {
      const Index c = p.corner[k];
      const Real n = c != NO_INDEX ? std::max(0.0, p.weight[k]) : 0.0;
      if (!(n > 0.0)) continue;
      if (!(inverse_mass[c] > 0.0)) {
        rigid = true;
        break;
      }
      share += n * n / (inverse_mass[c] * m_tie_corner_weight[c]);
    }
    m_contact_inverse[p.slave] = rigid || !(share > 0.0) ? 0.0 : 1.0 / share;
    m_contact_mass[p.slave] = rigid ? contact::RIGID_MASS : share;
  }
}

void ContactStage::check_penalty(const ElementIncrement& elements, int step,
                                 const std::vector<Real>& inverse_mass) const {
  if (!m_engine) return;
  // With ties, the tie slaves' masses begin_step() made (from the same inverse masses).
  const contact::PenaltyLimit limit =
      m_engine->estimate_penalty_limit(m_tie_slaves.empty() ? inverse_mass : m_contact_inverse);
  const Step& s = m_model.steps[step];
  if (s.increment.fixed || !(limit.omega_sq > 0.0)) return;
  const Real dt_elements = elements.dt;
  const Real dt =
      contact_increment(elements.raw_dt, dt_elements, s.increment.scale_factor, limit.omega_sq);
  if (!(dt < dt_elements)) return;
  const SurfaceInteraction& i = m_model.surface_interactions[limit.interaction];
  // ω_c² grows with the slope; the springs stop governing at ω_c²Δt_e² = B·s².
  const Real threshold = i.linear_slope * contact::PENALTY_INCREMENT_BUDGET *
                         s.increment.scale_factor * s.increment.scale_factor /
                         (limit.omega_sq * dt_elements * dt_elements);
  m_sink.message(Severity::Warning,
                 "step " + s.name + ": the penalty of interaction " + i.name +
                     " (PRESSURE-OVERCLOSURE=LINEAR, slope " + format_real(i.linear_slope) +
                     " Pa/m) will govern the stable increment while in contact: about " +
                     format_real(dt) + " s against the elements' " + format_real(dt_elements) +
                     " s (x" + format_real(dt / dt_elements) + ", stiffest at node " +
                     std::to_string(m_model.node_ids[limit.node]) + "); a slope up to " +
                     format_real(threshold) + " Pa/m would not");
}

void ContactStage::fill_output(FrameFields& frame) const {
  const Index n = m_model.node_count();
  frame.contact_pressure.assign(n, 0.0);
  frame.contact_status.assign(n, 0.0);
  frame.contact_shear = NodalVectors::Zero(n, 3);
  frame.contact_normal_force = NodalVectors::Zero(n, 3);
  frame.contact_shear_force = NodalVectors::Zero(n, 3);
  if (!m_engine) return;
  const contact::SlaveNodes& slaves = m_engine->domain().slaves();
  for (Index s = 0; s < slaves.size(); ++s) {
    const contact::Vec3 f = m_engine->nodal_force(s);
    if (f.dot(f) == 0.0) continue;
    const Index i = slaves.nodes()[s];
    // A point node (node-based surface) has no normal of its own: the contact normal of its
    // touch, which points out of the master face (read as for a double-sided node).
    const bool point = m_engine->domain().slave_point(s);
    const contact::Vec3 normal =
        point ? std::as_const(*m_engine).constraints()[s].normal : slaves.normal(s);
    const Real along = f.dot(normal);
    const contact::Vec3 fn = along * normal, ft = f - fn;
    const Real area = slaves.areas()[s];
    const bool shell_node = point || m_engine->domain().slave_double_sided(s);
    const Real pressure = shell_node ? std::abs(along) : -along;
    if (area > 0.0) frame.contact_pressure[i] = pressure / area;
    const auto own = m_engine->output_status(s);
    frame.contact_status[i] =
        own == contact::OutputStatus::Open ? 1.0 : static_cast<Real>(static_cast<int>(own));
    for (int c = 0; c < 3; ++c) {
      if (area > 0.0) frame.contact_shear(i, c) = ft[c] / area;
      frame.contact_normal_force(i, c) = fn[c];
      frame.contact_shear_force(i, c) = ft[c];
    }
  }
}

void ContactStage::add_history_series(std::vector<HistorySeries>& series) const {
  if (!m_engine) return;
  // Columns in the table's order (CFN, CFS), as add_history_values appends them.
  for (const std::string& name : m_pair_names) append_contact_pair_series(series, name);
}

void ContactStage::add_history_values(std::vector<Real>& row) const {
  if (!m_engine) return;
  for (std::size_t k = 0; k < m_pair_names.size(); ++k) {
    row.push_back(m_engine->pair_normal_force()[k]);
    row.push_back(m_engine->pair_friction_force()[k]);
  }
}

}  // namespace xpl

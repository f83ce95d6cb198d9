#include "solver/element_set.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "solver/loads/gravity_loads.hpp"
#include "solver/mass_scaling.hpp"
#include "solver/message_text.hpp"

namespace xpl {

namespace {

/// `mass_factor`: the element's *FIXED MASS SCALING factor (1: none), applied to the density.
elements::HexMaterial hex_material(const Model& model, Index element, Real mass_factor) {
  const SolidSection& section = model.solid_sections[model.element_section[element]];
  const Material& m = model.materials[section.material];
  elements::HexMaterial h;
  h.density = m.density * mass_factor;
  h.young = m.young;
  h.poisson = m.poisson;
  if (m.plastic) h.plastic = &*m.plastic;
  // The enhanced form unless HOURGLASS= asks for STIFFNESS, RELAX STIFFNESS (run as
  // STIFFNESS) or VISCOUS (R5: the default stabilisation is physical).
  h.hourglass = elements::HourglassForm::Enhanced;
  if (section.controls != NO_INDEX) {
    const SectionControls& c = model.section_controls[section.controls];
    if (c.hourglass_given && c.hourglass == HourglassType::Viscous)
      h.hourglass = elements::HourglassForm::Viscous;
    else if (c.hourglass_given && c.hourglass != HourglassType::Enhanced)
      h.hourglass = elements::HourglassForm::Stiffness;
    h.hourglass_scale =
        h.hourglass == elements::HourglassForm::Viscous ? c.viscous_scale : c.stiffness_scale;
  }
  return h;
}

elements::ShellProperties shell_properties(const Model& model, Index element, Real mass_factor) {
  const ShellSection& section = model.shell_sections[model.element_section[element]];
  const Material& m = model.materials[section.material];
  elements::ShellProperties p;
  p.density = m.density * mass_factor;
  p.young = m.young;
  p.poisson = m.poisson;
  p.thickness = section.thickness;
  p.integration_points = section.integration_points;
  p.offset = section.offset;
  p.rotary_exact = section.rotary_exact;
  if (m.plastic) p.plastic = &*m.plastic;
  if (section.controls != NO_INDEX) {
    const SectionControls& c = model.section_controls[section.controls];
    p.hourglass_scale = c.stiffness_scale;
    // HOURGLASS=STIFFNESS, VISCOUS, RELAX STIFFNESS: the older stiffness form.
    if (c.hourglass_given && c.hourglass != HourglassType::Enhanced)
      p.hourglass = elements::ShellHourglass::Stiffness;
  }
  return p;
}

bool deformable(const RigidBodies& rigid, Index e) {
  return rigid.element_body().empty() || rigid.element_body()[e] == NO_INDEX;
}

}  // namespace

ElementSet::ElementSet(const Model& model, const RigidBodies& rigid, State& state,
                       PhaseTimers& timers)
    : m_model(model), m_timers(timers) {
  m_force_internal = NodalVectors::Zero(model.node_count(), 3);
  m_mass_scaling = fixed_mass_scaling(model, rigid, state.reference);
  build_hex_block(rigid, state);
  build_shell_block(rigid, state);
  add_other_masses(rigid, state);
  if (m_shell) {
    m_inverse_inertia.assign(model.node_count(), 0.0);
    for (Index i = 0; i < model.node_count(); ++i)
      if (state.rotary_inertia[i] > 0.0) m_inverse_inertia[i] = 1.0 / state.rotary_inertia[i];
  }
  m_element_kinds.resize(static_cast<std::size_t>(model.element_count()));
  for (Index e = 0; e < model.element_count(); ++e)
    m_element_kinds[e] = is_hex(model.element_types[e])     ? contact::ElementKind::Hex
                         : is_shell(model.element_types[e]) ? contact::ElementKind::Shell
                                                            : contact::ElementKind::Other;
  set_node_thickness(rigid, state.reference);
  set_inverse_mass(rigid, state.mass);
}

void ElementSet::build_hex_block(const RigidBodies& rigid, State& state) {
  std::vector<Index> hex_elements;
  std::vector<Index> connectivity;
  std::vector<elements::HexMaterial> materials;
  std::vector<Index> full_elements, full_connectivity;  // C3D8
  std::vector<elements::HexMaterial> full_materials;
  for (Index e = 0; e < m_model.element_count(); ++e) {
    if (!is_hex(m_model.element_types[e]) || !deformable(rigid, e)) continue;
    const bool full = m_model.element_types[e] == ElementType::C3D8;
    std::vector<Index>& conn = full ? full_connectivity : connectivity;
    (full ? full_elements : hex_elements).push_back(e);
    conn.insert(conn.end(), m_model.nodes_of(e), m_model.nodes_of(e) + 8);
    (full ? full_materials : materials).push_back(hex_material(m_model, e, mass_factor(e)));
  }
  if (!hex_elements.empty()) {
    m_hex = std::make_unique<elements::Hex8rBlock>(hex_elements, connectivity, materials,
                                                   m_model.node_count());
    m_hex->add_lumped_mass(state.reference, state.mass);
  }
  if (!full_elements.empty()) {
    m_hex8 = std::make_unique<elements::Hex8Block>(full_elements, full_connectivity, full_materials,
                                                   m_model.node_count());
    m_hex8->add_lumped_mass(state.reference, state.mass);
  }
}

void ElementSet::build_shell_block(const RigidBodies& rigid, State& state) {
  const Index n = m_model.node_count();
  std::vector<Index> shell_elements;
  std::vector<elements::ShellProperties> shell_props;
  std::vector<Index> connectivity;
  for (Index e = 0; e < m_model.element_count(); ++e) {
    if (!is_shell(m_model.element_types[e]) || !deformable(rigid, e)) continue;
    shell_elements.push_back(e);
    const Index* nodes = m_model.nodes_of(e);
    connectivity.insert(connectivity.end(), nodes, nodes + 4);
    shell_props.push_back(shell_properties(m_model, e, mass_factor(e)));
  }
  if (shell_elements.empty()) return;
  // Rotational DOFs exist only in shell models (P2).
  m_shell = std::make_unique<elements::Shell4rBlock>(shell_elements, connectivity, shell_props, n);
  state.rotation = NodalVectors::Zero(n, 3);
  // *INITIAL CONDITIONS: dofs 4–6 and rigid spins (zero unless given).
  state.angular_velocity = m_model.initial_angular_velocity.rows() == n
                               ? m_model.initial_angular_velocity
                               : NodalVectors::Zero(n, 3);
  state.angular_velocity_half = state.angular_velocity;
  state.reaction_moment = NodalVectors::Zero(n, 3);
  state.rotary_inertia.assign(n, 0.0);
  m_moment_internal = NodalVectors::Zero(n, 3);
  m_shell->add_lumped_mass(state.reference, state.mass, state.rotary_inertia);
  m_shell->note_reference_corners(state.reference);
}

void ElementSet::add_other_masses(const RigidBodies& rigid, State& state) const {
  // Rigid elements: their lumped mass joins the body; point masses join their node.
  for (Index e = 0; e < m_model.element_count(); ++e) {
    if (deformable(rigid, e)) continue;
    const Real m = element_node_mass(m_model, e, state.reference);
    const Index* nodes = m_model.nodes_of(e);
    for (int a = 0; a < nodes_per_element(m_model.element_types[e]); ++a) state.mass[nodes[a]] += m;
  }
  for (const PointInertia& p : m_model.point_inertias) state.mass[p.node] += p.mass;
}

void ElementSet::set_node_thickness(const RigidBodies& rigid, const NodalVectors& reference) {
  const Index n = m_model.node_count();
  if (m_shell) m_node_thickness = m_shell->node_thickness(reference, n);
  for (Index e = 0; e < m_model.element_count(); ++e) {
    if (deformable(rigid, e) || !is_shell(m_model.element_types[e])) continue;
    if (m_node_thickness.empty()) m_node_thickness.assign(n, 0.0);
    const Real t = m_model.shell_sections[m_model.element_section[e]].thickness;
    const Index* nodes = m_model.nodes_of(e);
    for (int a = 0; a < 4; ++a)
      m_node_thickness[nodes[a]] = std::max(m_node_thickness[nodes[a]], t);
  }
}

void ElementSet::set_inverse_mass(const RigidBodies& rigid, const std::vector<Real>& mass) {
  const Index n = m_model.node_count();
  m_inverse_mass.assign(n, 0.0);
  for (Index i = 0; i < n; ++i) {
    if (rigid.is_rigid_node(i)) continue;  // moved by its body
    if (mass[i] > 0.0)
      m_inverse_mass[i] = 1.0 / mass[i];
    else
      ++m_massless;
  }
}

void ElementSet::update_inverse_mass(const std::vector<Index>& nodes, const State& state,
                                     const RigidBodies& rigid) {
  for (Index i : nodes) {
    if (rigid.is_rigid_node(i)) continue;
    m_inverse_mass[i] = state.mass[i] > 0.0 ? 1.0 / state.mass[i] : 0.0;
    if (!m_inverse_inertia.empty())
      m_inverse_inertia[i] = state.rotary_inertia[i] > 0.0 ? 1.0 / state.rotary_inertia[i] : 0.0;
  }
}

Real ElementSet::mass_factor(Index e) const {
  return m_mass_scaling.factor.empty() ? 1.0 : m_mass_scaling.factor[e];
}

Index ElementSet::size() const {
  return (m_hex ? m_hex->size() : 0) + (m_hex8 ? m_hex8->size() : 0) +
         (m_shell ? m_shell->size() : 0);
}

void ElementSet::report_setup(const NodalVectors& reference, OutputSink& sink) const {
  for (const std::string& m : m_mass_scaling.messages) sink.message(Severity::Info, m);
  if (!m_mass_scaling.summary.empty()) sink.status_note(m_mass_scaling.summary);
  if (m_massless > 0)
    sink.message(Severity::Warning, std::to_string(m_massless) +
                                        " node(s) belong to no element and have no mass; "
                                        "they keep their initial velocity");
  if (m_hex)
    sink.message(Severity::Info, "C3D8R elements: " + std::to_string(m_hex->size()) + " in " +
                                     std::to_string(m_hex->color_count()) +
                                     " colours (race-free parallel assembly)");
  if (m_hex8)
    sink.message(Severity::Info, "C3D8 elements: " + std::to_string(m_hex8->size()) + " in " +
                                     std::to_string(m_hex8->color_count()) +
                                     " colours; 2x2x2 points, mean dilatation (selectively "
                                     "reduced), no hourglass control");
  if (!m_shell) return;
  sink.message(Severity::Info,
               "S4R elements: " + std::to_string(m_shell->size()) + " in " +
                   std::to_string(m_shell->color_count()) +
                   " colours; rotary inertia scaled to (m/4)·max(t²/12, c_nu L²) per node so "
                   "that the membrane wave sets the stable increment");
  report_warped_shells(reference, sink);
  for (const SectionControls& c : m_model.section_controls)
    if (c.hourglass == HourglassType::Viscous)
      sink.message(Severity::Note, "section controls " + c.name +
                                       ": S4R elements use the older stiffness hourglass form "
                                       "(HOURGLASS=VISCOUS applies to C3D8R only)");
  // One section point is a membrane: it carries no bending moment, elastic or plastic, so
  // a plastic hinge cannot form. Legitimate for membranes, a mistake for a crash part.
  for (const ShellSection& s : m_model.shell_sections) {
    const Material& material = m_model.materials[s.material];
    if (s.integration_points != 1 || !material.plastic) continue;
    sink.message(Severity::Warning,
                 s.where.file + ":" + std::to_string(s.where.line) +
                     ": *SHELL SECTION: 1 section point on the plastic material " + material.name +
                     ": a membrane-only section (no bending stiffness, no plastic bending); "
                     "give 5 or more points for bending");
  }
}

void ElementSet::report_warped_shells(const NodalVectors& reference, OutputSink& sink) const {
  // Warped elements are evaluated on their projected plane with rigid links to the nodes
  // (accurate for moderate warping); strongly warped ones deserve the user's attention.
  constexpr Real WARN_DEGREES = 10.0;
  constexpr int MAX_LISTED = 20;
  int warped = 0;
  Real worst = 0.0;
  for (Index i = 0; i < m_shell->size(); ++i) {
    const Real angle = m_shell->warp_angle(reference, i);
    worst = std::max(worst, angle);
    if (angle <= WARN_DEGREES) continue;
    if (++warped > MAX_LISTED) continue;
    const Index e = m_shell->element_index(i);
    const SourceLocation where = m_model.element_where(e);
    sink.message(Severity::Warning,
                 where.file + ":" + std::to_string(where.line) + ": *ELEMENT: S4R element " +
                     std::to_string(m_model.element_ids[e]) + " is warped by " +
                     format_real(angle) + " degrees (more than " + format_real(WARN_DEGREES) +
                     "); refine the mesh where the surface is curved");
  }
  if (warped > MAX_LISTED)
    sink.message(Severity::Warning,
                 std::to_string(warped) + " S4R elements are warped by more than " +
                     format_real(WARN_DEGREES) + " degrees (worst " + format_real(worst) +
                     "); the first " + std::to_string(MAX_LISTED) + " are listed above");
}

void ElementSet::set_stress(const NodalVectors& position, std::span<const Real> middle,
                            std::span<const Real> bottom, std::span<const Real> top) {
  if (m_hex) m_hex->set_stress(middle);
  if (m_hex8) m_hex8->set_stress(middle);
  if (m_shell) m_shell->set_output_stress(position, middle, bottom, top);
}

void ElementSet::set_plastic_strain(std::span<const Real> peeq, std::span<const Real> middle,
                                    std::span<const Real> bottom, std::span<const Real> top) {
  if (m_hex && !peeq.empty()) m_hex->set_plastic_strain(peeq);
  if (m_hex8 && !peeq.empty()) m_hex8->set_plastic_strain(peeq);
  if (m_shell && !middle.empty()) m_shell->set_plastic_strain(middle, bottom, top);
}

void ElementSet::set_hourglass_state(std::span<const Real> rows) {
  if (m_hex) m_hex->set_hourglass_state(rows);
  if (m_shell) m_shell->set_hourglass_state(rows);
}

void ElementSet::set_shell_thickness(std::span<const Real> thickness) {
  if (m_shell) m_shell->set_thickness(thickness);
}

void ElementSet::use_partition(int parts) {
  if (m_parts == parts) return;
  // The boundary nodes are those two parts share over all blocks, so that a node's
  // contributions keep their order (C3D8R colours, then S4R, then C3D8) too.
  std::vector<Index> node_part(static_cast<std::size_t>(m_model.node_count()), elements::UNTOUCHED);
  if (m_hex) m_hex->mark_nodes(parts, node_part);
  if (m_shell) m_shell->mark_nodes(parts, node_part);
  if (m_hex8) m_hex8->mark_nodes(parts, node_part);
  const elements::BoundaryNodes boundary = elements::boundary_nodes(node_part);
  if (m_hex) m_hex->set_partition(parts, boundary);
  if (m_shell) m_shell->set_partition(parts, boundary);
  if (m_hex8) m_hex8->set_partition(parts, boundary);
  m_boundary_nodes = boundary.nodes;
  m_parts = parts;
}

void ElementSet::compute_forces(const State& state, Real dt, ElementTotals& totals) {
  ScopedTimer timer(m_timers, Phase::InternalForce);
  const Step& s = m_model.steps[state.step];
  // One parallel region for every block and colour (thread_partition.hpp).
  const int parts = std::max(1, omp_get_max_threads());
  use_partition(parts);
  elements::partitioned_pass(
      parts, static_cast<Index>(m_boundary_nodes.size()),
      [&](int p) {
        if (m_hex)
          m_hex->forces_of_part(p, state.position, state.velocity_half, dt, s.bulk_linear,
                                s.bulk_quadratic, m_force_internal);
        if (m_shell)
          m_shell->forces_of_part(p, state.position, state.velocity_half,
                                  state.angular_velocity_half, dt, m_force_internal,
                                  m_moment_internal);
        if (m_hex8)
          m_hex8->forces_of_part(p, state.position, state.velocity_half, dt, s.bulk_linear,
                                 s.bulk_quadratic, m_force_internal);
      },
      [&](Index k) {
        const Index node = m_boundary_nodes[k];
        if (m_hex) m_hex->add_boundary_forces(k, node, m_force_internal);
        if (m_shell) m_shell->add_boundary_forces(k, node, m_force_internal, m_moment_internal);
        if (m_hex8) m_hex8->add_boundary_forces(k, node, m_force_internal);
      });
  if (m_hex) {
    elements::HexStepTotals t;
    m_hex->add_totals(t);
    totals.add(t);
    totals.viscous_energy_increment += t.viscous_energy_increment;
  }
  if (m_hex8) {
    elements::HexStepTotals t;
    m_hex8->add_totals(t);
    totals.add(t);
    totals.viscous_energy_increment += t.viscous_energy_increment;
  }
  if (m_shell) {
    elements::ShellStepTotals t;
    m_shell->add_totals(t);
    totals.add(t);
  }
}

ElementEstimate ElementSet::increment_estimate(const State& state, const ElementTotals& totals) {
  ElementEstimate e;
  e.stable_dt = totals.stable_dt;
  e.critical_element = totals.critical_element;
  const Step& s = m_model.steps[state.step];
  // Shell-only models pass their own stress test; the global estimate covers the hexes.
  if ((m_hex || m_hex8) && !s.increment.fixed) {
    ScopedTimer timer(m_timers, Phase::InternalForce);
    const auto product = [this, &state](const NodalVectors& u, NodalVectors& y) {
      if (m_hex) m_hex->add_stiffness_product(state.position, u, y);
      if (m_hex8) m_hex8->add_stiffness_product(state.position, u, y);
    };
    e.global_ratio =
        m_global.apply(product, state.position.rows(), m_inverse_mass, s.bulk_linear, totals);
  }
  return e;
}

ElementEstimate ElementSet::increment_estimate(const State& state) {
  ElementTotals totals;
  compute_forces(state, 0.0, totals);
  clear_forces();
  return increment_estimate(state, totals);
}

void ElementSet::report_increment_limit(OutputSink& sink) {
  FrequencyEstimate e;
  if (!m_global.take_new_estimate(e)) return;
  sink.message(Severity::Info,
               "global stable-increment estimate: omega_max " + format_real(e.omega_max) +
                   " rad/s, limit (2/omega_max)(sqrt(1+xi^2)-xi) " + format_real(e.global_dt) +
                   " s; element estimate " + format_real(e.element_dt) +
                   " s = " + format_real(e.element_dt / e.global_dt) + " x the global limit: " +
                   (e.governs() ? "the global limit governs, increment = element estimate x " +
                                      format_real(e.ratio)
                                : std::string("the element estimate governs")) +
                   " (" + std::to_string(e.products) + " Lanczos iterations, " +
                   format_real(e.seconds) + " s)");
}

void ElementSet::gather_output(const State& state, const FrameRequest& what,
                               FrameFields& frame) const {
  if (what.plastic_strain) {
    // PEEQ of every element (0 where elastic); each block writes the rows of its elements.
    frame.peeq.assign(static_cast<std::size_t>(m_model.element_count()), 0.0);
    if (m_hex) m_hex->gather_plastic_strain(frame.peeq);
    if (m_hex8) m_hex8->gather_plastic_strain(frame.peeq);
    if (m_shell) m_shell->gather_plastic_strain(frame.peeq);
    if (m_model.has_plastic_shells()) {
      // Per section point: NaN rows for solids and rigid elements, like S_SNEG and S_SPOS.
      const auto n = static_cast<std::size_t>(m_model.element_count());
      const Real nan = std::numeric_limits<Real>::quiet_NaN();
      frame.peeq_bottom.assign(n, nan);
      frame.peeq_middle.assign(n, nan);
      frame.peeq_top.assign(n, nan);
      if (m_shell)
        m_shell->gather_section_plastic_strain(frame.peeq_bottom, frame.peeq_middle,
                                               frame.peeq_top);
    }
  }
  if (!what.stress && !what.volume && !what.thickness) return;
  // Element output arrays exist only in runs that write element output (P2).
  const auto n_elements = static_cast<std::size_t>(m_model.element_count());
  frame.stress.resize(n_elements * 6, 0.0);
  frame.volume.resize(n_elements, 0.0);
  if (m_hex) m_hex->gather_output(frame.stress, frame.volume);
  if (m_hex8) m_hex8->gather_output(frame.stress, frame.volume);
  if (what.stress && has_hourglass_state()) {
    frame.hourglass_state.assign(n_elements * elements::HOURGLASS_STATE_WIDTH, 0.0);
    if (m_hex) m_hex->gather_hourglass_state(frame.hourglass_state);
    if (m_shell) m_shell->gather_hourglass_state(frame.hourglass_state);
  }
  if (m_shell) {
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    frame.stress_bottom.resize(n_elements * 6, nan);
    frame.stress_top.resize(n_elements * 6, nan);
    frame.thickness.resize(n_elements, nan);
    m_shell->gather_output(state.position, frame.stress, frame.stress_bottom, frame.stress_top,
                           frame.thickness);
  }
}

void ElementSet::clear_forces() {
  m_force_internal.setZero();
  if (m_shell) m_moment_internal.setZero();
}

}  // namespace xpl

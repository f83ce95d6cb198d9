#include "solver/forces/element_set.hpp"

#include "solver/forces/element_set_blocks.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>

#include "solver/distributed_run.hpp"
#include "solver/increment/mass_scaling.hpp"
#include "solver/loads/gravity_loads.hpp"
#include "solver/message_text.hpp"

namespace xpl {

namespace {

bool deformable(const RigidBodies& rigid, Index e) {
  return rigid.element_body().empty() || rigid.element_body()[e] == NO_INDEX;
}

}  // namespace

ElementSet::ElementSet(const Model& model, const RigidBodies& rigid, State& state,
                       PhaseTimers& timers)
    : m_model(model), m_timers(timers) {
  m_force_internal = NodalVectors::Zero(model.node_count(), 3);
  m_mass_scaling = fixed_mass_scaling(model, rigid, state.reference);
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (build_block<std::tuple_element_t<I, ElementKinds>>(rigid, state), ...);
  }
  (std::make_index_sequence<std::tuple_size_v<ElementKinds>>{});
  add_other_masses(rigid, state);
  if (m_rotations) {
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

template <class K>
void ElementSet::build_block(const RigidBodies& rigid, State& state) {
  std::vector<Index> elements;
  std::vector<Index> connectivity;
  std::vector<typename K::Properties> properties;
  for (Index e = 0; e < m_model.element_count(); ++e) {
    if (!KindBinding<K>::takes(m_model.element_types[e]) || !deformable(rigid, e)) continue;
    elements.push_back(e);
    connectivity.insert(connectivity.end(), m_model.nodes_of(e), m_model.nodes_of(e) + K::NODES);
    properties.push_back(KindBinding<K>::properties(m_model, e, mass_factor(e)));
  }
  if (elements.empty()) return;
  auto& block = std::get<std::unique_ptr<K>>(m_blocks);
  block = std::make_unique<K>(elements, connectivity, properties, m_model.node_count());
  if constexpr (requires { K::ROTATIONS; })
    if (!m_rotations) add_rotations(state);
  block->add_lumped_mass(state.reference, state.mass, state.rotary_inertia);
  if constexpr (requires { block->note_reference_corners(state.reference); })
    block->note_reference_corners(state.reference);
}

void ElementSet::add_rotations(State& state) {
  // Rotational DOFs exist only in models with a kind that has them (P2).
  const Index n = m_model.node_count();
  state.rotation = NodalVectors::Zero(n, 3);
  // *INITIAL CONDITIONS: dofs 4–6 and rigid spins (zero unless given).
  state.angular_velocity = m_model.initial_angular_velocity.rows() == n
                               ? m_model.initial_angular_velocity
                               : NodalVectors::Zero(n, 3);
  state.angular_velocity_half = state.angular_velocity;
  state.reaction_moment = NodalVectors::Zero(n, 3);
  state.rotary_inertia.assign(n, 0.0);
  m_moment_internal = NodalVectors::Zero(n, 3);
  m_rotations = true;
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
  if (shells()) m_node_thickness = shells()->node_thickness(reference, n);
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
  Index n = 0;
  for_each_whole_block([&](const auto& block) { n += block.size(); });
  return n;
}

bool ElementSet::has_shells() const {
  bool any = false;
  for_each_whole_block([&](const auto& block) {
    any = any || std::is_same_v<std::decay_t<decltype(block)>, elements::Shell4rBlock>;
  });
  return any;
}

bool ElementSet::has_hourglass_state() const {
  // The whole model's kinds: every rank of a distributed run writes (and gathers) the same
  // fields, also one whose part holds no element of a kind with the state.
  bool any = false;
  for_each_whole_block([&](const auto& block) {
    if constexpr (requires(std::vector<Real> & rows) { block.gather_hourglass_state(rows); })
      any = true;
  });
  return any;
}

void ElementSet::report_setup(const NodalVectors& reference, OutputSink& sink) const {
  for (const std::string& m : m_mass_scaling.messages) sink.message(Severity::Info, m);
  if (!m_mass_scaling.summary.empty()) sink.status_note(m_mass_scaling.summary);
  if (m_massless > 0)
    sink.message(Severity::Warning, std::to_string(m_massless) +
                                        " node(s) belong to no element and have no mass; "
                                        "they keep their initial velocity");
  for_each_block([&](const auto& block) {
    sink.message(Severity::Info,
                 std::string(block.NAME) + " elements: " + std::to_string(block.size()) + " in " +
                     std::to_string(block.color_count()) + " colours" + block.SETUP_NOTE);
  });
  if (!shells()) return;
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
  const elements::Shell4rBlock& shell = *shells();
  for (Index i = 0; i < shell.size(); ++i) {
    const Real angle = shell.warp_angle(reference, i);
    worst = std::max(worst, angle);
    if (angle <= WARN_DEGREES) continue;
    if (++warped > MAX_LISTED) continue;
    const Index e = shell.element_index(i);
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
  for_each_block([&](auto& block) { block.set_stress(position, middle, bottom, top); });
}

void ElementSet::set_plastic_strain(std::span<const Real> peeq, std::span<const Real> middle,
                                    std::span<const Real> bottom, std::span<const Real> top) {
  for_each_block([&](auto& block) {
    // Solids take one value per element, shells their three section points.
    if constexpr (requires { block.set_plastic_strain(middle, bottom, top); }) {
      if (!middle.empty()) block.set_plastic_strain(middle, bottom, top);
    } else if (!peeq.empty()) {
      block.set_plastic_strain(peeq);
    }
  });
}

void ElementSet::set_hourglass_state(std::span<const Real> rows) {
  for_each_block([&](auto& block) {
    if constexpr (requires { block.set_hourglass_state(rows); }) block.set_hourglass_state(rows);
  });
}

void ElementSet::set_shell_thickness(std::span<const Real> thickness) {
  for_each_block([&](auto& block) {
    if constexpr (requires { block.set_thickness(thickness); }) block.set_thickness(thickness);
  });
}

void ElementSet::use_partition(int parts) {
  if (m_parts == parts) return;
  // The boundary nodes are those two parts share over all blocks, so that a node's
  // contributions keep their order (ForcePassOrder) too.
  std::vector<Index> node_part(static_cast<std::size_t>(m_model.node_count()), elements::UNTOUCHED);
  for_each_block(ForcePassOrder{}, [&](auto& block) { block.mark_nodes(parts, node_part); });
  // Distributed runs: the interface nodes' corners go to slots too, for the exchange.
  if (m_run != nullptr) mark_batch_phases(node_part);
  const elements::BoundaryNodes boundary = elements::boundary_nodes(node_part);
  for_each_block(ForcePassOrder{}, [&](auto& block) { block.set_partition(parts, boundary); });
  m_boundary_nodes = boundary.nodes;
  m_parts = parts;
}

void ElementSet::compute_forces(const State& state, Real dt, ElementTotals& totals) {
  ScopedTimer timer(m_timers, Phase::InternalForce);
  const Step& s = m_model.steps[state.step];
  // One parallel region for every block and colour (thread_partition.hpp).
  const int parts = std::max(1, omp_get_max_threads());
  use_partition(parts);
  elements::ForcePass pass{state.position,
                           state.velocity_half,
                           state.angular_velocity_half,
                           dt,
                           s.bulk_linear,
                           s.bulk_quadratic,
                           m_force_internal,
                           m_moment_internal};
  const auto compute_parts = [&](int p) {
    for_each_block(ForcePassOrder{}, [&](auto& block) { block.forces_of_part(p, pass); });
  };
  const auto add_boundary = [&](Index k) {
    const Index node = m_boundary_nodes[k];
    for_each_block(ForcePassOrder{},
                   [&](auto& block) { block.add_boundary_forces(k, node, pass); });
  };
  if (m_run != nullptr) {
    // Distributed runs: the batches at the interface first, their corners sent, then the
    // others while the messages travel (mark_batch_phases()).
    m_run->post_receives(m_rotations ? 6 : 3);
    pass.phase = 0;
    elements::partitioned_pass(parts, 0, compute_parts, add_boundary);
    send_interface_forces();
    pass.phase = 1;
  }
  elements::partitioned_pass(parts, static_cast<Index>(m_boundary_nodes.size()), compute_parts,
                             add_boundary);
  if (m_run != nullptr) {
    // The batch totals travel while the rank waits for its neighbours' corners and ships its
    // chunk owners' forces: one wait for all three.
    post_totals();
    combine_interface_forces();
    m_run->ship_forces(m_force_internal, m_rotations ? &m_moment_internal : nullptr);
    reduce_totals(totals);
    return;
  }
  for_each_block([&](const auto& block) {
    typename std::remove_cvref_t<decltype(block)>::Totals t;
    block.add_totals(t);
    totals.add(t);
  });
}

ElementEstimate ElementSet::increment_estimate(const State& state, const ElementTotals& totals) {
  ElementEstimate e;
  e.stable_dt = totals.stable_dt;
  e.critical_element = totals.critical_element;
  const Step& s = m_model.steps[state.step];
  // The kinds with a stiffness product (the hexes) take the global estimate; shell-only
  // models pass their own stress test.
  bool stiffness = false;
  for_each_whole_block([&](const auto& block) {
    if constexpr (requires(NodalVectors & y) { block.add_stiffness_product(y, y, y); })
      stiffness = true;
  });
  if (stiffness && !s.increment.fixed) {
    ScopedTimer timer(m_timers, Phase::InternalForce);
    // Distributed runs: every rank runs the estimate on the whole mesh, with the positions of
    // every node from their owners when it is due; in each product a rank multiplies the whole
    // blocks' batches at the nodes it owns (distribute()), whose rows then hold the one-rank
    // sums, and every rank takes each node's row from its owner.
    const auto gather = [this, &state] {
      if (m_run == nullptr) return;
      m_whole_position = state.position;
      m_run->allgather_rows(m_whole_position);
    };
    const auto product = [this, &state](const NodalVectors& u, NodalVectors& y) {
      if (m_run == nullptr) {
        for_each_whole_block([&](const auto& block) {
          if constexpr (requires { block.add_stiffness_product(state.position, u, y); })
            block.add_stiffness_product(state.position, u, y);
        });
        return;
      }
      [&]<std::size_t... I>(std::index_sequence<I...>) {
        (
            [&] {
              const auto& whole = std::get<I>(m_whole);
              const std::vector<char>& selected = m_product_batches[I];
              if constexpr (requires {
                              whole->add_stiffness_product(m_whole_position, u, y, selected);
                            })
                if (whole) whole->add_stiffness_product(m_whole_position, u, y, selected);
            }(),
            ...);
      }
      (std::make_index_sequence<3>{});
      m_run->allgather_rows(y);
    };
    e.global_ratio = m_global.apply(product, state.position.rows(), m_inverse_mass, s.bulk_linear,
                                    totals, gather);
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

void ElementSet::clear_forces() {
  m_force_internal.setZero();
  if (m_rotations) m_moment_internal.setZero();
}

}  // namespace xpl

#include "solver/explicit_solver.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "elements/hex8r.hpp"
#include "solver/boundary_state.hpp"
#include "solver/output_schedule.hpp"

namespace xpl {

namespace {

/// Nodes per chunk of the nodal loops; partial sums per chunk are added in chunk order so
/// that energies do not depend on the thread count.
constexpr Index NODE_CHUNK = 2048;

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
  BoundaryState boundary;
  OutputSchedule schedule;
  PhaseTimers timers;
  NodalVectors force_internal;  ///< (n_nodes × 3), zeroed after each use
  /// (n_nodes × 3), non-zero only on loaded DOFs; allocated only when a step has loads (P2).
  NodalVectors force_external;
  std::vector<Real> inverse_mass;  ///< 0 for nodes without mass (no element)
  std::vector<Real> chunk_sums;
  std::vector<Real> history_row;
  NodalVectors previous_force;        ///< f_ext + reaction at the previous increment (work)
  std::vector<LoadedDof> free_loads;  ///< loaded DOFs that are not prescribed
  std::vector<Real> v_old_prescribed, v_old_loaded;
  Real dt_half = 0.0;     ///< dt_{n+1/2}: the increment about to be taken
  Real dt_first = 0.0;    ///< first stable increment (for the collapse check)
  Real max_energy = 0.0;  ///< running maximum of the energy scales (instability check)
  Real initial_total = 0.0;
  ExternalId critical_id = 0;
  long loop_increments = 0;
  double loop_seconds = 0.0;
  bool started = false;

  Impl(const Model& m, OutputSink& s, SolverOptions o) : model(m), sink(s), options(o) {}

  void setup();
  void begin_step(int step);
  void compute_forces(Real dt, elements::HexStepTotals& totals);
  Real next_increment(const elements::HexStepTotals& totals, Real remaining, int step) const;
  void update_nodes(Real dt_prev, Real dt_next, Real t_next_half, Real t_next_end);
  void apply_loads(Real step_time, Real total_time);
  void write_frame(const FrameRequest& what);
  void write_history();
  void write_status();
  void check_health(const elements::HexStepTotals& totals);
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

  std::vector<Index> hex_elements;
  std::vector<Index> connectivity;
  std::vector<elements::HexMaterial> materials;
  for (Index e = 0; e < model.element_count(); ++e) {
    if (model.element_types[e] != ElementType::C3D8R) continue;
    hex_elements.push_back(e);
    const Index* nodes = model.nodes_of(e);
    connectivity.insert(connectivity.end(), nodes, nodes + 8);
    materials.push_back(hex_material(model, e));
  }
  if (!hex_elements.empty()) {
    hex = std::make_unique<elements::Hex8rBlock>(hex_elements, connectivity, materials, n);
    hex->add_lumped_mass(state.reference, state.mass);
  }
  inverse_mass.assign(n, 0.0);
  Index massless = 0;
  for (Index i = 0; i < n; ++i) {
    if (state.mass[i] > 0.0)
      inverse_mass[i] = 1.0 / state.mass[i];
    else
      ++massless;
  }
  chunk_sums.assign((n + NODE_CHUNK - 1) / NODE_CHUNK * 2, 0.0);

  sink.begin_run(model);
  for (const SectionControls& c : model.section_controls)
    if (c.hourglass == HourglassType::RelaxStiffness)
      sink.message(Severity::Note, "section controls " + c.name +
                                       ": HOURGLASS=RELAX STIFFNESS is run as STIFFNESS "
                                       "(Flanagan-Belytschko stiffness form)");
  if (massless > 0)
    sink.message(Severity::Warning, std::to_string(massless) +
                                        " node(s) belong to no element and have no mass; "
                                        "they keep their initial velocity");
  if (hex)
    sink.message(Severity::Info, "C3D8R elements: " + std::to_string(hex->size()) + " in " +
                                     std::to_string(hex->color_count()) +
                                     " colours (race-free parallel assembly)");
}

void ExplicitSolver::Impl::begin_step(int step) {
  const NodalVectors displacement = state.position - state.reference;
  boundary.begin_step(model, step, displacement, state.velocity);
  schedule.begin_step(model, step);
  state.reaction.setZero();
  v_old_prescribed.assign(boundary.prescribed().size(), 0.0);
  std::vector<char> is_prescribed(static_cast<std::size_t>(model.node_count()) * 3, 0);
  for (const PrescribedDof& d : boundary.prescribed())
    is_prescribed[static_cast<std::size_t>(d.component) * model.node_count() + d.node] = 1;
  free_loads.clear();
  for (const LoadedDof& l : boundary.loads())
    if (!is_prescribed[static_cast<std::size_t>(l.component) * model.node_count() + l.node])
      free_loads.push_back(l);
  v_old_loaded.assign(free_loads.size(), 0.0);
  if (previous_force.rows() == 0 && (!boundary.prescribed().empty() || !free_loads.empty()))
    previous_force = NodalVectors::Zero(model.node_count(), 3);
  state.step = step;
  state.step_time = 0.0;
  sink.begin_step(model, step);
  if (boundary.has_rotational_dofs())
    sink.message(Severity::Note, "step " + model.steps[step].name +
                                     ": boundary conditions on DOFs 4-6 are ignored (solid "
                                     "element nodes have no rotations)");
  if (schedule.has_history()) sink.declare_history(schedule.series());
}

void ExplicitSolver::Impl::compute_forces(Real dt, elements::HexStepTotals& totals) {
  ScopedTimer timer(timers, Phase::InternalForce);
  const Step& s = model.steps[state.step];
  if (hex)
    hex->internal_forces(state.position, state.velocity_half, dt, s.bulk_linear, s.bulk_quadratic,
                         force_internal, totals);
}

void ExplicitSolver::Impl::apply_loads(Real step_time, Real total_time) {
  if (boundary.loads().empty()) return;
  if (force_external.rows() == 0) force_external = NodalVectors::Zero(model.node_count(), 3);
  for (const LoadedDof& l : boundary.loads()) force_external(l.node, l.component) = 0.0;
  for (const LoadedDof& l : boundary.loads())
    force_external(l.node, l.component) +=
        l.value * boundary.factor(model, l.amplitude, step_time, total_time);
}

Real ExplicitSolver::Impl::next_increment(const elements::HexStepTotals& totals, Real remaining,
                                          int step) const {
  const Step& s = model.steps[step];
  Real dt = s.fixed_increment ? *s.fixed_increment
                              : totals.stable_dt * s.time_scale_factor * options.dt_safety;
  if (!std::isfinite(dt)) dt = remaining;  // no elements: one increment to the end
  // Land exactly on the end of the step; avoid a sliver increment just before it.
  if (dt >= remaining || remaining - dt < 1e-3 * dt) dt = remaining;
  return dt;
}

void ExplicitSolver::Impl::update_nodes(Real dt_prev, Real dt_next, Real t_next_half,
                                        Real t_next_end) {
  ScopedTimer timer(timers, Phase::Integration);
  const Index n = model.node_count();
  const Real dt_avg = 0.5 * (dt_prev + dt_next);
  // At t = 0 the whole-step velocity is the initial velocity itself.
  const Real w_new = dt_prev > 0.0 ? 0.5 : 0.0;
  const Index n_chunks = (n + NODE_CHUNK - 1) / NODE_CHUNK;
  Real* fi = force_internal.data();
  // No loads in the model: the external force array does not exist and is not read.
  const bool loaded = force_external.rows() > 0;
  const Real* fe = loaded ? force_external.data() : fi;
  const Real fe_scale = loaded ? 1.0 : 0.0;
  Real* v = state.velocity_half.data();
  Real* vw = state.velocity.data();
  Real* a = state.acceleration.data();

  // Prescribed and loaded DOFs keep v_{n-1/2} for the work and reaction terms.
  const auto& prescribed = boundary.prescribed();
  for (std::size_t k = 0; k < prescribed.size(); ++k)
    v_old_prescribed[k] = state.velocity_half(prescribed[k].node, prescribed[k].component);
  for (std::size_t k = 0; k < free_loads.size(); ++k)
    v_old_loaded[k] = state.velocity_half(free_loads[k].node, free_loads[k].component);

#pragma omp parallel for schedule(static)
  for (Index chunk = 0; chunk < n_chunks; ++chunk) {
    const Index first = chunk * NODE_CHUNK, last = std::min(n, first + NODE_CHUNK);
    Real ke = 0.0;
    for (int c = 0; c < 3; ++c) {
      const Index off = c * n;
#pragma omp simd reduction(+ : ke)
      for (Index i = first; i < last; ++i) {
        const Real acc = (fe_scale * fe[off + i] - fi[off + i]) * inverse_mass[i];
        const Real v_new = v[off + i] + dt_avg * acc;
        const Real v_whole = v[off + i] + w_new * (v_new - v[off + i]);
        ke += state.mass[i] * v_whole * v_whole;
        a[off + i] = acc;
        v[off + i] = v_new;
        vw[off + i] = v_whole;
      }
    }
    chunk_sums[chunk] = 0.5 * ke;
  }

  // Prescribed DOFs: velocity from the BC, reaction = m a - (f_ext - f_int).
  // External work by the trapezoidal rule over [t_{n-1}, t_n]: exact for constant forces.
  Real ke_fix = 0.0, work = 0.0;
  const Real step_next_half = state.step_time + 0.5 * dt_next;
  const Real step_next_end = state.step_time + dt_next;
  for (std::size_t k = 0; k < prescribed.size(); ++k) {
    const PrescribedDof& d = prescribed[k];
    const Index i = d.node, off = d.component * n;
    const Real v_old = v_old_prescribed[k];
    Real v_new = 0.0;
    if (d.type == BoundaryType::Velocity) {
      v_new = boundary.target(model, d, step_next_half, t_next_half);
    } else if (dt_next > 0.0) {
      const Real u_next = boundary.target(model, d, step_next_end, t_next_end);
      v_new = (state.reference(i, d.component) + u_next - state.position(i, d.component)) / dt_next;
    }
    const Real m = state.mass[i];
    const Real wrong = vw[off + i];  // what the free update counted
    const Real right = v_old + w_new * (v_new - v_old);
    ke_fix += 0.5 * m * (right * right - wrong * wrong);
    const Real acc = dt_avg > 0.0 ? (v_new - v_old) / dt_avg : 0.0;
    const Real f_ext = fe_scale * fe[off + i];
    const Real r = m * acc - (f_ext - fi[off + i]);
    state.reaction(i, d.component) = r;
    a[off + i] = acc;
    v[off + i] = v_new;
    vw[off + i] = right;
    const Real f_now = f_ext + r;
    work += 0.5 * (previous_force(i, d.component) + f_now) * dt_prev * v_old;
    previous_force(i, d.component) = f_now;
  }
  for (std::size_t k = 0; k < free_loads.size(); ++k) {
    const Index i = free_loads[k].node;
    const int c = free_loads[k].component;
    const Real f_now = force_external(i, c);
    work += 0.5 * (previous_force(i, c) + f_now) * dt_prev * v_old_loaded[k];
    previous_force(i, c) = f_now;
  }
  Real ke = 0.0;
  for (Index chunk = 0; chunk < n_chunks; ++chunk) ke += chunk_sums[chunk];
  state.energies.kinetic = ke + ke_fix;
  state.energies.external_work += work;
  force_internal.setZero();
}

void ExplicitSolver::Impl::write_frame(const FrameRequest& what) {
  ScopedTimer timer(timers, Phase::Output);
  if (hex && (what.stress || what.volume)) {
    // Element output arrays exist only in runs that write element output (P2).
    state.stress.resize(static_cast<std::size_t>(model.element_count()) * 6, 0.0);
    state.volume.resize(model.element_count(), 0.0);
    hex->gather_output(state.stress, state.volume);
  }
  sink.write_frame(model, state, what);
}

void ExplicitSolver::Impl::write_history() {
  ScopedTimer timer(timers, Phase::Output);
  schedule.history_row(state, history_row);
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

void ExplicitSolver::Impl::check_health(const elements::HexStepTotals& totals) {
  if (totals.failed_element != NO_INDEX) {
    const ExternalId id = model.element_ids[totals.failed_element];
    throw SolverError("NaN/instability at increment " + std::to_string(state.increment) +
                          ", element " + std::to_string(id) +
                          ": non-positive or undefined volume (element inverted)",
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
  if (max_energy > 0.0 && drift > 0.5 * max_energy && drift > 1e-12) {
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
  const Real period = model.steps[step].time_period;
  const Real step_start = state.time;
  elements::HexStepTotals totals;

  if (!started) {
    // t = 0: forces on the initial geometry, first increment, half-step velocity.
    compute_forces(0.0, totals);
    state.energies.strain += totals.strain_energy_increment;
    apply_loads(0.0, 0.0);
    dt_half = next_increment(totals, period, step);
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
    }
    const Real dt_prev = dt_half;
    state.time += dt_prev;
    state.step_time = state.time - step_start;
    const bool last = state.step_time >= period * (1.0 - 1e-12);
    if (last) state.step_time = period;
    ++state.increment;
    state.dt = dt_prev;

    totals = elements::HexStepTotals{};
    compute_forces(dt_prev, totals);
    state.energies.strain += totals.strain_energy_increment;
    state.energies.artificial += totals.hourglass_energy_increment;
    state.energies.viscous += totals.viscous_energy_increment;
    if (totals.critical_element != NO_INDEX)
      critical_id = model.element_ids[totals.critical_element];
    apply_loads(state.step_time, state.time);

    dt_half = last ? dt_prev : next_increment(totals, period - state.step_time, step);
    update_nodes(dt_prev, dt_half, state.time + 0.5 * dt_half, state.time + dt_half);
    check_health(totals);

    const FrameRequest frame = schedule.field_due(state.step_time, last);
    if (frame.displacement || frame.velocity || frame.acceleration || frame.reaction ||
        frame.stress || frame.volume)
      write_frame(frame);
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
  const double cycles = static_cast<double>(hex ? hex->size() : 0) * state.increment;
  s.element_cycles_per_second = loop_seconds > 0.0 ? cycles / loop_seconds : 0.0;
  s.timers = timers;
  s.energies = state.energies;
  return s;
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
    elements::HexStepTotals totals;
    s.compute_forces(0.0, totals);
    s.force_internal.setZero();
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

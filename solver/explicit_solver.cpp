#include "solver/explicit_solver.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <string>

#include "common/error.hpp"
#include "common/parallel_error.hpp"
#include "solver/explicit_solver_impl.hpp"
#include "solver/increment/increment_control.hpp"
#include "solver/message_text.hpp"
#include "solver/model_partition.hpp"
#include "solver/thread_team.hpp"

namespace xpl {

void ExplicitSolver::Impl::begin_step(int step) {
  m_nodes.begin_step(step, m_state, m_rigid);
  m_elements.begin_step();
  m_output.begin_step(step);
  m_state.step = step;
  m_state.step_time = 0.0;
  m_sink.begin_step(m_model, step);
  m_nodes.report_step(step, m_sink);
  m_contact.begin_step(step, m_state, m_elements, m_rigid, m_nodes.prescribed());
  m_output.declare_history(m_contact);
  m_output.report_notes();
}

void ExplicitSolver::Impl::start_run(int step, Real period) {
  ElementTotals totals;
  m_next = evaluate_forces(Pass::Start, 0.0, period, totals);
  const Real dt = m_next.dt;
  m_nodes.update_nodes(m_state, m_elements, m_rigid, 0.0, dt, 0.5 * dt, dt);
  m_nodes.report_jump(step, m_sink);
  m_energy.start(m_state);
  m_increment.start(dt);
  m_started = true;
  if (m_output.has_field()) write_frame(m_output.field_all());
}

bool ExplicitSolver::Impl::advance_clock(Real dt, Real step_start, Real period) {
  m_state.time += dt;
  m_state.step_time = m_state.time - step_start;
  const bool last = m_state.step_time >= period * (1.0 - 1e-12);
  if (last) m_state.step_time = period;
  ++m_state.increment;
  m_state.dt = dt;
  return last;
}

IncrementDecision ExplicitSolver::Impl::evaluate_forces(Pass pass, Real dt_taken, Real remaining,
                                                        ElementTotals& totals) {
  const int step = m_state.step;
  m_elements.compute_forces(m_state, dt_taken, totals);
  const ElementEstimate estimate = m_elements.increment_estimate(m_state, totals);
  m_elements.report_increment_limit(m_sink);
  note_critical(totals);
  const ElementIncrement elements = m_increment.elements(step, estimate);
  if (pass == Pass::Check) {
    m_elements.clear_forces();
    m_contact.check_penalty(elements, step, m_elements.inverse_mass());
    return choose_increment(elements, {}, remaining);
  }
  m_state.energies.strain += totals.strain_energy_increment;
  if (pass == Pass::Increment) {  // t = 0 books the strain energy of the initial state only
    m_state.energies.artificial += totals.hourglass_energy_increment;
    m_state.energies.viscous += totals.viscous_energy_increment;
    m_state.energies.plastic += totals.plastic_energy_increment;
  }
  m_nodes.apply_loads(m_state, m_state.step_time, m_state.time);
  // The penalty is tied to the increment the elements allow, not to one shortened to land
  // on the end of a step: a short last increment must not stiffen the springs.
  m_contact.apply(m_state, m_elements, dt_taken,
                  elements.penalty_dt(pass == Pass::Start ? remaining : dt_taken));
  // A deck's own penalty stiffness may shorten the increment
  // (solver/increment/penalty_increment_limit.hpp).
  const ContactIncrement springs = m_contact.penalty_increment(elements, step, m_state);
  return choose_increment(elements, springs, remaining);
}

void ExplicitSolver::Impl::note_critical(const ElementTotals& totals) {
  if (totals.critical_element != NO_INDEX)
    m_critical_id = m_model.element_ids[totals.critical_element];
}

void ExplicitSolver::Impl::run_step(int step) {
  begin_step(step);
  m_contact_energy.begin_step(m_state.increment);
  const Real period = m_model.steps[step].time_period;
  const Real step_start = m_state.time;
  if (!m_started) {
    start_run(step, period);
    report_partition(m_model, m_rigid, m_ties, m_contact.engine(), m_options.partition_parts,
                     m_options.partition_method, m_options.partition_note, m_sink);
  } else
    m_next = carry_increment(m_next, period);
  m_increment.report_start(step, m_next);
  m_output.note_short_intervals(m_next.dt);
  if (m_output.has_history()) write_history();
  write_status();

  const auto loop_start = std::chrono::steady_clock::now();
  const LoopShares shares_start = loop_shares();
  Real next_status = 0.01 * period;
  while (m_state.step_time < period) {
    // x_{n+1} = x_n + dt_{n+1/2} v_{n+1/2}; t_{n+1} = t_n + dt_{n+1/2}.
    m_nodes.advance_positions(m_state, m_elements, m_next.dt);
    const Real dt_prev = m_next.dt;
    const bool last = advance_clock(dt_prev, step_start, period);
    m_increment.count(m_next);

    // Forces at x_{n+1}: elements, loads, contact (its penalty tied to the stable increment),
    // and the next increment.
    ElementTotals totals;
    const IncrementDecision next =
        evaluate_forces(Pass::Increment, dt_prev, period - m_state.step_time, totals);

    // v_{n+3/2} over the next increment (the last one of a step keeps the increment taken),
    // then the health of the run.
    if (!last) m_next = next;
    const Real dt_next = m_next.dt;
    m_nodes.update_nodes(m_state, m_elements, m_rigid, dt_prev, dt_next,
                         m_state.time + 0.5 * dt_next, m_state.time + dt_next);
    m_nodes.report_jump(step, m_sink);
    // The contact check first: when contact creates the energy, its own cause is the one to
    // report, not the balance it upset.
    if (m_contact.active()) {
      const std::string warning =
          m_contact_energy.check(m_state, m_contact.stored_energy(), m_critical_id);
      if (!warning.empty()) m_sink.message(Severity::Warning, warning);
    }
    m_energy.check(m_state, totals, dt_next, m_nodes.largest_speed(), m_critical_id, m_sink);
    m_increment.check_floor(m_state, dt_next, m_critical_id);
    if (fault_injection::SITE == ParallelSite::SolverStop) [[unlikely]]
      fault_injection::stop_at(m_state.increment, m_state.time);

    // Output as it falls due; a status line every 1 % of the step.
    const FrameRequest frame = m_output.field_due(m_state.step_time, last);
    if (frame.any()) write_frame(frame);
    const bool history = m_output.history_due(m_state.step_time, last);
    if (history) write_history();
    const bool status = m_state.step_time >= next_status || last;
    if (status) {
      write_status();
      next_status = (std::floor(m_state.step_time / (0.01 * period)) + 1.0) * 0.01 * period;
    }
    if (last) break;
    if (const int signal = stop_requested(); signal != 0) {
      m_stopped_by = signal;
      write_interrupted(frame.any(), history);
      if (!status) write_status();
      break;
    }
  }
  m_contact.end_step();
  m_increment.report_step(step);
  m_loop_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - loop_start).count();
  const LoopShares shares_end = loop_shares();
  m_loop_shares.output += shares_end.output - shares_start.output;
  m_loop_shares.exchange += shares_end.exchange - shares_start.exchange;
  m_loop_shares.wait += shares_end.wait - shares_start.wait;
}

int ExplicitSolver::Impl::local_signal() const {
  return m_options.stop_signal != nullptr ? static_cast<int>(*m_options.stop_signal) : 0;
}

int ExplicitSolver::Impl::stop_requested() const {
  // Distributed runs stop at the same increment on every rank: the largest signal of the
  // ranks, gathered with the kinetic sums of this increment's nodal update.
  return m_run ? m_shared_signal : local_signal();
}

void ExplicitSolver::Impl::write_interrupted(bool frame_written, bool history_written) {
  if (m_output.has_field() && !frame_written) write_frame(m_output.field_all());
  if (m_output.has_history() && !history_written) write_history();
}

void ExplicitSolver::Impl::report_drift() {
  if (!m_started) return;
  const EnergyDrift& d = m_energy.largest_drift();
  const std::string text = d.fraction > 0.0 ? "largest energy balance drift: " + describe(d)
                                            : "largest energy balance drift: none";
  m_sink.message(Severity::Info, text);
  m_sink.status_note(text);
  m_sink.energy_drift(
      {d.fraction, d.drift, d.fraction > 0.0 ? d.largest : m_energy.scale(), d.time});
}

void ExplicitSolver::Impl::end_failed(const std::string& cause) noexcept {
  try {
    report_drift();
  } catch (...) {  // NOLINT(bugprone-empty-catch): the failure itself matters more
  }
  try {
    // The partition still goes to the summary; the ranks' times would need a collective,
    // which a rank failing alone would never join.
    if (m_run) m_sink.distribution(partition_summary());
  } catch (...) {  // NOLINT(bugprone-empty-catch): the failure itself matters more
  }
  try {
    const RunSummary s = summary();
    m_sink.end_run(RunStatus::Failed, cause, s.timers, s.element_cycles_per_second);
  } catch (...) {  // NOLINT(bugprone-empty-catch): the first error is the one to report
  }
}

void ExplicitSolver::Impl::write_frame(const FrameRequest& what) {
  const double exchanged = m_run ? m_run->exchange_seconds() : 0.0;
  if (m_run && !m_output.shared_frames()) {
    // Rank 0 writes the frame alone (--gather-frames): gathering it is part of its output.
    ScopedTimer timer(m_timers, Phase::Output);
    gather_state();
  }
  m_output.write_frame(m_state, what, m_elements, m_contact, m_nodes);
  // The frame's gathers count as exchanges (and waits) in the summary, not as output too.
  if (m_run) m_output_exchange += m_run->exchange_seconds() - exchanged;
}

void ExplicitSolver::Impl::write_history() {
  // Energies alone are everyone's; the nodes a row reads come from their owners.
  if (m_run && !m_output.history_nodes().empty()) {
    m_nodes.sync_rotation(m_state);
    m_run->gather_nodes_to_root(
        m_output.history_nodes(),
        {&m_state.position, &m_state.velocity, &m_state.acceleration, &m_state.reaction,
         &m_state.rotation, &m_state.angular_velocity, &m_state.reaction_moment});
  }
  m_output.write_history(m_state, m_contact, m_nodes);
}

void ExplicitSolver::Impl::write_status() {
  m_output.write_status(m_state, m_next.dt, cause_name(m_next.cause), m_critical_id,
                        m_contact.critical_contact_node());
}

RunSummary ExplicitSolver::Impl::summary() const {
  RunSummary s = m_output.summary(m_state, m_elements.size(), m_loop_seconds);
  s.energy_drift = m_energy.largest_drift().fraction;
  s.energy_drift_time = m_energy.largest_drift().time;
  return s;
}

RunSummary ExplicitSolver::Impl::run() {
  try {
    for (int step = 0; step < static_cast<int>(m_model.steps.size()) && m_stopped_by == 0; ++step)
      run_step(step);
  } catch (const SolverError& e) {
    // end_run records the error in every log; no separate message (it would repeat).
    end_failed(e.what());
    throw;
  } catch (const std::exception& e) {
    // An internal or I/O error (std::bad_alloc, a failed write): its own cause, not a
    // generic one, wherever it can still be written.
    end_failed(e.what());
    throw;
  }
  report_drift();
  report_exchange();
  RunSummary s = summary();
  if (m_stopped_by != 0) {
    s.stop_signal = m_stopped_by;
    m_sink.end_run(RunStatus::Interrupted, interrupted_text(), s.timers,
                   s.element_cycles_per_second);
    return s;
  }
  m_sink.end_run(RunStatus::Completed, "", s.timers, s.element_cycles_per_second);
  return s;
}

ExplicitSolver::Impl::LoopShares ExplicitSolver::Impl::loop_shares() const {
  LoopShares s;
  s.output = m_timers.seconds(Phase::Output) - m_output_exchange;
  if (m_run) {
    s.exchange = m_run->exchange_seconds();
    s.wait = m_run->exchange_seconds(DistributedRun::WAITS);
  }
  return s;
}

DistributionSummary ExplicitSolver::Impl::partition_summary() const {
  DistributionSummary d = m_distribution;
  d.ranks.resize(static_cast<std::size_t>(m_run->size()));
  for (int r = 0; r < m_run->size(); ++r) {
    const partition::PartPlan& p = m_run->exchange_plan().part[r];
    DistributionSummary::Rank& k = d.ranks[static_cast<std::size_t>(r)];
    k.elements = static_cast<Index>(p.elements.size());
    k.owned_nodes = static_cast<Index>(p.owned.size());
    k.interface_nodes = static_cast<Index>(p.interface_nodes.size());
    k.neighbours = static_cast<Index>(p.neighbours.size());
  }
  return d;
}

void ExplicitSolver::Impl::report_exchange() {
  if (!m_run) return;
  // Every rank's time in exchanges and collectives (waits included) against the time loop.
  std::vector<int> counts;
  const DistributedRun& run = *m_run;
  constexpr std::size_t WIDTH = 24;
  const ContactRows::BuildValues build = m_contact.rows_per_build();
  // The tie rows' values per increment (tie_routes.hpp) after the times and contact values.
  const auto with_ties = [this](std::vector<Real> values) {
    const auto increments = static_cast<double>(std::max<Index>(1, m_tie_traffic.increments));
    for (const double v : {m_tie_traffic.received, m_tie_traffic.sent, m_tie_traffic.whole})
      values.push_back(v / increments);
    return values;
  };
  const std::vector<Real> all =
      m_run->allgather(with_ties({run.exchange_seconds(),
                                  run.exchange_seconds(DistributedRun::NEIGHBOURS),
                                  run.exchange_seconds(DistributedRun::SHIP),
                                  run.exchange_seconds(DistributedRun::GATHERS),
                                  m_loop_seconds,
                                  static_cast<Real>(m_nodes.integrated_count()),
                                  m_loop_shares.exchange,
                                  m_loop_shares.wait,
                                  m_loop_shares.output,
                                  m_timers.seconds(Phase::ContactSearch),
                                  m_timers.seconds(Phase::ContactForce),
                                  m_contact.sharing_seconds(),
                                  m_contact.rows_received().first,
                                  m_contact.rows_received().second,
                                  m_contact.rows_sent(),
                                  build.received,
                                  build.sent,
                                  build.lists_received,
                                  build.lists_sent,
                                  m_contact.slot_values().first,
                                  m_contact.slot_values().second}),
                       counts);
  // The summary's partition and times (rank 0's sink keeps them).
  DistributionSummary d = partition_summary();
  d.times_gathered = true;
  for (int r = 0; r < run.size(); ++r) {
    const Real* t = &all[WIDTH * static_cast<std::size_t>(r)];
    DistributionSummary::Rank& k = d.ranks[static_cast<std::size_t>(r)];
    k.time_loop = t[4];
    k.exchange = t[6] - t[7];
    k.wait = t[7];
    k.output = t[8];
    k.compute = std::max(0.0, t[4] - t[6] - t[8]);
    k.contact_search = t[9];
    k.contact_force = t[10];
    k.contact_exchange = t[11];
    k.contact_values = t[12];
    k.contact_values_whole = t[13];
    k.contact_values_sent = t[14];
    k.contact_build_received = t[15];
    k.contact_build_sent = t[16];
    k.contact_lists_received = t[17];
    k.contact_lists_sent = t[18];
    k.contact_slot_received = t[19];
    k.contact_slot_sent = t[20];
    k.tie_values = t[21];
    k.tie_values_sent = t[22];
    k.tie_values_whole = t[23];
  }
  m_sink.distribution(d);
  for (int r = 0; r < m_run->size(); ++r) {
    const Real* t = &all[WIDTH * static_cast<std::size_t>(r)];
    m_sink.message(Severity::Info,
                   "mpi: rank " + std::to_string(r) + ": exchanges and collectives " +
                       format_real(t[0]) + " s of " + format_real(t[4]) + " s in the time loop (" +
                       format_real(t[4] > 0.0 ? 100.0 * t[0] / t[4] : 0.0) +
                       " %, waits for slower ranks and setup included): neighbours " +
                       format_real(t[1]) + " s, chunk forces " + format_real(t[2]) +
                       " s, gathers and reductions " + format_real(t[3]) +
                       " s; its nodal update moves " + std::to_string(static_cast<Index>(t[5])) +
                       " of " + std::to_string(m_model.node_count()) + " nodes");
  }
}

std::string ExplicitSolver::Impl::interrupted_text() const {
  const std::string signal = m_stopped_by == SIGINT    ? "SIGINT"
                             : m_stopped_by == SIGTERM ? "SIGTERM"
                                                       : "signal " + std::to_string(m_stopped_by);
  return "interrupted by " + signal + " at t = " + format_real(m_state.time) + " s (step " +
         std::to_string(m_state.step + 1) + ", increment " + std::to_string(m_state.increment) +
         "); the last frame is written";
}

RunSummary ExplicitSolver::Impl::check() {
  if (!m_model.steps.empty()) {
    begin_step(0);
    ElementTotals totals;
    m_next = evaluate_forces(Pass::Check, 0.0, m_model.steps[0].time_period, totals);
    report_partition(m_model, m_rigid, m_ties, m_contact.engine(), m_options.partition_parts,
                     m_options.partition_method, m_options.partition_note, m_sink);
    m_sink.message(Severity::Info, "initial stable increment " + format_real(m_next.dt) +
                                       " s (element " + std::to_string(m_critical_id) +
                                       "), governed by " + cause_text(m_next.cause));
    Real kinetic = 0.0;
    for (Index i = 0; i < m_model.node_count(); ++i)
      for (int c = 0; c < 3; ++c)
        kinetic += 0.5 * m_state.mass[i] * m_state.velocity(i, c) * m_state.velocity(i, c);
    m_state.energies.kinetic = kinetic;
    FrameRequest all;
    all.displacement = all.velocity = all.acceleration = all.reaction = all.stress = true;
    all.plastic_strain = m_model.has_plasticity();
    write_frame(all);
    write_status();
  }
  const RunSummary s = summary();
  m_sink.end_run(RunStatus::Checked, "", s.timers, 0.0);
  return s;
}

ExplicitSolver::ExplicitSolver(const Model& model, OutputSink& sink, SolverOptions options) {
  // The parts are built in Impl's constructor; their setup (masses, colours, messages) is
  // timed here and handed over to the run's timers.
  PhaseTimers setup;
  {
    ScopedTimer timer(setup, Phase::Setup);
    m_saved_threads = omp_get_max_threads();
    m_threads = team_size(model, options.threads, m_saved_threads);
    if (m_threads != m_saved_threads) omp_set_num_threads(m_threads);
    try {
      m_impl = std::make_unique<Impl>(model, sink, options);
    } catch (...) {
      omp_set_num_threads(m_saved_threads);  // no destructor runs for a failed constructor
      throw;
    }
  }
  m_impl->add_setup_time(setup.seconds(Phase::Setup));
}

ExplicitSolver::~ExplicitSolver() {
  if (m_threads != m_saved_threads) omp_set_num_threads(m_saved_threads);
}

const State& ExplicitSolver::state() const {
  return m_impl->state();
}

RunSummary ExplicitSolver::run() {
  return m_impl->run();
}

RunSummary ExplicitSolver::check() {
  return m_impl->check();
}

}  // namespace xpl

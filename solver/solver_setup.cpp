// The set-up of a run (ExplicitSolver::Impl, explicit_solver_impl.hpp): the parts of the time
// loop built in order, the initial or imported state, and the set-up report.
#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/explicit_solver_impl.hpp"
#include "solver/message_text.hpp"
#include "solver/model_partition.hpp"

namespace xpl {

ExplicitSolver::Impl::Impl(const Model& model, OutputSink& sink, SolverOptions options)
    : m_model(model),
      m_sink(sink),
      m_options(options),
      m_state(initial_state(model)),
      m_rigid(model),
      m_ties(model, m_state),
      m_elements(model, m_rigid, m_state, m_timers),
      m_nodes(model, m_timers, m_elements.has_shells()),
      m_energy(model, options.energy_limit),
      m_increment(model, sink, options.dt_safety, options.dt_floor_ratio, m_energy.transit_time()),
      m_contact(model, sink, m_timers, m_increment, options.initial_state != nullptr),
      m_output(model, sink, m_timers) {
  if (m_ties.active()) {
    // Slave masses to their master corners before the rigid bodies sum theirs.
    m_ties.distribute_mass(m_state);
    m_elements.update_inverse_mass(m_ties.changed_nodes(), m_state, m_rigid);
    m_nodes.set_ties(&m_ties);
    m_contact.set_tied_nodes(m_ties.tied_nodes());
    m_contact.set_tie_slaves(m_ties.slave_points());
  }
  const std::vector<std::string> rigid_messages = set_up_rigid_bodies();
  if (m_options.initial_state != nullptr) apply_initial_state(*m_options.initial_state);
  report_setup(rigid_messages);
  if (m_options.distributed && DistributedRun::world_size() > 1) set_up_distribution();
}

namespace {

/// The runs of consecutive indices i < n with writer[i] == rank.
std::vector<std::pair<Index, Index>> runs_of(const std::vector<int>& writer, int rank) {
  std::vector<std::pair<Index, Index>> runs;
  const auto n = static_cast<Index>(writer.size());
  for (Index i = 0; i < n;) {
    if (writer[i] != rank) {
      ++i;
      continue;
    }
    const Index first = i;
    while (i < n && writer[i] == rank) ++i;
    runs.emplace_back(first, i - first);
  }
  return runs;
}

/// The rows each rank writes of each frame when every rank writes its own (FrameRows), by
/// rank: the rows each node's owner and each element's rank gather_to_root() and
/// gather_elements_to_root() send to rank 0, which writes those of the rest (rigid bodies'
/// elements, which every rank holds alike, and the nodes no rank owns: rank 0 moves the
/// rigid bodies' ones, set_rigid_roles()).
std::vector<FrameRows> frame_rows(const Model& model, const DistributedRun& run) {
  std::vector<int> node_writer(static_cast<std::size_t>(model.node_count()), 0);
  std::vector<int> element_writer(static_cast<std::size_t>(model.element_count()), 0);
  for (int r = 1; r < run.size(); ++r) {
    const partition::PartPlan& p = run.exchange_plan().part[r];
    for (const Index n : p.owned) node_writer[n] = r;
    for (const Index e : p.elements) element_writer[e] = r;
  }
  std::vector<FrameRows> rows(static_cast<std::size_t>(run.size()));
  for (int r = 0; r < run.size(); ++r) {
    rows[r].collective = true;
    rows[r].nodes = runs_of(node_writer, r);
    rows[r].elements = runs_of(element_writer, r);
  }
  return rows;
}

/// Rows in `runs`.
Index row_count(const std::vector<std::pair<Index, Index>>& runs) {
  Index n = 0;
  for (const auto& run : runs) n += run.second;
  return n;
}

}  // namespace

void ExplicitSolver::Impl::set_up_distribution() {
  if (const std::vector<std::string> refused =
          DistributedRun::refusals(m_model, m_options.initial_state != nullptr);
      !refused.empty())
    throw std::invalid_argument("distributed run: " + refused.front());
  const auto start = std::chrono::steady_clock::now();
  m_run = std::make_unique<DistributedRun>();
  DistributedRun& run = *m_run;
  // METIS on rank 0 (deterministic anyway) on the graph of the SIMD batches of the one-rank
  // layout, so that every batch, and its per-batch totals, belongs to one rank.
  std::vector<int> element_part;
  partition::MeshPartition metis;
  // The t = 0 contact candidate pairs and the tie bindings as extra edges (issue 37 item 2),
  // so that contact partners and tied surfaces tend to share a rank.
  if (run.rank() == 0)
    metis = m_elements.partition_batches(
        run.size(), m_options.partition_method, element_part,
        m_contact.start_candidates(m_state.position, m_elements, m_rigid),
        m_ties.active() ? m_ties.slave_master_nodes() : std::vector<std::pair<Index, Index>>{});
  run.broadcast(element_part);
  m_distribution.method = partition::method_name(metis.method);
  m_distribution.imbalance = metis.imbalance;
  m_distribution.interface_nodes = static_cast<Index>(metis.interface_nodes.size());
  m_distribution.cut_edges = metis.cut_edges;
  m_distribution.shared_frames = m_options.shared_frames;
  run.set_partition(m_model, element_part, m_elements.element_order(),
                    CentralDifference::NODE_CHUNK, m_rigid.element_body());
  m_elements.distribute(run);

  // Nodes this rank neither uses nor counts stay at rest (a node of no element moves on the
  // rank counting its chunk); each nodal chunk is counted by one rank (distributed_run.hpp).
  const Index n = m_model.node_count();
  const bool rotations = !m_state.rotary_inertia.empty();
  std::vector<unsigned char> counted(static_cast<std::size_t>(n), 0);
  // The nodes this rank moves: those its elements use, those of the chunks it counts, and
  // the nodes of the rigid bodies it owns or replays (set_rigid_roles(); the passes skip the
  // others). Tie nodes are moved where they live (tie_routes.hpp).
  std::vector<unsigned char> integrated(static_cast<std::size_t>(n), 0);
  for (Index i = 0; i < n; ++i) integrated[i] = run.counts(i) || run.in_part(i) ? 1 : 0;
  const std::vector<unsigned char> moves_body = set_rigid_roles(run, integrated);
  // The nodes of the rigid bodies this rank moves keep their motion.
  for (Index i = 0; i < n; ++i) {
    if (run.counts(i)) {
      counted[i] = 1;
    } else if (!run.in_part(i) && moves_body[i] == 0) {
      m_state.velocity.row(i).setZero();
      m_state.velocity_half.row(i).setZero();
      if (rotations) {
        m_state.angular_velocity.row(i).setZero();
        m_state.angular_velocity_half.row(i).setZero();
      }
    }
  }
  const auto share = [this, &run, counts = std::vector<int>()](
                         std::vector<KineticSums>& sums, std::vector<Real>& speed,
                         std::vector<Real>& rows, bool same_counts) mutable {
    // Translations, rotations, speeds (and a 0): three blocks of two values per chunk; the
    // stop signal (stop_requested()) and the prescribed DOFs' rows ride along.
    std::vector<Real> values;
    values.reserve(sums.size() * 2 + speed.size() * 2);
    for (const KineticSums& s : sums) values.insert(values.end(), {s.centred, s.spread});
    for (const Real v : speed) values.insert(values.end(), {v, 0.0});
    m_shared_signal = local_signal();
    run.share_chunks(values, 2, 3, m_shared_signal, rows, counts, same_counts && !counts.empty());
    for (std::size_t k = 0; k < sums.size(); ++k) sums[k] = {values[2 * k], values[2 * k + 1]};
    for (std::size_t k = 0; k < speed.size(); ++k) speed[k] = values[2 * (sums.size() + k)];
  };
  m_nodes.set_distribution(share, std::move(counted), integrated);
  share_features(run);
  std::vector<FrameRows> rows;
  if (m_options.shared_frames) rows = frame_rows(m_model, run);

  // The report (rank 0's sink writes it).
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  m_sink.message(Severity::Info,
                 "mpi: " + std::to_string(run.size()) +
                     " ranks, distributed time loop (issue 37 item 3): each rank computes the "
                     "forces of its elements, interface forces go to the neighbours as "
                     "per-corner contributions summed in the one-rank order; " +
                     (m_options.shared_frames
                          ? std::string("every rank writes its nodes' and elements' rows of "
                                        "each frame into JOB.h5 (parallel HDF5), rank 0 the rest")
                          : std::string("rank 0 writes the results")));
  if (run.rank() == 0) {
    m_sink.message(Severity::Info,
                   "mpi: the partition below is of the SIMD batches (each up to 8 elements of one "
                   "colour, spread along the mesh: its vertices are batches, not elements)");
    for (const std::string& line : partition::partition_report(metis, seconds))
      m_sink.message(Severity::Info, line);
  }
  const partition::ExchangePlan& plan = run.exchange_plan();
  for (int r = 0; r < run.size(); ++r) {
    const partition::PartPlan& p = plan.part[r];
    m_sink.message(Severity::Info,
                   "mpi: rank " + std::to_string(r) + ": " + std::to_string(p.elements.size()) +
                       " elements (whole SIMD batches), " + std::to_string(p.owned.size()) +
                       " owned nodes, " + std::to_string(p.interface_nodes.size()) +
                       " interface nodes, " + std::to_string(p.neighbours.size()) +
                       " neighbour(s), " + std::to_string(p.send_slots()) +
                       " corner contributions sent per increment, the forces of " +
                       std::to_string(run.ship_count(r)) + " nodes received for its nodal chunks");
    if (!rows.empty())
      m_sink.message(Severity::Info, "mpi: rank " + std::to_string(r) + " writes the rows of " +
                                         std::to_string(row_count(rows[r].nodes)) + " nodes (" +
                                         std::to_string(rows[r].nodes.size()) +
                                         " run(s) of consecutive rows) and " +
                                         std::to_string(row_count(rows[r].elements)) +
                                         " elements (" + std::to_string(rows[r].elements.size()) +
                                         " run(s)) of each frame");
  }
  report_rigid_owners(run);
  report_tie_routes();
  if (!rows.empty()) m_output.set_frame_rows(std::move(rows[run.rank()]));
}

void ExplicitSolver::Impl::report_rigid_owners(const DistributedRun& run) {
  if (m_rigid.empty()) return;
  // Each body's owner, the body nodes each rank integrates (row_source()), and the forces
  // each rank receives and sends per increment (rigid_bodies.hpp).
  const auto size = static_cast<std::size_t>(run.size());
  std::vector<Index> bodies(size, 0), sources(size, 0), received(size, 0), sent(size, 0);
  for (const int owner : m_body_owner) ++bodies[owner];
  const std::vector<Index>& node_body = m_rigid.node_body();
  for (Index i = 0; i < m_model.node_count(); ++i) {
    if (node_body[i] == NO_INDEX) continue;
    const int source = run.row_source(i), owner = m_body_owner[node_body[i]];
    ++sources[source];
    if (source != owner) ++received[owner], ++sent[source];
  }
  for (int r = 0; r < run.size(); ++r)
    m_sink.message(Severity::Info, "mpi: rank " + std::to_string(r) + " updates " +
                                       std::to_string(bodies[r]) + " rigid bod" +
                                       (bodies[r] == 1 ? "y" : "ies") + " and integrates " +
                                       std::to_string(sources[r]) +
                                       " body nodes; per increment it receives "
                                       "the forces of " +
                                       std::to_string(received[r]) + " and sends those of " +
                                       std::to_string(sent[r]) + " (point to point)");
}

void ExplicitSolver::Impl::report_tie_routes() {
  for (int r = 0; r < static_cast<int>(m_tie_ranks.size()); ++r) {
    const TieRoutes::Rank& k = m_tie_ranks[static_cast<std::size_t>(r)];
    m_sink.message(
        Severity::Info,
        "mpi: rank " + std::to_string(r) + " ties: gathers slave forces into " +
            std::to_string(k.masters) + " master nodes and moves " + std::to_string(k.slaves) +
            " slave nodes; per increment it receives the forces of " +
            std::to_string(k.forces_received) + " slave nodes and the motion of " +
            std::to_string(k.motion_received) + " master nodes, and sends " +
            std::to_string(k.forces_sent) + " and " + std::to_string(k.motion_sent) +
            " (point to point; gathering every tie node took " + std::to_string(k.whole_forces) +
            " and " + std::to_string(k.whole_motion) + ")");
  }
}

void ExplicitSolver::Impl::share_features(DistributedRun& run) {
  m_contact.set_distribution(&run, m_options.shared_contact, !m_options.shared_frames);
  m_nodes.set_load_share(
      [&run](const std::vector<Index>& nodes, const std::vector<NodalVectors*>& rows) {
        run.share_rows(nodes, {rows.begin(), rows.end()}, rows);
      });
  if (m_ties.active()) {
    // Each rank gathers into the master corners it integrates and makes the slaves it
    // integrates follow, on the rows of the others' nodes it receives point to point.
    TieRoutes routes = make_tie_routes(m_ties.slave_master_nodes(), run, m_model.node_count());
    m_ties.set_local(routes.gathers, routes.follows);
    const TieRoutes::Rank mine = routes.ranks[static_cast<std::size_t>(run.rank())];
    m_tie_ranks = std::move(routes.ranks);
    // Values per increment for the summary: 3 per row of each array the route carries.
    m_nodes.set_tie_share(
        [this, &run, route = std::move(routes.forces),
         mine](const std::vector<NodalVectors*>& rows) {
          const auto width = static_cast<double>(3 * rows.size());
          ++m_tie_traffic.increments;
          m_tie_traffic.received += width * static_cast<double>(mine.forces_received);
          m_tie_traffic.sent += width * static_cast<double>(mine.forces_sent);
          m_tie_traffic.whole += width * static_cast<double>(mine.whole_forces);
          run.route_rows(route, rows);
        },
        [this, &run, route = std::move(routes.motion),
         mine](const std::vector<NodalVectors*>& rows) {
          const auto width = static_cast<double>(3 * rows.size());
          m_tie_traffic.received += width * static_cast<double>(mine.motion_received);
          m_tie_traffic.sent += width * static_cast<double>(mine.motion_sent);
          m_tie_traffic.whole += width * static_cast<double>(mine.whole_motion);
          run.route_rows(route, rows);
        });
  }
  if (!m_rigid.empty()) {
    // The forces on each body's nodes (elements, contact, loads) from the ranks integrating
    // them to the body's owner only, point to point, so that the owner's update of the body
    // is the one-rank update.
    DistributedRun::RowRoute route;
    route.send.assign(static_cast<std::size_t>(run.size()), {});
    route.receive = route.send;
    const std::vector<Index>& node_body = m_rigid.node_body();
    for (Index i = 0; i < m_model.node_count(); ++i) {
      if (node_body[i] == NO_INDEX) continue;
      const int to = m_body_owner[node_body[i]], from = run.row_source(i);
      if (from == to) continue;
      if (from == run.rank()) route.send[to].push_back(i);
      if (to == run.rank()) route.receive[from].push_back(i);
    }
    m_nodes.set_rigid_share(
        [&run, route = std::move(route)](const std::vector<NodalVectors*>& rows) {
          run.route_rows(route, rows);
        });
  }
}

std::vector<unsigned char> ExplicitSolver::Impl::set_rigid_roles(
    const DistributedRun& run, std::vector<unsigned char>& integrated) {
  // Each body is owned by the rank integrating most of its nodes (row_source(); ties: the
  // lowest), so that the fewest forces travel; a rank that moves any node of a body (it uses,
  // counts or writes it) replays the body's motion and so moves all its nodes.
  const Index n = m_model.node_count();
  std::vector<unsigned char> moves(static_cast<std::size_t>(n), 0);
  m_body_owner.assign(static_cast<std::size_t>(m_rigid.body_count()), 0);
  std::vector<unsigned char> roles(m_body_owner.size(), 0);
  std::vector<Index> sources(static_cast<std::size_t>(run.size()));
  for (Index b = 0; b < m_rigid.body_count(); ++b) {
    const std::vector<Index> nodes = m_rigid.body_nodes(b);
    std::fill(sources.begin(), sources.end(), 0);
    bool needed = false;
    for (const Index i : nodes) {
      ++sources[run.row_source(i)];
      needed = needed || integrated[i] != 0 || run.owner(i) == run.rank();
    }
    m_body_owner[b] =
        static_cast<int>(std::max_element(sources.begin(), sources.end()) - sources.begin());
    roles[b] = m_body_owner[b] == run.rank() ? 1 : needed ? 2 : 0;
    if (roles[b] != 0)
      for (const Index i : nodes) integrated[i] = moves[i] = 1;
  }
  m_rigid.set_roles(std::move(roles));
  return moves;
}

void ExplicitSolver::Impl::gather_state() {
  if (!m_run) return;
  m_nodes.sync_rotation(m_state);
  for (NodalVectors* rows :
       {&m_state.position, &m_state.velocity, &m_state.acceleration, &m_state.reaction,
        &m_state.rotation, &m_state.angular_velocity, &m_state.reaction_moment})
    m_run->gather_to_root(*rows);
}

State ExplicitSolver::Impl::initial_state(const Model& model) {
  const Index n = model.node_count();
  State state;
  state.reference = model.coordinates;
  state.position = model.coordinates;
  state.velocity =
      model.initial_velocity.rows() == n ? model.initial_velocity : NodalVectors::Zero(n, 3);
  state.velocity_half = state.velocity;
  state.acceleration = NodalVectors::Zero(n, 3);
  state.reaction = NodalVectors::Zero(n, 3);
  state.mass.assign(n, 0.0);
  return state;
}

std::vector<std::string> ExplicitSolver::Impl::set_up_rigid_bodies() {
  if (m_rigid.empty()) return {};
  if (!m_elements.has_shells()) {
    // The reference nodes carry rotations (UR, VR, RM) even without shells.
    const Index n = m_model.node_count();
    m_state.rotation = NodalVectors::Zero(n, 3);
    m_state.angular_velocity = NodalVectors::Zero(n, 3);
    m_state.angular_velocity_half = NodalVectors::Zero(n, 3);
    m_state.reaction_moment = NodalVectors::Zero(n, 3);
  }
  return m_rigid.setup(m_model, m_state.mass, m_state);
}

void ExplicitSolver::Impl::apply_initial_state(const InitialState& imported) {
  const Index n = m_model.node_count();
  if (imported.displacement.rows() != n || imported.velocity.rows() != n)
    throw std::invalid_argument("imported state: U and V must have one row per node");
  m_state.position = m_state.reference + imported.displacement;
  m_state.velocity = imported.velocity;
  m_state.velocity_half = imported.velocity;
  if (m_elements.has_shells() && imported.rotation.rows() == n) {
    m_nodes.import_rotation(imported.rotation, m_state);
    if (imported.angular_velocity.rows() == n) {
      m_state.angular_velocity = imported.angular_velocity;
      m_state.angular_velocity_half = imported.angular_velocity;
    }
  }
  if (!imported.stress.empty())
    m_elements.set_stress(m_state.position, imported.stress,
                          imported.stress_bottom.empty() ? imported.stress : imported.stress_bottom,
                          imported.stress_top.empty() ? imported.stress : imported.stress_top);
  if (!imported.peeq.empty() || !imported.peeq_middle.empty())
    m_elements.set_plastic_strain(imported.peeq, imported.peeq_middle, imported.peeq_bottom,
                                  imported.peeq_top);
  if (!imported.hourglass_state.empty()) m_elements.set_hourglass_state(imported.hourglass_state);
  if (!imported.shell_thickness.empty()) m_elements.set_shell_thickness(imported.shell_thickness);
}

void ExplicitSolver::Impl::report_setup(const std::vector<std::string>& rigid_messages) {
  m_sink.begin_run(m_model);
  const InitialState* imported = m_options.initial_state;
  if (imported != nullptr)
    m_sink.message(Severity::Info,
                   "the run starts from the imported state of " + imported->source +
                       " (positions, velocities" +
                       (imported->stress.empty() ? "" : ", element stresses") +
                       (imported->peeq.empty() ? "" : ", equivalent plastic strains") +
                       (imported->shell_thickness.empty() ? "" : ", shell thicknesses") +
                       (imported->hourglass_state.empty() ? "" : ", hourglass forces") +
                       "); time starts at 0. " +
                       (imported->hourglass_state.empty() ? "Hourglass forces and contact state"
                                                          : "Contact state") +
                       " start at zero; ALLSE counts the strain energy from here on");
  for (const DeckMessage& m : m_model.deck_messages)
    m_sink.message(m.warning ? Severity::Warning : Severity::Note, escape_control(m.text));
  for (const SectionControls& c : m_model.section_controls)
    if (c.hourglass == HourglassType::RelaxStiffness)
      m_sink.message(Severity::Note, "section controls " + c.name +
                                         ": HOURGLASS=RELAX STIFFNESS is run as STIFFNESS "
                                         "(Flanagan-Belytschko stiffness form)");
  for (const std::string& m : rigid_messages) m_sink.message(Severity::Info, m);
  for (const std::string& m : m_ties.messages()) m_sink.message(Severity::Info, m);
  for (const std::string& m : m_ties.warnings()) m_sink.message(Severity::Warning, m);
  m_elements.report_setup(m_state.reference, m_sink);
}

}  // namespace xpl

#include "solver/forces/contact_rows.hpp"

#include <algorithm>
#include <stdexcept>

#include "solver/distributed_run.hpp"

namespace xpl {

namespace {

constexpr std::size_t ROW_WIDTH = 6;  // position and v(n+½)

}  // namespace

void ContactRows::reset(const DistributedRun& run, std::vector<Index> nodes, Index n_nodes,
                        bool root_writes) {
  m_run = &run;
  m_root_writes = root_writes;
  m_all = std::move(nodes);
  m_integrated.assign(static_cast<std::size_t>(n_nodes), 0);
  m_integrated_count = 0;
  for (const Index n : m_all)
    if (run.row_source(n) == run.rank()) {
      m_integrated[n] = 1;
      ++m_integrated_count;
    }
  m_local.clear();
  m_send_nodes.clear();
  m_receive_nodes.clear();
  m_lists = false;
  m_partial = false;
}

void ContactRows::gather_all(const State& state, NodalVectors& position, NodalVectors& velocity) {
  m_run->share_rows(m_all, {&state.position, &state.velocity_half}, {&position, &velocity});
  m_values += static_cast<double>(ROW_WIDTH * (m_all.size() - m_integrated_count));
  ++m_gathers;
}

void ContactRows::gather(contact::ContactEngine& engine, const State& state, NodalVectors& position,
                         NodalVectors& velocity) {
  m_partial = false;
  const contact::BroadPhase& broad = engine.broad_phase();
  if (!m_lists || broad.build_count() == 0) {
    gather_all(state, position, velocity);
    return;
  }
  // Each rank the rows it asked for at the build, and to every rank this rank's largest
  // motion of the contact nodes it integrates (current in `state`; reduced by max below).
  const int rank = m_run->rank();
  const Real motion = broad.largest_motion_sq(state.position, m_integrated);
  // And the motion since the last update (the sleeping slots' path, ContactEngine).
  const Real step = engine.measure_step_motion(state.position, m_integrated);
  m_send.clear();
  for (int r = 0; r < m_run->size(); ++r) {
    for (const Index n : m_send_nodes[r])
      for (const NodalVectors* rows : {&state.position, &state.velocity_half})
        for (int c = 0; c < 3; ++c) m_send.push_back((*rows)(n, c));
    m_send.push_back(motion);
    m_send.push_back(step);
  }
  m_run->alltoall_into(m_send, m_send_counts, m_receive, m_receive_counts);
  std::size_t k = 0;
  Real largest = 0.0, largest_step = 0.0;
  for (int r = 0; r < m_run->size(); ++r) {
    for (const Index n : m_receive_nodes[r])
      for (NodalVectors* rows : {&position, &velocity})
        for (int c = 0; c < 3; ++c) (*rows)(n, c) = m_receive[k++];
    largest = std::max(largest, m_receive[k++]);
    largest_step = std::max(largest_step, m_receive[k++]);
    if (r != rank) m_values += static_cast<double>(m_receive_counts[r]);
  }
  for (const Index n : m_local) {
    position.row(n) = state.position.row(n);
    velocity.row(n) = state.velocity_half.row(n);
  }
  ++m_gathers;
  // The one-rank decision, bit for bit: the engine takes it rather than measure the motion
  // again on its copies. A build reads every contact node (the rows not sent above are as the
  // last whole gather left them).
  const bool due = broad.exceeds_rebuild_motion(largest);
  engine.decide_rebuild(due, largest_step);
  if (due)
    gather_all(state, position, velocity);
  else
    m_partial = true;
}

void ContactRows::update_lists(const contact::ContactEngine& engine, bool rebuilt) {
  if (m_partial && rebuilt)
    throw std::logic_error("contact rows: the broad phase was built on partly gathered rows");
  if (m_lists && !rebuilt) return;
  const int rank = m_run->rank();
  std::vector<char> mark(m_integrated.size(), 0);
  if (!engine.mark_read_nodes(mark)) return;  // the same answer on every rank
  // Every rank's marks: the nodes that may carry a contact force until the next build (a
  // slot's node, the corners of the faces it may touch), whose output rows their owners
  // write, and whose velocities (the work terms) the rank integrating them sends with the
  // forces (ContactEngine::share_forces()).
  std::vector<Real> mine;
  for (const Index n : m_all)
    if (mark[n] != 0) mine.push_back(static_cast<Real>(n));
  std::vector<int> counts;
  const std::vector<Real> read = m_run->allgather(mine, counts);
  std::vector<char> anyone(mark.size(), 0);
  for (const Real n : read) anyone[static_cast<std::size_t>(n)] = 1;
  // What this rank reads: its marks, the output rows it writes of those nodes, and around
  // each of them the faces whose areas and normals the node's area and normal sum, and whose
  // neighbours across an edge the search looks at (ContactEngine::update()).
  std::vector<char> seed = mark;
  for (const Index n : m_all)
    if (anyone[n] != 0 && (m_root_writes ? 0 : m_run->owner(n)) == rank) seed[n] = 1;
  const contact::SlaveNodes& slaves = engine.domain().slaves();
  const std::vector<contact::ContactFace>& faces = engine.domain().faces();
  std::vector<char> rows = seed;
  for (const Index n : m_all) {
    if (seed[n] == 0) continue;
    for (const Index g : slaves.faces_of(slaves.slot(n)))
      for (const Index a : faces[g].nodes) rows[a] = 1;
  }
  // The rows this rank integrates come from `state` (those of its own slots' velocities too).
  m_local.clear();
  m_receive_nodes.assign(static_cast<std::size_t>(m_run->size()), {});
  for (const Index n : m_all) {
    const int source = m_run->row_source(n);
    if (source == rank && (rows[n] != 0 || anyone[n] != 0))
      m_local.push_back(n);
    else if (source != rank && rows[n] != 0)
      m_receive_nodes[source].push_back(n);
  }
  // Each source learns which rows it sends this rank (point to point, at builds only).
  std::vector<int> asked(m_receive_nodes.size(), 0);
  std::vector<Real> wanted;
  for (std::size_t r = 0; r < m_receive_nodes.size(); ++r) {
    asked[r] = static_cast<int>(m_receive_nodes[r].size());
    for (const Index n : m_receive_nodes[r]) wanted.push_back(static_cast<Real>(n));
  }
  const std::vector<int> asked_of_me = m_run->alltoall_counts(asked);
  std::vector<Real> to_send;
  m_run->alltoall_into(wanted, asked, to_send, asked_of_me);
  m_send_nodes.assign(m_receive_nodes.size(), {});
  m_send_counts.resize(m_receive_nodes.size());
  m_receive_counts.resize(m_receive_nodes.size());
  std::size_t k = 0;
  for (std::size_t r = 0; r < m_receive_nodes.size(); ++r) {
    for (int i = 0; i < asked_of_me[r]; ++i)
      m_send_nodes[r].push_back(static_cast<Index>(to_send[k++]));
    m_send_counts[r] = static_cast<int>(ROW_WIDTH * m_send_nodes[r].size() + 2);
    m_receive_counts[r] = static_cast<int>(ROW_WIDTH * m_receive_nodes[r].size() + 2);
  }
  m_lists = true;
}

}  // namespace xpl

#include "solver/forces/contact_rows.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>

#include "solver/distributed_run.hpp"

namespace xpl {

namespace {

constexpr std::size_t ROW_WIDTH = 6;  // position and v(n+½)

}  // namespace

void ContactRows::reset(const DistributedRun& run, const contact::ContactEngine& engine,
                        std::vector<Index> nodes, Index n_nodes, bool root_writes) {
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
  m_ghost_built = false;
  // The rank sourcing each face (the one integrating its first corner, so one per face), and
  // the corners it needs of the ranks integrating them to box the face.
  const int rank = run.rank();
  const auto ranks = static_cast<std::size_t>(run.size());
  const std::vector<contact::ContactFace>& faces = engine.domain().faces();
  std::vector<std::pair<int, Index>> send, receive;
  m_sourced.clear();
  for (Index f = 0; f < static_cast<Index>(faces.size()); ++f) {
    const int source = run.row_source(faces[f].nodes[0]);
    if (source == rank) m_sourced.push_back(f);
    for (const Index a : faces[f].nodes) {
      const int from = run.row_source(a);
      if (from == source) continue;
      if (source == rank) receive.emplace_back(from, a);
      if (from == rank) send.emplace_back(source, a);
    }
  }
  const auto sorted = [ranks](std::vector<std::pair<int, Index>>& pairs) {
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    std::vector<std::vector<Index>> lists(ranks);
    for (const auto& [r, n] : pairs) lists[static_cast<std::size_t>(r)].push_back(n);
    return lists;
  };
  m_corner_send = sorted(send);
  m_corner_receive = sorted(receive);
}

ContactRows::BuildValues ContactRows::values_per_build() const {
  const double b = m_builds > 0 ? static_cast<double>(m_builds) : 1.0;
  const double l = m_list_makings > 0 ? static_cast<double>(m_list_makings) : 1.0;
  return {m_build_values.received / b, m_build_values.sent / b, m_build_values.lists_received / l,
          m_build_values.lists_sent / l};
}

void ContactRows::gather_all(const State& state, NodalVectors& position, NodalVectors& velocity) {
  m_run->share_rows(m_all, {&state.position, &state.velocity_half}, {&position, &velocity});
  m_values += static_cast<double>(ROW_WIDTH * (m_all.size() - m_integrated_count));
  m_sent += static_cast<double>(ROW_WIDTH * m_integrated_count * (m_run->size() - 1));
  ++m_gathers;
}

bool ContactRows::gather(contact::ContactEngine& engine, const State& state, NodalVectors& position,
                         NodalVectors& velocity) {
  m_partial = false;
  m_ghost_built = false;
  const contact::BroadPhase& broad = engine.broad_phase();
  if (!m_lists || broad.build_count() == 0) {
    gather_all(state, position, velocity);
    return false;
  }
  // Each rank the rows it asked for at the build, and to every rank this rank's largest
  // motion of the contact nodes it integrates (current in `state`; reduced by max) with their
  // motion since the last update (the sleeping slots' path, ContactEngine), from one walk.
  Real step = 0.0;
  const Real motion = engine.measure_motions(state.position, m_integrated, step);
  Real largest_step = 0.0;
  const Real largest =
      exchange_listed(state, position, velocity, motion, step, largest_step, m_values, m_sent);
  ++m_gathers;
  // The one-rank decision, bit for bit: the engine takes it rather than measure the motion
  // again on its copies. A build reads the ghost faces (build_ghosts()).
  const bool due = broad.exceeds_rebuild_motion(largest);
  engine.decide_rebuild(due, largest_step);
  m_partial = true;
  return due;
}

Real ContactRows::exchange_listed(const State& state, NodalVectors& position,
                                  NodalVectors& velocity, Real motion, Real step,
                                  Real& largest_step, double& received, double& sent) {
  const int rank = m_run->rank();
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
  Real largest = 0.0;
  largest_step = 0.0;
  for (int r = 0; r < m_run->size(); ++r) {
    for (const Index n : m_receive_nodes[r])
      for (NodalVectors* rows : {&position, &velocity})
        for (int c = 0; c < 3; ++c) (*rows)(n, c) = m_receive[k++];
    largest = std::max(largest, m_receive[k++]);
    largest_step = std::max(largest_step, m_receive[k++]);
    if (r == rank) continue;
    received += static_cast<double>(m_receive_counts[r]);
    sent += static_cast<double>(m_send_counts[r]);
  }
  for (const Index n : m_local) {
    position.row(n) = state.position.row(n);
    velocity.row(n) = state.velocity_half.row(n);
  }
  return largest;
}

void ContactRows::build_ghosts(contact::ContactEngine& engine, const State& state,
                               std::span<const Real> node_thickness, NodalVectors& position,
                               NodalVectors& velocity) {
  // This rank's own rows current in the copies: the build remembers their positions for the
  // next rebuild decisions (largest_motion_sq() over the nodes each rank integrates).
  std::vector<char> fresh = m_integrated;
  for (const Index n : m_all)
    if (m_integrated[n] != 0) {
      position.row(n) = state.position.row(n);
      velocity.row(n) = state.velocity_half.row(n);
    }
  exchange_ghost_positions(engine, state, node_thickness, position, fresh);
  // The faces whose boxes are the one-rank ones here: those with every corner current.
  const std::vector<contact::ContactFace>& faces = engine.domain().faces();
  std::vector<char> held(faces.size(), 0);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto& c = faces[f].nodes;
    held[f] = fresh[c[0]] != 0 && fresh[c[1]] != 0 && fresh[c[2]] != 0 && fresh[c[3]] != 0;
  }
  engine.build_shared_broad_phase(position, node_thickness, held);
  m_ghost_built = true;
  // The rows the new lists read, now (the search and springs of this increment read them).
  update_lists(engine, true);
  Real step = 0.0;  // a build starts the sleeping slots' records afresh: no path read
  exchange_listed(state, position, velocity, 0.0, 0.0, step, m_build_values.received,
                  m_build_values.sent);
  engine.decide_rebuild(false, 0.0);
  ++m_builds;
}

void ContactRows::exchange_ghost_positions(const contact::ContactEngine& engine, const State& state,
                                           std::span<const Real> node_thickness,
                                           NodalVectors& position, std::vector<char>& fresh) {
  const int rank = m_run->rank();
  const auto ranks = static_cast<std::size_t>(m_run->size());
  BuildValues& count = m_build_values;
  // The corners of the faces this rank sources that other ranks integrate (fixed lists).
  std::vector<int> send_counts(ranks, 0), receive_counts(ranks, 0);
  std::vector<Real> send, receive;
  for (std::size_t r = 0; r < ranks; ++r) {
    for (const Index n : m_corner_send[r])
      for (int c = 0; c < 3; ++c) send.push_back(state.position(n, c));
    send_counts[r] = static_cast<int>(3 * m_corner_send[r].size());
    receive_counts[r] = static_cast<int>(3 * m_corner_receive[r].size());
  }
  m_run->alltoall_into(send, send_counts, receive, receive_counts);
  std::size_t k = 0;
  for (std::size_t r = 0; r < ranks; ++r)
    for (const Index n : m_corner_receive[r]) {
      for (int c = 0; c < 3; ++c) position(n, c) = receive[k++];
      fresh[n] = 1;
    }
  count.sent += static_cast<double>(send.size());
  count.received += static_cast<double>(receive.size());
  // Each rank's box of the slots it scans: the contact nodes it integrates.
  std::vector<Real> box{std::numeric_limits<Real>::max(),    std::numeric_limits<Real>::max(),
                        std::numeric_limits<Real>::max(),    std::numeric_limits<Real>::lowest(),
                        std::numeric_limits<Real>::lowest(), std::numeric_limits<Real>::lowest()};
  for (const Index n : m_all)
    if (m_integrated[n] != 0)
      for (int d = 0; d < 3; ++d) {
        box[d] = std::min(box[d], state.position(n, d));
        box[3 + d] = std::max(box[3 + d], state.position(n, d));
      }
  std::vector<int> box_counts(ranks, 6);
  const std::vector<Real> boxes = m_run->allgather(box, box_counts, true);
  count.sent += static_cast<double>(6 * (ranks - 1));
  count.received += static_cast<double>(6 * (ranks - 1));
  // Each face this rank sources to every rank whose box its box, inflated as the broad phase
  // inflates it, meets (exact: the same bits as the receiver's broad phase computes; a node
  // inside the face's box and the rank's box makes them meet): its corners' positions.
  const std::vector<contact::ContactFace>& faces = engine.domain().faces();
  const std::span<const Real> depth = engine.domain().face_depths();
  const Real margin = engine.broad_phase().margin();
  std::vector<std::vector<Index>> to(ranks);
  for (const Index f : m_sourced) {
    Real lo[3], hi[3];
    contact::BroadPhase::face_box(faces[f], position, node_thickness,
                                  depth.empty() ? 0.0 : depth[f], lo, hi);
    for (std::size_t r = 0; r < ranks; ++r) {
      if (static_cast<int>(r) == rank) continue;
      const Real* b = &boxes[6 * r];
      bool meets = true;
      for (int d = 0; d < 3; ++d)
        meets = meets && lo[d] - margin <= b[3 + d] && hi[d] + margin >= b[d];
      if (meets) to[r].insert(to[r].end(), faces[f].nodes.begin(), faces[f].nodes.end());
    }
  }
  send.clear();
  for (std::size_t r = 0; r < ranks; ++r) {
    std::sort(to[r].begin(), to[r].end());
    to[r].erase(std::unique(to[r].begin(), to[r].end()), to[r].end());
    for (const Index n : to[r]) {
      send.push_back(static_cast<Real>(n));
      for (int c = 0; c < 3; ++c) send.push_back(position(n, c));
    }
    send_counts[r] = static_cast<int>(4 * to[r].size());
  }
  receive_counts = m_run->alltoall_counts(send_counts);
  m_run->alltoall_into(send, send_counts, receive, receive_counts);
  for (k = 0; k + 3 < receive.size(); k += 4) {
    const auto n = static_cast<Index>(receive[k]);
    for (int c = 0; c < 3; ++c) position(n, c) = receive[k + 1 + c];
    fresh[n] = 1;
  }
  count.sent += static_cast<double>(send.size());
  count.received += static_cast<double>(receive.size());
}

void ContactRows::tell_marks(const std::vector<char>& mark, std::vector<char>& anyone) {
  const int rank = m_run->rank();
  const auto ranks = static_cast<std::size_t>(m_run->size());
  std::vector<std::vector<Index>> tell(ranks);
  for (const Index n : m_all) {
    if (mark[n] == 0) continue;
    const int source = m_run->row_source(n);
    const int writer = m_root_writes ? 0 : m_run->owner(n);
    if (source != rank) tell[static_cast<std::size_t>(source)].push_back(n);
    if (writer != rank && writer != source && writer >= 0 && writer < m_run->size())
      tell[static_cast<std::size_t>(writer)].push_back(n);
  }
  std::vector<int> counts(ranks, 0);
  std::vector<Real> send, receive;
  for (std::size_t r = 0; r < ranks; ++r) {
    counts[r] = static_cast<int>(tell[r].size());
    for (const Index n : tell[r]) send.push_back(static_cast<Real>(n));
  }
  const std::vector<int> told = m_run->alltoall_counts(counts);
  m_run->alltoall_into(send, counts, receive, told);
  for (const Real n : receive) anyone[static_cast<std::size_t>(n)] = 1;
  ++m_list_makings;
  for (std::size_t r = 0; r < ranks; ++r) {
    if (static_cast<int>(r) == rank) continue;
    m_build_values.lists_sent += static_cast<double>(counts[r] + 1);
    m_build_values.lists_received += static_cast<double>(told[r] + 1);
  }
}

void ContactRows::update_lists(const contact::ContactEngine& engine, bool rebuilt) {
  if (m_partial && rebuilt && !m_ghost_built)
    throw std::logic_error("contact rows: the broad phase was built on partly gathered rows");
  if (m_lists && !rebuilt) return;
  const int rank = m_run->rank();
  std::vector<char> mark(m_integrated.size(), 0);
  if (!engine.mark_read_nodes(mark)) return;  // the same answer on every rank
  // Every rank's marks are the nodes that may carry a contact force until the next build (a
  // slot's node, the corners of the faces it may touch): each goes to the rank integrating
  // the node (it copies the node's rows from `state`: their velocities travel with the
  // forces, ContactEngine::share_forces()) and to the rank writing its output rows (the
  // contact pressure reads its area and normal), point to point; `anyone` holds them here.
  std::vector<char> anyone = mark;
  tell_marks(mark, anyone);
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
  for (std::size_t r = 0; r < asked.size(); ++r) {
    if (static_cast<int>(r) == rank) continue;
    m_build_values.lists_sent += static_cast<double>(asked[r] + 1);
    m_build_values.lists_received += static_cast<double>(asked_of_me[r] + 1);
  }
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

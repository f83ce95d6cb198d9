#include "solver/forces/contact_rows.hpp"

#include <algorithm>
#include <stdexcept>

#include "solver/distributed_run.hpp"

namespace xpl {

namespace {

constexpr std::size_t ROW_WIDTH = 6;  // position and v(n+½)

}  // namespace

void ContactRows::reset(const DistributedRun& run, std::vector<Index> nodes, Index n_nodes) {
  m_run = &run;
  m_all = std::move(nodes);
  m_integrated.assign(static_cast<std::size_t>(n_nodes), 0);
  m_integrated_count = 0;
  for (const Index n : m_all)
    if (run.row_source(n) == run.rank()) {
      m_integrated[n] = 1;
      ++m_integrated_count;
    }
  m_of_rank.clear();
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
  const int rank = m_run->rank();
  m_mine.clear();
  for (const Index n : m_of_rank[rank])
    for (const NodalVectors* rows : {&state.position, &state.velocity_half})
      for (int c = 0; c < 3; ++c) m_mine.push_back((*rows)(n, c));
  // The rows this rank integrates are current in `state`: their largest motion since the
  // build, every rank's reduced by max below.
  m_mine.push_back(broad.largest_motion_sq(state.position, m_integrated));
  m_run->allgather_into(m_mine, m_counts, m_all_values);
  std::size_t k = 0;
  Real largest = 0.0;
  for (int r = 0; r < m_run->size(); ++r) {
    for (const Index n : m_of_rank[r])
      for (NodalVectors* rows : {&position, &velocity})
        for (int c = 0; c < 3; ++c) (*rows)(n, c) = m_all_values[k++];
    largest = std::max(largest, m_all_values[k++]);
    if (r != rank) m_values += static_cast<double>(m_counts[r]);
  }
  ++m_gathers;
  // The one-rank decision, bit for bit: the engine takes it rather than measure the motion
  // again on its copies. A build reads every contact node (the rows not sent above are as the
  // last whole gather left them).
  const bool due = broad.exceeds_rebuild_motion(largest);
  engine.decide_rebuild(due);
  if (due)
    gather_all(state, position, velocity);
  else
    m_partial = true;
}

void ContactRows::update_lists(const contact::ContactEngine& engine, bool rebuilt) {
  if (m_partial && rebuilt)
    throw std::logic_error("contact rows: the broad phase was built on partly gathered rows");
  if (m_lists && !rebuilt) return;
  std::vector<char> mark(m_integrated.size(), 0);
  if (!engine.mark_read_nodes(mark)) return;  // the same answer on every rank
  std::vector<Real> mine;
  for (const Index n : m_all)
    if (mark[n] != 0) mine.push_back(static_cast<Real>(n));
  std::vector<int> counts;
  const std::vector<Real> read = m_run->allgather(mine, counts);
  std::fill(mark.begin(), mark.end(), 0);
  for (const Real n : read) mark[static_cast<std::size_t>(n)] = 1;
  // The faces around each read node: every rank updates the areas and normals of the slots
  // with candidates and of the face corners a force reaches (ContactEngine::update()).
  const contact::SlaveNodes& slaves = engine.domain().slaves();
  const std::vector<contact::ContactFace>& faces = engine.domain().faces();
  std::vector<char> rows = mark;
  for (const Index n : m_all) {
    if (mark[n] == 0) continue;
    for (const Index g : slaves.faces_of(slaves.slot(n)))
      for (const Index a : faces[g].nodes) rows[a] = 1;
  }
  m_of_rank.assign(static_cast<std::size_t>(m_run->size()), {});
  for (const Index n : m_all)
    if (rows[n] != 0) m_of_rank[m_run->row_source(n)].push_back(n);
  m_counts.resize(m_of_rank.size());
  for (std::size_t r = 0; r < m_of_rank.size(); ++r)
    m_counts[r] = static_cast<int>(ROW_WIDTH * m_of_rank[r].size() + 1);
  m_lists = true;
}

}  // namespace xpl

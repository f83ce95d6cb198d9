// The engine of a step's contact definition (ContactStage, contact_stage.hpp): the domain
// described from the deck's *CONTACT and *CONTACT PAIR definitions, the engine built on it, and
// the t = 0 candidate pairs of a distributed run's partition.
#include <algorithm>
#include <chrono>

#include "solver/distributed_run.hpp"
#include "solver/forces/contact_stage.hpp"

namespace xpl {

namespace {

/// The slot rows of the ranks of a distributed run, gathered in rank order. Without the
/// counts, one collective where it can: each rank sends a block of a capacity every rank
/// knows, its count first (the rows padded, or nothing but the count when they do not fit);
/// only when some rank's rows do not fit does a second gather follow, with the counts the
/// first gave, and the capacity grows to twice the largest count.
class RankSlotSharing final : public contact::SlotSharing {
 public:
  explicit RankSlotSharing(const DistributedRun& run) : m_run(run) {}
  std::vector<Real> gather(const std::vector<Real>& mine, std::vector<int>& counts,
                           bool counts_known) override {
    const auto start = std::chrono::steady_clock::now();
    std::vector<Real> all;
    if (counts_known) {
      all = m_run.allgather(mine, counts, true);
      count(counts);
      ++exchanges;  // exchange 2, once per shared update()
    } else {
      all = gather_found(mine, counts);
    }
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return all;
  }
  double seconds = 0.0;  ///< in gather(), waits for the other ranks included
  /// Values this rank received from and sent to the other ranks in gather() (the padding of
  /// the one-collective gather included), and the shared update()s (exchange 2 each).
  double received = 0.0, sent = 0.0;
  long exchanges = 0;

 private:
  std::vector<Real> gather_found(const std::vector<Real>& mine, std::vector<int>& counts) {
    const auto block = static_cast<std::size_t>(m_capacity) + 1;
    std::vector<Real> padded(block, 0.0);
    padded[0] = static_cast<Real>(mine.size());
    if (mine.size() <= static_cast<std::size_t>(m_capacity))
      std::copy(mine.begin(), mine.end(), padded.begin() + 1);
    std::vector<int> blocks(static_cast<std::size_t>(m_run.size()), static_cast<int>(block));
    const std::vector<Real> gathered = m_run.allgather(padded, blocks, true);
    count(blocks);
    counts.assign(blocks.size(), 0);
    int largest = 0;
    for (std::size_t r = 0; r < blocks.size(); ++r) {
      counts[r] = static_cast<int>(gathered[r * block]);
      largest = std::max(largest, counts[r]);
    }
    if (largest > m_capacity) {
      m_capacity = 2 * largest;
      count(counts);
      return m_run.allgather(mine, counts, true);
    }
    std::vector<Real> all;
    for (std::size_t r = 0; r < blocks.size(); ++r) {
      const auto first = gathered.begin() + static_cast<std::ptrdiff_t>(r * block + 1);
      all.insert(all.end(), first, first + counts[r]);
    }
    return all;
  }

  /// Counts one allgather of `counts` values per rank into `received` and `sent`.
  void count(const std::vector<int>& counts) {
    const auto me = static_cast<std::size_t>(m_run.rank());
    for (std::size_t r = 0; r < counts.size(); ++r)
      if (r != me) {
        received += counts[r];
        sent += counts[me];
      }
  }

  const DistributedRun& m_run;
  int m_capacity = 1024;  ///< values per rank the one-collective gather carries
};

}  // namespace

void ContactStage::share_slots() {
  if (m_run->size() < 2) return;
  const std::string ranks = std::to_string(m_run->size()) + " ranks";
  if (!m_shared) {
    m_sink.message(Severity::Info, "mpi: contact: every rank runs the whole contact pass of the " +
                                       ranks + " (--contact-redundant)");
    return;
  }
  const contact::SlaveNodes& slaves = m_engine->domain().slaves();
  std::vector<int> slot_rank(static_cast<std::size_t>(slaves.size()), 0);
  Index mine = 0;
  for (Index s = 0; s < slaves.size(); ++s) {
    slot_rank[s] = m_run->row_source(slaves.nodes()[s]);
    mine += slot_rank[s] == m_run->rank() ? 1 : 0;
  }
  m_sink.message(Severity::Info,
                 "mpi: contact shared out among the " + ranks +
                     ": each searches and computes the springs of the slave nodes it integrates "
                     "(rank 0: " +
                     std::to_string(mine) + " of " + std::to_string(slaves.size()) +
                     "), the results exchanged and assembled in the one-rank order");
  if (!m_sharing) m_sharing = std::make_unique<RankSlotSharing>(*m_run);
  m_engine->share_slots(std::move(slot_rank), m_run->rank(), m_sharing.get());
}

double ContactStage::sharing_seconds() const {
  return m_sharing ? static_cast<const RankSlotSharing&>(*m_sharing).seconds : 0.0;
}

std::pair<double, double> ContactStage::slot_values() const {
  if (!m_sharing) return {0.0, 0.0};
  const auto& sharing = static_cast<const RankSlotSharing&>(*m_sharing);
  const double n = sharing.exchanges > 0 ? static_cast<double>(sharing.exchanges) : 1.0;
  return {sharing.received / n, sharing.sent / n};
}

std::vector<std::pair<Index, Index>> ContactStage::start_candidates(const NodalVectors& position,
                                                                    const ElementSet& elements,
                                                                    const RigidBodies& rigid) {
  std::vector<std::pair<Index, Index>> candidates;
  const std::vector<std::string> names = m_pair_names;
  const std::unique_ptr<contact::ContactEngine> engine = build_engine(0, position, elements, rigid);
  m_pair_names = names;
  if (!engine) return candidates;
  engine->probe(position, elements.node_thickness());
  const contact::BroadPhase& broad = engine->broad_phase();
  const std::vector<Index>& slaves = engine->domain().slaves().nodes();
  const auto& faces = engine->domain().faces();
  for (Index s = 0; s < static_cast<Index>(slaves.size()); ++s)
    for (const Index f : broad.candidates(s))
      if (faces[f].element != NO_INDEX) candidates.emplace_back(slaves[s], faces[f].element);
  return candidates;
}

bool ContactStage::defines_contact(int step) const {
  const GeneralContact* general = nullptr;
  for (int k = step; k >= 0 && general == nullptr; --k)
    if (m_model.steps[k].contact) general = &*m_model.steps[k].contact;
  bool pairs = !m_model.contact_pairs.empty();
  for (int k = 0; k <= step; ++k) pairs = pairs || !m_model.steps[k].contact_pairs.empty();
  return pairs || (general != nullptr && (general->all_exterior || !general->inclusions.empty()));
}

std::unique_ptr<contact::ContactEngine> ContactStage::build_engine(int step,
                                                                   const NodalVectors& position,
                                                                   const ElementSet& elements,
                                                                   const RigidBodies& rigid) {
  const GeneralContact* general = nullptr;
  for (int k = step; k >= 0 && general == nullptr; --k)
    if (m_model.steps[k].contact) general = &*m_model.steps[k].contact;
  std::vector<ContactPair> pairs = m_model.contact_pairs;
  for (int k = 0; k <= step; ++k)
    pairs.insert(pairs.end(), m_model.steps[k].contact_pairs.begin(),
                 m_model.steps[k].contact_pairs.end());
  m_pair_names.clear();
  const bool has_general =
      general != nullptr && (general->all_exterior || !general->inclusions.empty());
  if (!has_general && pairs.empty()) return nullptr;

  contact::DomainSpec spec = domain_spec(has_general ? general : nullptr, pairs);
  spec.element_body = rigid.element_body();
  // Rigid nodes of node-based surfaces (point nodes) touch deformable faces only.
  const bool node_based =
      std::any_of(spec.surfaces.begin(), spec.surfaces.end(),
                  [](const contact::DomainSurface& d) { return !d.nodes.empty(); });
  if (node_based && !spec.element_body.empty()) {
    spec.rigid_node.assign(static_cast<std::size_t>(m_model.node_count()), 0);
    for (Index i = 0; i < m_model.node_count(); ++i) spec.rigid_node[i] = rigid.is_rigid_node(i);
  }
  std::vector<contact::InteractionLaw> laws;
  for (const SurfaceInteraction& i : m_model.surface_interactions)
    laws.push_back({i.friction, i.linear ? i.linear_slope : 0.0});
  contact::ContactOptions options;
  if (has_general) options.penalty_scale = general->penalty_scale;
  const contact::ElementTopology topology{m_model.element_offsets, m_model.element_nodes,
                                          elements.element_kinds()};
  contact::ContactDomain domain(spec, topology, position);
  return std::make_unique<contact::ContactEngine>(std::move(domain), std::move(laws), options,
                                                  position, elements.node_thickness());
}

contact::DomainSpec ContactStage::domain_spec(const GeneralContact* general,
                                              const std::vector<ContactPair>& pairs) {
  contact::DomainSpec spec;
  std::vector<Index> domain_surface(m_model.surfaces.size(), NO_INDEX);
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
      const Surface& from = m_model.surfaces[model_surface];
      contact::DomainSurface d;
      d.name = from.name;
      for (const ElementFace& f : from.faces) d.faces.push_back({f.element, f.face});
      d.nodes = from.nodes;
      d.node_areas = from.node_areas;
      spec.surfaces.push_back(std::move(d));
    }
    return k;
  };
  // A node-based surface is slave only (SPEC C13; the deck reader refuses it as a master): a
  // pair with one is one-sided, the node-based surface first, whatever the deck's order.
  auto node_based = [&](Index model_surface) {
    return model_surface != NO_INDEX && m_model.surfaces[model_surface].type == Surface::Type::Node;
  };
  auto name_of = [&](Index a, Index b) {
    return spec.surfaces[a].name + (a == b ? "" : "-" + spec.surfaces[b].name);
  };
  if (general != nullptr) {
    if (general->all_exterior) {
      const Index k = surface(NO_INDEX);
      spec.inclusions.push_back({k, k, false});
      m_pair_names.push_back(name_of(k, k));
    }
    for (const SurfacePair& p : general->inclusions) {
      const Index a = surface(p.first), b = surface(p.second);
      if (node_based(p.first))
        spec.inclusions.push_back({a, b, true});
      else if (node_based(p.second))
        spec.inclusions.push_back({b, a, true});
      else
        spec.inclusions.push_back({a, b, false});
      m_pair_names.push_back(name_of(a, b));
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
    m_pair_names.push_back(name_of(a, b));
  }
  return spec;
}

}  // namespace xpl

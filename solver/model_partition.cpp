#include "solver/model_partition.hpp"

#include <chrono>

namespace xpl {

namespace {

/// Relative costs per element cycle (model_partition.hpp says where they come from).
constexpr Real COST_C3D8R = 1.0;
constexpr Real COST_C3D8 = 2.2;
constexpr Real COST_S4R = 1.67;
constexpr Real PLASTIC_HEX_FACTOR = 1.12;
constexpr Real PLASTIC_SHELL_FACTOR = 1.67;

bool plastic_element(const Model& model, Index e) {
  const Index section = model.element_section[e];
  if (section == NO_INDEX) return false;
  const Index material = is_shell(model.element_types[e]) ? model.shell_sections[section].material
                                                          : model.solid_sections[section].material;
  return material != NO_INDEX && model.materials[material].plastic.has_value();
}

}  // namespace

Real element_cost(const Model& model, Index e, bool rigid) {
  if (rigid) return 0.0;
  const bool plastic = plastic_element(model, e);
  switch (model.element_types[e]) {
    case ElementType::C3D8R:
      return COST_C3D8R * (plastic ? PLASTIC_HEX_FACTOR : 1.0);
    case ElementType::C3D8:
      return COST_C3D8 * (plastic ? PLASTIC_HEX_FACTOR : 1.0);
    case ElementType::S4R:
      return COST_S4R * (plastic ? PLASTIC_SHELL_FACTOR : 1.0);
  }
  return COST_C3D8R;
}

partition::MeshPartition partition_model(const Model& model, const RigidBodies& rigid,
                                         const Ties& ties, const contact::ContactEngine* engine,
                                         int parts, partition::Method method) {
  const Index n_elements = model.element_count();
  const std::vector<Index>& element_body = rigid.element_body();
  std::vector<Real> weight(static_cast<std::size_t>(n_elements));
  for (Index e = 0; e < n_elements; ++e)
    weight[e] = element_cost(model, e, !element_body.empty() && element_body[e] != NO_INDEX);

  // The element of a node: the first that holds it (a node-based slave node may have none:
  // no edge).
  std::vector<Index> first_element(static_cast<std::size_t>(model.node_count()), NO_INDEX);
  for (Index e = n_elements - 1; e >= 0; --e)
    for (Index k = model.element_offsets[e]; k < model.element_offsets[e + 1]; ++k)
      first_element[model.element_nodes[k]] = e;
  std::vector<std::pair<Index, Index>> extra_edges;
  for (const auto& [slave, corner] : ties.slave_master_nodes())
    if (first_element[slave] != NO_INDEX && first_element[corner] != NO_INDEX)
      extra_edges.emplace_back(first_element[slave], first_element[corner]);
  if (engine != nullptr) {
    const contact::BroadPhase& broad = engine->broad_phase();
    const std::vector<Index>& slaves = engine->domain().slaves().nodes();
    const auto& faces = engine->domain().faces();
    if (broad.build_count() > 0)
      for (Index s = 0; s < static_cast<Index>(slaves.size()); ++s) {
        const Index e = first_element[slaves[s]];
        if (e == NO_INDEX) continue;
        for (const Index f : broad.candidates(s))
          if (faces[f].element != NO_INDEX && faces[f].element != e)
            extra_edges.emplace_back(e, faces[f].element);
      }
  }

  partition::PartitionInput input;
  input.node_count = model.node_count();
  input.element_offsets = model.element_offsets;
  input.element_nodes = model.element_nodes;
  input.element_weight = weight;
  input.coordinates = &model.coordinates;
  input.element_group = element_body;
  input.node_group = rigid.node_body();
  input.extra_edges = extra_edges;
  return partition::partition_mesh(input, parts, method);
}

void report_partition(const Model& model, const RigidBodies& rigid, const Ties& ties,
                      const contact::ContactEngine* engine, int parts, partition::Method method,
                      const std::string& note, OutputSink& sink) {
  if (parts < 2) return;
  if (!note.empty()) sink.message(Severity::Info, note);
  const auto start = std::chrono::steady_clock::now();
  const partition::MeshPartition p = partition_model(model, rigid, ties, engine, parts, method);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (const std::string& line : partition::partition_report(p, seconds))
    sink.message(Severity::Info, line);
}

}  // namespace xpl

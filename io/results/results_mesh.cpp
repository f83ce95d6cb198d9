#include "io/results/results_mesh.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace xpl::io {

namespace {

/// Every element type, in the order their groups are written.
constexpr ElementType ELEMENT_TYPES[] = {ElementType::C3D8R, ElementType::C3D8, ElementType::S4R};

/// The element types that occur in the model, in ELEMENT_TYPES order.
std::vector<ElementType> types_present(const Model& model) {
  std::vector<ElementType> present;
  for (ElementType type : ELEMENT_TYPES) {
    if (std::find(model.element_types.begin(), model.element_types.end(), type) !=
        model.element_types.end()) {
      present.push_back(type);
    }
  }
  return present;
}

/// Writes /mesh/TYPE: deck ids and connectivity of the elements of `type` in element order,
/// and in a mixed mesh their rows into /mesh/element_ids (the rows of the cell fields).
void write_type_group(hid_t mesh, const Model& model, ElementType type, bool mixed) {
  const auto corners = static_cast<std::size_t>(nodes_per_element(type));
  std::vector<std::int64_t> ids, rows, connectivity;
  for (Index e = 0; e < model.element_count(); ++e) {
    if (model.element_types[static_cast<std::size_t>(e)] != type) continue;
    ids.push_back(model.element_ids[static_cast<std::size_t>(e)]);
    rows.push_back(e);
    const Index* nodes = model.nodes_of(e);
    connectivity.insert(connectivity.end(), nodes, nodes + corners);
  }
  const h5::Handle group = h5::require_group(mesh, element_type_name(type));
  h5::write_int64(group.get(), "element_ids", ids, {ids.size()});
  h5::write_int64(group.get(), "connectivity", connectivity, {ids.size(), corners});
  if (mixed) h5::write_int64(group.get(), "element_rows", rows, {rows.size()});
}

/// The XDMF Mixed topology in element order: per element its cell code, then its node rows.
std::vector<std::int64_t> mixed_topology(const Model& model) {
  std::vector<std::int64_t> out;
  out.reserve(model.element_types.size() + model.element_nodes.size());
  for (Index e = 0; e < model.element_count(); ++e) {
    const ElementType type = model.element_types[static_cast<std::size_t>(e)];
    out.push_back(xdmf_cell_code(type));
    const Index* nodes = model.nodes_of(e);
    out.insert(out.end(), nodes, nodes + nodes_per_element(type));
  }
  return out;
}

/// Deck ids of the members of a set.
std::vector<std::int64_t> member_ids(const NamedSet& set, const std::vector<ExternalId>& ids) {
  std::vector<std::int64_t> out;
  out.reserve(set.members.size());
  for (Index m : set.members) out.push_back(ids.at(static_cast<std::size_t>(m)));
  return out;
}

/// A set name as an HDF5 link name ('/' would make it a path).
std::string link_name(std::string name) {
  for (char& c : name) {
    if (c == '/') c = '_';
  }
  return name;
}

/// Writes /mesh/GROUP/NAME (deck ids) and, for the XDMF file, /xdmf/sets/GROUP_rows/NAME
/// (zero-based rows) and /xdmf/sets/GROUP_flags/NAME (1 for members, else 0) of every set.
void write_sets(hid_t file, hid_t mesh, const std::string& group_name,
                const std::vector<NamedSet>& sets, const std::vector<ExternalId>& ids, bool node,
                std::vector<XdmfSet>& xdmf) {
  const h5::Handle group = h5::require_group(mesh, group_name);
  const std::string base = "/xdmf/sets/" + group_name;
  const h5::Handle rows_group = h5::require_group(file, base + "_rows");
  const h5::Handle flags_group = h5::require_group(file, base + "_flags");
  for (const NamedSet& set : sets) {
    const std::string link = link_name(set.name);
    const std::vector<std::int64_t> members = member_ids(set, ids);
    h5::write_int64(group.get(), link, members, {members.size()});
    std::vector<std::int64_t> rows(set.members.begin(), set.members.end());
    h5::write_int64(rows_group.get(), link, rows, {rows.size()});
    std::vector<std::uint8_t> flags(ids.size(), 0);
    for (Index m : set.members) flags[static_cast<std::size_t>(m)] = 1;
    h5::write_uint8(flags_group.get(), link, flags, {flags.size()});
    xdmf.push_back({set.name, node, static_cast<Index>(rows.size()), base + "_rows/" + link,
                    base + "_flags/" + link});
  }
}

/// Instances of an assembly model: /mesh/node_instance and /mesh/element_instance (index into
/// the instance list, -1 at the assembly level), /mesh/node_local_ids and
/// /mesh/element_local_ids (the ids in the part as the deck wrote them), and the instance and
/// part names (attributes `instances`, `instance_parts`, comma-separated, in index order).
/// Returns the names, comma-separated.
std::string write_instances(hid_t mesh, const Model& model) {
  std::string names, parts;
  for (const PartInstance& instance : model.instances) {
    names += (names.empty() ? "" : ",") + instance.name;
    parts += (parts.empty() ? "" : ",") + instance.part;
  }
  const auto as_int64 = [](const auto& values) {
    return std::vector<std::int64_t>(values.begin(), values.end());
  };
  const std::vector<std::int64_t> node_instance = as_int64(model.node_instance);
  const std::vector<std::int64_t> element_instance = as_int64(model.element_instance);
  h5::write_int64(mesh, "node_instance", node_instance, {node_instance.size()});
  h5::write_int64(mesh, "element_instance", element_instance, {element_instance.size()});
  h5::write_int64(mesh, "node_local_ids", model.node_local_ids, {model.node_local_ids.size()});
  h5::write_int64(mesh, "element_local_ids", model.element_local_ids,
                  {model.element_local_ids.size()});
  h5::set_string_attribute(mesh, "instances", names);
  h5::set_string_attribute(mesh, "instance_parts", parts);
  return names;
}

}  // namespace

const char* xdmf_cell_name(ElementType type) {
  switch (type) {
    case ElementType::C3D8R:
    case ElementType::C3D8:
      return "Hexahedron";
    case ElementType::S4R:
      return "Quadrilateral";
  }
  return "NoTopology";
}

std::int64_t xdmf_cell_code(ElementType type) {
  switch (type) {
    case ElementType::C3D8R:
    case ElementType::C3D8:
      return 9;
    case ElementType::S4R:
      return 5;
  }
  return 0;
}

std::vector<double> row_major(const NodalVectors& field) {
  std::vector<double> out(static_cast<std::size_t>(field.rows()) * 3);
  for (Eigen::Index i = 0; i < field.rows(); ++i) {
    for (int c = 0; c < 3; ++c) out[static_cast<std::size_t>(i) * 3 + c] = field(i, c);
  }
  return out;
}

XdmfMesh write_mesh_group(hid_t file, const Model& model) {
  const h5::Handle mesh = h5::require_group(file, "mesh");
  const auto n_nodes = static_cast<hsize_t>(model.node_count());
  if (model.coordinates.rows() != model.node_count()) {
    throw std::invalid_argument("model coordinates do not match the number of nodes");
  }
  h5::write_int64(mesh.get(), "node_ids", model.node_ids, {n_nodes});
  h5::write_real(mesh.get(), "coordinates", row_major(model.coordinates), {n_nodes, 3});
  h5::write_int64(mesh.get(), "element_ids", model.element_ids, {model.element_ids.size()});

  const std::vector<ElementType> present = types_present(model);
  const bool mixed = present.size() > 1;
  for (ElementType type : present) write_type_group(mesh.get(), model, type, mixed);

  XdmfMesh xdmf;
  xdmf.nodes = model.node_count();
  xdmf.cells = model.element_count();
  xdmf.shells = std::any_of(present.begin(), present.end(), is_shell);
  xdmf.plastic = model.has_plasticity();
  if (mixed) {
    const std::vector<std::int64_t> topology = mixed_topology(model);
    h5::write_int64(mesh.get(), "mixed_topology", topology, {topology.size()});
    xdmf.topology_type = "Mixed";
    xdmf.topology_dataset = "/mesh/mixed_topology";
    xdmf.topology_dimensions = std::to_string(topology.size());
  } else {
    // An empty mesh keeps the hexahedron topology (with no cells) of the files before shells.
    const ElementType type = present.empty() ? ElementType::C3D8R : present.front();
    xdmf.topology_type = xdmf_cell_name(type);
    xdmf.topology_dataset = std::string("/mesh/") + element_type_name(type) + "/connectivity";
    xdmf.topology_dimensions =
        std::to_string(xdmf.cells) + " " + std::to_string(nodes_per_element(type));
  }
  if (!model.instances.empty()) xdmf.instance_names = write_instances(mesh.get(), model);
  write_sets(file, mesh.get(), "node_sets", model.node_sets, model.node_ids, true, xdmf.sets);
  write_sets(file, mesh.get(), "element_sets", model.element_sets, model.element_ids, false,
             xdmf.sets);
  return xdmf;
}

}  // namespace xpl::io

#include "solver/model/model.hpp"

#include <algorithm>
#include <cctype>

namespace xpl {

std::vector<Index> Model::surface_nodes(const Surface& surface) const {
  std::vector<Index> nodes;
  if (surface.type == Surface::Type::Node) {
    nodes = surface.nodes;
  } else {
    for (const ElementFace& f : surface.faces) {
      if (f.element < 0 || f.element >= element_count()) continue;
      const Index* en = nodes_of(f.element);
      if (is_hex(element_types[f.element]))
        for (int k : HEX_FACE_NODES[f.face]) nodes.push_back(en[k]);
      else
        nodes.insert(nodes.end(), en, en + 4);
    }
  }
  const Index n = node_count();
  std::erase_if(nodes, [n](Index i) { return i < 0 || i >= n; });
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

std::string to_upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

Real Amplitude::evaluate(Real t) const {
  if (time.empty()) return 1.0;
  if (t <= time.front()) return value.front();
  if (t >= time.back()) return value.back();
  const auto it = std::upper_bound(time.begin(), time.end(), t);
  const auto i = static_cast<std::size_t>(it - time.begin());
  const Real t0 = time[i - 1], t1 = time[i];
  if (t1 <= t0) return value[i];
  const Real s = (t - t0) / (t1 - t0);
  return value[i - 1] + s * (value[i] - value[i - 1]);
}

namespace {
template <class Items>
Index find_by_name(const Items& items, const std::string& name) {
  const std::string key = to_upper(name);
  for (std::size_t i = 0; i < items.size(); ++i)
    if (items[i].name == key) return static_cast<Index>(i);
  return NO_INDEX;
}
}  // namespace

bool Model::has_contact() const {
  if (!contact_pairs.empty()) return true;
  for (const Step& s : steps)
    if (s.contact || !s.contact_pairs.empty()) return true;
  return false;
}

bool Model::has_plasticity() const {
  return std::any_of(materials.begin(), materials.end(),
                     [](const Material& m) { return m.plastic.has_value(); });
}

bool Model::has_plastic_shells() const {
  return std::any_of(shell_sections.begin(), shell_sections.end(), [&](const ShellSection& s) {
    return s.material != NO_INDEX && materials[s.material].plastic.has_value();
  });
}

bool Model::has_shells() const {
  return std::any_of(element_types.begin(), element_types.end(), is_shell);
}

void Model::add_element_source(const std::string& file, int line) {
  // Elements come in long runs from one file: compare with the last file first.
  std::size_t f = element_file.empty() ? 0 : element_file.back();
  if (f >= source_files.size() || source_files[f] != file) {
    f = 0;
    while (f < source_files.size() && source_files[f] != file) ++f;
    if (f == source_files.size()) source_files.push_back(file);
  }
  element_file.push_back(static_cast<std::uint16_t>(f));
  element_line.push_back(line);
}

Index Model::find_node_set(const std::string& name) const {
  return find_by_name(node_sets, name);
}
Index Model::find_element_set(const std::string& name) const {
  return find_by_name(element_sets, name);
}
const Diagnostics& Model::diagnostics_of(int step) const {
  for (int k = std::min(step, static_cast<int>(steps.size()) - 1); k >= 0; --k)
    if (steps[k].diagnostics) return *steps[k].diagnostics;
  return diagnostics;
}

Index Model::find_surface(const std::string& name) const {
  return find_by_name(surfaces, name);
}
Index Model::find_amplitude(const std::string& name) const {
  return find_by_name(amplitudes, name);
}
Index Model::find_material(const std::string& name) const {
  return find_by_name(materials, name);
}

}  // namespace xpl

#include "solver/forces/element_kinds.hpp"

#include <array>

namespace xpl {

elements::HexMaterial KindBinding<elements::Hex8rBlock>::properties(const Model& model,
                                                                    Index element,
                                                                    Real mass_factor) {
  const SolidSection& section = model.solid_sections[model.element_section[element]];
  const Material& m = model.materials[section.material];
  elements::HexMaterial h;
  h.density = m.density * mass_factor;
  h.young = m.young;
  h.poisson = m.poisson;
  if (m.plastic) h.plastic = &*m.plastic;
  // The enhanced form unless HOURGLASS= asks for STIFFNESS, RELAX STIFFNESS (run as
  // STIFFNESS) or VISCOUS (R5: the default stabilisation is physical).
  h.hourglass = elements::HourglassForm::Enhanced;
  if (section.controls != NO_INDEX) {
    const SectionControls& c = model.section_controls[section.controls];
    if (c.hourglass_given && c.hourglass == HourglassType::Viscous)
      h.hourglass = elements::HourglassForm::Viscous;
    else if (c.hourglass_given && c.hourglass != HourglassType::Enhanced)
      h.hourglass = elements::HourglassForm::Stiffness;
    h.hourglass_scale =
        h.hourglass == elements::HourglassForm::Viscous ? c.viscous_scale : c.stiffness_scale;
  }
  return h;
}

elements::ShellProperties KindBinding<elements::Shell4rBlock>::properties(const Model& model,
                                                                          Index element,
                                                                          Real mass_factor) {
  const ShellSection& section = model.shell_sections[model.element_section[element]];
  const Material& m = model.materials[section.material];
  elements::ShellProperties p;
  p.density = m.density * mass_factor;
  p.young = m.young;
  p.poisson = m.poisson;
  p.thickness = section.thickness;
  p.integration_points = section.integration_points;
  p.offset = section.offset;
  p.rotary_exact = section.rotary_exact;
  if (m.plastic) p.plastic = &*m.plastic;
  if (section.controls != NO_INDEX) {
    const SectionControls& c = model.section_controls[section.controls];
    p.hourglass_scale = c.stiffness_scale;
    // HOURGLASS=STIFFNESS, VISCOUS, RELAX STIFFNESS: the older stiffness form.
    if (c.hourglass_given && c.hourglass != HourglassType::Enhanced)
      p.hourglass = elements::ShellHourglass::Stiffness;
    p.plastic_hourglass = !c.plastic_hourglass_elastic;
  }
  return p;
}

namespace {

/// Corner coordinates of element e of kind K in `reference`.
template <class K>
std::array<elements::V3<Real>, K::NODES> corners_of(const Model& model, Index e,
                                                    const NodalVectors& reference) {
  std::array<elements::V3<Real>, K::NODES> p;
  const Index* nodes = model.nodes_of(e);
  for (int a = 0; a < K::NODES; ++a)
    p[a] = {reference(nodes[a], 0), reference(nodes[a], 1), reference(nodes[a], 2)};
  return p;
}

}  // namespace

Real element_node_mass(const Model& model, Index e, const NodalVectors& reference) {
  return with_element_kind(model.element_types[e], [&]<class K>(std::type_identity<K>) {
    return K::node_mass(KindBinding<K>::properties(model, e, 1.0),
                        corners_of<K>(model, e, reference).data());
  });
}

Real element_stable_increment(const Model& model, Index e, const NodalVectors& reference,
                              Real bulk_linear) {
  return with_element_kind(model.element_types[e], [&]<class K>(std::type_identity<K>) {
    return K::stable_increment(KindBinding<K>::properties(model, e, 1.0),
                               corners_of<K>(model, e, reference).data(), bulk_linear);
  });
}

}  // namespace xpl

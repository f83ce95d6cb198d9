#include "solver/output/frame_fields.hpp"

#include "elements/shell/shell_stress_axes.hpp"

namespace xpl {

const std::vector<Real>& FrameFields::element_rows(ElementField field,
                                                   std::vector<Real>& buffer) const {
  if (source != nullptr) {
    source->fill(field, buffer);
    return buffer;
  }
  switch (field) {
    case ElementField::Stress:
      return stress;
    case ElementField::StressBottom:
      return stress_bottom;
    case ElementField::StressTop:
      return stress_top;
    case ElementField::Thickness:
      return thickness;
    case ElementField::Volume:
      return volume;
    case ElementField::HourglassState:
      break;
  }
  return hourglass_state;
}

void global_axis_rows(const Model& model, const NodalVectors& position,
                      const std::vector<Real>& rows, std::vector<Real>& global) {
  const auto n = static_cast<std::size_t>(model.element_count());
  global.resize(n * 6);
  for (std::size_t e = 0; e < n; ++e) {
    const Real* row = &rows[e * 6];
    const auto type = model.element_types[e];
    if (!is_shell(type)) {
      to_vtk(row, &global[e * 6]);
      continue;
    }
    const Index* nodes = model.nodes_of(static_cast<Index>(e));
    elements::V3<Real> p[4];
    for (int k = 0; k < 4; ++k)
      p[k] = {position(nodes[k], 0), position(nodes[k], 1), position(nodes[k], 2)};
    // Rotated into a local row first: the rounding of the XDMF copies is the one of the
    // writer that computed them before (bitwise the same results, issue 36).
    Real rotated[6];
    elements::shell_stress_to_global(elements::quad_frame(p), row, rotated);
    to_vtk(rotated, &global[e * 6]);
  }
}

}  // namespace xpl

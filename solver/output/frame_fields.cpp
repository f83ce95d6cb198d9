#include "solver/output/frame_fields.hpp"

#include "elements/shell/shell_stress_axes.hpp"

namespace xpl {

void global_axis_stresses(const Model& model, const NodalVectors& position, FrameFields& frame) {
  const bool shells = model.has_shells();
  const auto n = static_cast<std::size_t>(model.element_count());
  struct Tensor {
    const std::vector<Real>* rows;  ///< Abaqus order, local axes on shells
    std::vector<Real>* global;      ///< global axes, VTK order
  };
  const Tensor tensors[] = {{&frame.stress, &frame.stress_global},
                            {&frame.stress_bottom, &frame.stress_bottom_global},
                            {&frame.stress_top, &frame.stress_top_global}};
  for (const Tensor& t : tensors) {
    if (!shells && t.rows != &frame.stress) continue;
    std::vector<double>& global = *t.global;
    global.assign(n * 6, 0.0);
    for (std::size_t e = 0; e < n; ++e) {
      const Real* row = &(*t.rows)[e * 6];
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
}

}  // namespace xpl

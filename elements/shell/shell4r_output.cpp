/// \file Shell4rBlock: section output in the Abaqus default local axes and its inverse for
/// --import, hourglass state and thickness; the force pass is in shell4r.cpp.

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "elements/shell/quad_shell_geometry.hpp"
#include "elements/shell/shell4r.hpp"
#include "elements/shell/shell4r_corners.hpp"

namespace xpl::elements {

using simd::Vec;

namespace {

/// The Abaqus default local axes of a shell in its corotational frame: local 1 = c e1 + s e2.
struct OutputAxes {
  Real c, s;
};

/// Abaqus default local 1-axis: global x projected on the shell, or global z when x is within
/// 0.1° of the normal.
OutputAxes output_axes(const QuadFrame<Real>& frame) {
  V3<Real> axis = {1.0, 0.0, 0.0};
  if (std::abs(frame.e3.x) > std::cos(0.1 * 3.14159265358979323846 / 180.0)) {
    axis = {0.0, 0.0, 1.0};
  }
  const Real c0 = dot(axis, frame.e1), s0 = dot(axis, frame.e2);
  const Real len = std::sqrt(c0 * c0 + s0 * s0);
  return {c0 / len, s0 / len};
}

}  // namespace

ShellSectionOutput Shell4rBlock::section_output(const NodalVectors& position, Index i) const {
  const std::size_t s = slot_of(i), b = s / W, l = s % W;
  Index nodes[4];
  for (int a = 0; a < 4; ++a) nodes[a] = m_conn[(b * 4 + a) * W + l];
  V3<Real> p[4];
  gather_corners(position, nodes, p);
  const OutputAxes axes = output_axes(quad_frame(p));
  const Real c = axes.c, sn = axes.s;
  const int points = points_of(b, l);
  const int pick[3] = {0, (points - 1) / 2, points - 1};
  ShellSectionOutput out;
  const Real txz = m_shear[(b * 2) * W + l], tyz = m_shear[(b * 2 + 1) * W + l];
  for (int q = 0; q < 3; ++q) {
    const Real* st = &m_stress[(b * m_points + pick[q]) * 3 * W + l];
    const Real sxx = st[0], syy = st[W], sxy = st[2 * W];
    std::array<Real, 6>& o = out.stress[q];
    o[0] = c * c * sxx + 2.0 * c * sn * sxy + sn * sn * syy;
    o[1] = sn * sn * sxx - 2.0 * c * sn * sxy + c * c * syy;
    o[2] = 0.0;
    o[3] = -c * sn * sxx + (c * c - sn * sn) * sxy + c * sn * syy;
    o[4] = c * txz + sn * tyz;
    o[5] = -sn * txz + c * tyz;
  }
  out.thickness = m_thickness[b * W + l];
  if (has_plasticity()) {
    for (int q = 0; q < 3; ++q) out.peeq[q] = m_plastic.peeq(b, pick[q], l);
    for (int k = 0; k < points; ++k) out.peeq_max = std::max(out.peeq_max, m_plastic.peeq(b, k, l));
  }
  return out;
}

int Shell4rBlock::points_of(std::size_t b, std::size_t l) const {
  // Points used by an element: those with a weight (unused trailing points have none).
  int points = 0;
  while (points < m_points && m_weight[(b * m_points + points) * W + l] > 0.0) ++points;
  return points;
}

void Shell4rBlock::gather_output(const NodalVectors& position, std::vector<Real>& stress,
                                 std::vector<Real>& bottom, std::vector<Real>& top,
                                 std::vector<Real>& thickness) const {
  const bool stresses = !stress.empty() || !bottom.empty() || !top.empty();
  for (Index i = 0; i < size(); ++i) {
    const std::size_t e = static_cast<std::size_t>(m_element_index[i]);
    if (!thickness.empty()) thickness[e] = m_thickness[slot_of(i)];
    if (!stresses) continue;
    const ShellSectionOutput out = section_output(position, i);
    for (int c = 0; c < 6; ++c) {
      if (!bottom.empty()) bottom[e * 6 + c] = out.stress[0][c];
      if (!stress.empty()) stress[e * 6 + c] = out.stress[1][c];
      if (!top.empty()) top[e * 6 + c] = out.stress[2][c];
    }
  }
}

void Shell4rBlock::gather_hourglass_state(std::vector<Real>& rows) const {
  gather_lane_rows(m_hourglass, N_HOURGLASS, W, m_element_index, m_slot, rows);
}

void Shell4rBlock::set_hourglass_state(std::span<const Real> rows) {
  set_lane_rows(rows, N_HOURGLASS, W, m_element_index, m_slot, m_lane_owner, m_hourglass);
}

void Shell4rBlock::set_thickness(std::span<const Real> thickness) {
  for (Index i = 0; i < size(); ++i) {
    const auto e = static_cast<std::size_t>(m_element_index[i]);
    if (e >= thickness.size() || !(thickness[e] > 0.0))
      throw std::invalid_argument(
          "Shell4rBlock::set_thickness: no positive thickness for element " + std::to_string(e));
    m_thickness[slot_of(i)] = thickness[e];
  }
  const auto n_batches = static_cast<std::size_t>(m_color_batches.back());
  for (std::size_t b = 0; b < n_batches; ++b)
    for (int l = 1; l < W; ++l)
      if (m_lane_owner[b * W + l] == NO_INDEX) m_thickness[b * W + l] = m_thickness[b * W];
}

void Shell4rBlock::set_output_stress(const NodalVectors& position, std::span<const Real> middle,
                                     std::span<const Real> bottom, std::span<const Real> top) {
  for (Index e : m_element_index) {
    const std::size_t end = static_cast<std::size_t>(e) * 6 + 6;
    if (end > middle.size() || end > bottom.size() || end > top.size()) {
      throw std::invalid_argument(
          "Shell4rBlock::set_output_stress: the stress rows do not reach "
          "the row of element " +
          std::to_string(e) + "; expected n_elements × 6 each");
    }
  }
  for (Index i = 0; i < size(); ++i) {
    const std::size_t s = slot_of(i), b = s / W, l = s % W;
    Index nodes[4];
    for (int a = 0; a < 4; ++a) nodes[a] = m_conn[(b * 4 + a) * W + l];
    V3<Real> p[4];
    gather_corners(position, nodes, p);
    const OutputAxes axes = output_axes(quad_frame(p));
    const Real c = axes.c, sn = axes.s;
    const std::size_t e = static_cast<std::size_t>(m_element_index[i]) * 6;

    // Output axes -> corotational frame: σ_local = Rᵀ σ_out R with R the rotation by (c, sn)
    // that section_output applies.
    struct InPlane {
      Real xx, yy, xy;
    };
    const auto to_local = [&](const Real* o) {
      return InPlane{c * c * o[0] - 2.0 * c * sn * o[3] + sn * sn * o[1],
                     sn * sn * o[0] + 2.0 * c * sn * o[3] + c * c * o[1],
                     c * sn * (o[0] - o[1]) + (c * c - sn * sn) * o[3]};
    };
    const InPlane mid = to_local(&middle[e]);
    const int points = points_of(b, l);
    const InPlane low = points > 1 ? to_local(&bottom[e]) : mid;
    const InPlane high = points > 1 ? to_local(&top[e]) : mid;
    for (int k = 0; k < points; ++k) {
      const Real zeta = m_zeta[(b * m_points + k) * W + l];
      // Linear between the section points; the middle point itself (ζ = 0) takes `mid`.
      const InPlane& end = zeta < 0.0 ? low : high;
      const Real f = std::abs(zeta);
      Real* st = &m_stress[(b * m_points + k) * 3 * W + l];
      st[0] = (1.0 - f) * mid.xx + f * end.xx;
      st[W] = (1.0 - f) * mid.yy + f * end.yy;
      st[2 * W] = (1.0 - f) * mid.xy + f * end.xy;
    }
    m_shear[(b * 2) * W + l] = c * middle[e + 4] - sn * middle[e + 5];
    m_shear[(b * 2 + 1) * W + l] = sn * middle[e + 4] + c * middle[e + 5];
  }
  // Padding lanes compute a copy of lane 0 of their batch: give them its stresses as well.
  const auto n_batches = static_cast<std::size_t>(m_color_batches.back());
  for (std::size_t b = 0; b < n_batches; ++b)
    for (int l = 1; l < W; ++l) {
      if (m_lane_owner[b * W + l] != NO_INDEX) continue;
      for (int k = 0; k < m_points * 3; ++k)
        m_stress[(b * m_points * 3 + k) * W + l] = m_stress[(b * m_points * 3 + k) * W];
      for (int k = 0; k < 2; ++k) m_shear[(b * 2 + k) * W + l] = m_shear[(b * 2 + k) * W];
    }
}

}  // namespace xpl::elements

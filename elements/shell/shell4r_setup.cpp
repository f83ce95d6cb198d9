/// \file Shell4rBlock: setup (constants, colours and batches), lumped mass and rotary inertia,
/// and the geometry queries of the reference configuration; the force pass is in shell4r.cpp.

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "elements/parallel/element_coloring.hpp"
#include "elements/shell/quad_shell_geometry.hpp"
#include "elements/shell/shell4r.hpp"
#include "elements/shell/shell4r_corners.hpp"
#include "elements/shell/shell4r_increment.hpp"

namespace xpl::elements {

namespace {

/// Simpson's rule on ζ ∈ [−1, 1] with `points` (odd) points, weights normalised to Σ = 1;
/// one point is the mid-surface alone (membrane only).
void simpson(int points, Real* zeta, Real* weight) {
  if (points == 1) {
    zeta[0] = 0.0;
    weight[0] = 1.0;
    return;
  }
  const Real h = 2.0 / (points - 1);
  for (int k = 0; k < points; ++k) {
    zeta[k] = -1.0 + k * h;
    const Real w = (k == 0 || k == points - 1) ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
    weight[k] = 0.5 * w * h / 3.0;
  }
}

}  // namespace

Real shell_rotary_radius2(Real thickness, Real length, Real poisson, bool exact) {
  const Real nu = poisson;
  const Real ratio = 2.0 * (1.0 + nu) / (SHELL_SHEAR_FACTOR * (1.0 - nu)) - 1.0;
  if (exact) return thickness * thickness / 12.0;
  return std::max(thickness * thickness / 12.0,
                  SHELL_ROTARY_MARGIN * length * length / (4.0 * ratio));
}

Shell4rBlock::Shell4rBlock(std::vector<Index> element_index, const std::vector<Index>& connectivity,
                           const std::vector<ShellProperties>& properties, Index node_count,
                           const BatchLayout* given)
    : m_element_index(std::move(element_index)) {
  const Index n = size();
  for (const ShellProperties& p : properties)
    m_points = std::max(m_points, std::min(p.integration_points, SHELL_MAX_POINTS));
  BatchLayout layout = given != nullptr ? *given : make_batches(connectivity, 4, node_count, W);
  m_color_batches = std::move(layout.color_batches);
  m_lane_owner = std::move(layout.lane_owner);
  const auto n_batches = static_cast<std::size_t>(m_color_batches.back());
  m_conn.assign(n_batches * 4 * W, 0);
  // Built plain, then stored once per distinct batch block (SharedBlocks).
  std::vector<Real> constants(n_batches * N_CONST * W, 0.0);
  std::vector<Real> zetas(n_batches * m_points * W, 0.0);
  std::vector<Real> weights(n_batches * m_points * W, 0.0);
  m_thickness.assign(n_batches * W, 0.0);
  m_stress.assign(n_batches * m_points * 3 * W, 0.0);
  m_shear.assign(n_batches * 2 * W, 0.0);
  m_hourglass.assign(n_batches * N_HOURGLASS * W, 0.0);
  m_batch_forms.assign(n_batches, 0);
  m_fold_exempt.assign(n_batches * W, 0);
  m_slot.assign(n, NO_INDEX);
  m_batch_energy.assign(n_batches * 3, 0.0);
  m_batch_dt.assign(n_batches, 0.0);
  m_batch_critical.assign(n_batches, NO_INDEX);
  m_batch_failed.assign(n_batches, NO_INDEX);

  for (std::size_t b = 0; b < n_batches; ++b)
    for (int l = 0; l < W; ++l) {
      const Index owner = m_lane_owner[b * W + l];
      // Padding lanes compute a copy of lane 0 and are masked out of every result.
      const Index e = owner != NO_INDEX ? owner : m_lane_owner[b * W];
      if (owner != NO_INDEX) m_slot[owner] = static_cast<Index>(b * W + l);
      for (int a = 0; a < 4; ++a) m_conn[(b * 4 + a) * W + l] = connectivity[e * 4 + a];
      const ShellProperties& p = properties[e];
      const Real nu = p.poisson;
      const Real q11 = p.young / (1.0 - nu * nu);
      const Real g = p.young / (2.0 * (1.0 + nu));
      Real* c = &constants[b * N_CONST * W + l];
      c[Q11 * W] = q11;
      c[Q12 * W] = nu * q11;
      c[SHEAR * W] = g;
      c[SHEAR_T * W] = SHELL_SHEAR_FACTOR * g;
      c[NU_RATIO * W] = nu / (1.0 - nu);
      c[DT_SPEED * W] = shell_wave_speed(p);
      c[HG_MODULUS * W] = SHELL_HOURGLASS_STIFFNESS * p.hourglass_scale * p.young;
      const bool physical = p.hourglass == ShellHourglass::Physical;
      c[HG_OLD * W] = physical ? 0.0 : c[HG_MODULUS * W];
      c[HG_PHYS * W] = physical ? p.hourglass_scale : 0.0;
      c[PHYS_ON * W] = physical ? 1.0 : 0.0;
      c[HG_PLASTIC * W] = physical && p.plastic_hourglass ? 1.0 : 0.0;
      c[POISSON * W] = nu;
      m_batch_forms[b] |= physical ? FORM_PHYS : FORM_OLD;
      m_rotary_exact = m_rotary_exact || p.rotary_exact;
      c[OFFSET * W] = p.offset;
      c[DENSITY * W] = p.density;
      c[THICKNESS0 * W] = p.thickness;
      c[ROT_SPEED2 * W] =
          p.rotary_exact ? SHELL_EXACT_ROTARY_MARGIN * SHELL_SHEAR_FACTOR * g / p.density : 0.0;
      c[ROT_EXACT * W] = p.rotary_exact ? 1.0 : 0.0;
      m_thickness[b * W + l] = p.thickness;
      Real zeta[SHELL_MAX_POINTS], weight[SHELL_MAX_POINTS];
      const int points = std::min(p.integration_points, SHELL_MAX_POINTS);
      simpson(points, zeta, weight);
      for (int k = 0; k < points; ++k) {
        zetas[(b * m_points + k) * W + l] = zeta[k];
        weights[(b * m_points + k) * W + l] = weight[k];
      }
    }
  m_const = SharedBlocks<Real>(constants, N_CONST * W);
  m_zeta = SharedBlocks<Real>(zetas, static_cast<std::size_t>(m_points) * W);
  m_weight = SharedBlocks<Real>(weights, static_cast<std::size_t>(m_points) * W);
  std::vector<const Plasticity*> lane_law(n_batches * W, nullptr);
  for (std::size_t s = 0; s < lane_law.size(); ++s) {
    const Index owner = m_lane_owner[s];
    lane_law[s] = properties[owner != NO_INDEX ? owner : m_lane_owner[s - s % W]].plastic;
  }
  m_plastic = ShellPlasticState(lane_law, m_points);
}

Real shell_wave_speed(const ShellProperties& p) {
  const Real nu = p.poisson;
  const Real q11 = p.young / (1.0 - nu * nu);
  return std::sqrt(q11 / p.density) * std::sqrt(1.0 + std::max(nu, 0.0));
}

Real Shell4rBlock::node_mass(const ShellProperties& p, const V3<Real>* corners) {
  const V3<Real> c[4] = {corners[0], corners[1], corners[2], corners[3]};
  return p.density * p.thickness * quad_frame(c).area / 4.0;
}

Real Shell4rBlock::stable_increment(const ShellProperties& p, const V3<Real>* corners,
                                    Real /*bulk_linear*/) {
  const V3<Real> c[4] = {corners[0], corners[1], corners[2], corners[3]};
  const QuadFrame<Real> frame = quad_frame(c);
  const Real length = 1.41421356237309515 * frame.area / frame.diagonal;
  // As the kernel (shell4r_kernel.hpp): also held to the membrane bound of a crushed quad.
  const Real nu = p.poisson;
  const Real q11 = p.young / (1.0 - nu * nu);
  const Real omega2 =
      shell_membrane_omega2(frame, q11 / p.density, nu,
                            SHELL_HOURGLASS_STIFFNESS * p.hourglass_scale * p.young / p.density);
  return std::min(length / shell_wave_speed(p), 2.0 / std::sqrt(std::max(omega2, 1e-300)));
}

void Shell4rBlock::add_lumped_mass(const NodalVectors& reference, std::vector<Real>& mass,
                                   std::vector<Real>& rotary_inertia) const {
  for (Index i = 0; i < size(); ++i) {
    const std::size_t s = slot_of(i), b = s / W, l = s % W;
    Index nodes[4];
    for (int a = 0; a < 4; ++a) nodes[a] = m_conn[(b * 4 + a) * W + l];
    V3<Real> p[4];
    gather_corners(reference, nodes, p);
    const QuadFrame<Real> frame = quad_frame(p);
    const Real area = frame.area;
    const Real t = m_const[(b * N_CONST + THICKNESS0) * W + l];
    const Real share = m_const[(b * N_CONST + DENSITY) * W + l] * t * area / 4.0;  // node_mass()
    const Real length = 1.41421356237309515 * area / frame.diagonal;
    const bool exact = m_const[(b * N_CONST + ROT_EXACT) * W + l] > 0.0;
    // Skewed and tapered quads need more (shell4r_increment.hpp); 1 on rectangles.
    const Real shape = exact ? 1.0 : shell_rotary_shape_factor(frame, p);
    const Real inertia =
        share * shape *
        shell_rotary_radius2(t, length, m_const[(b * N_CONST + POISSON) * W + l], exact);
    for (Index node : nodes) {
      mass[node] += share;
      rotary_inertia[node] += inertia;
    }
  }
}

void Shell4rBlock::note_reference_corners(const NodalVectors& reference) {
  for (std::size_t s = 0; s < m_fold_exempt.size(); ++s) {
    const std::size_t b = s / W, l = s % W;
    Index nodes[4];
    for (int a = 0; a < 4; ++a) nodes[a] = m_conn[(b * 4 + a) * W + l];
    V3<Real> p[4];
    gather_corners(reference, nodes, p);
    Real det[4], columns[4];
    quad_corner_jacobians(quad_frame(p), det, columns);
    unsigned char exempt = 0;
    for (int k = 0; k < 4; ++k)
      if (!(det[k] > 0.0)) exempt |= static_cast<unsigned char>(1u << k);
    m_fold_exempt[s] = exempt;
  }
}

std::vector<Real> Shell4rBlock::node_thickness(const NodalVectors& reference,
                                               Index node_count) const {
  std::vector<Real> weighted(node_count, 0.0), area_sum(node_count, 0.0);
  for (Index i = 0; i < size(); ++i) {
    const std::size_t s = slot_of(i), b = s / W, l = s % W;
    Index nodes[4];
    for (int a = 0; a < 4; ++a) nodes[a] = m_conn[(b * 4 + a) * W + l];
    V3<Real> p[4];
    gather_corners(reference, nodes, p);
    const Real area = quad_frame(p).area;
    const Real t = m_const[(b * N_CONST + THICKNESS0) * W + l];
    for (Index node : nodes) {
      weighted[node] += area * t;
      area_sum[node] += area;
    }
  }
  for (Index i = 0; i < node_count; ++i)
    if (area_sum[i] > 0.0) weighted[i] /= area_sum[i];
  return weighted;
}

Real Shell4rBlock::warp_angle(const NodalVectors& position, Index i) const {
  const std::size_t s = slot_of(i), b = s / W, l = s % W;
  Index nodes[4];
  for (int a = 0; a < 4; ++a) nodes[a] = m_conn[(b * 4 + a) * W + l];
  V3<Real> p[4];
  gather_corners(position, nodes, p);
  return quad_warp_angle(p);
}

}  // namespace xpl::elements

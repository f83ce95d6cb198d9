#include "elements/shell4r.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "elements/element_coloring.hpp"
#include "elements/quad_shell_geometry.hpp"
#include "elements/shell4r_hourglass.hpp"
#include "elements/shell4r_increment.hpp"

namespace xpl::elements {

using simd::Vec;

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

template <class T>
void gather_corners(const NodalVectors& position, const Index* nodes, V3<T> p[4]) {
  for (int a = 0; a < 4; ++a)
    p[a] = {position(nodes[a], 0), position(nodes[a], 1), position(nodes[a], 2)};
}

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

/// Node signs of the gradient operator: B_I = sign_I · (b_a for I = 0, 2; b_b for I = 1, 3).
constexpr Real B_SIGN[4] = {1.0, 1.0, -1.0, -1.0};
/// Hourglass pattern Γ.
constexpr Real GAMMA[4] = {1.0, -1.0, 1.0, -1.0};

}  // namespace

Real shell_rotary_radius2(Real thickness, Real length, Real poisson, bool exact) {
  const Real nu = poisson;
  const Real ratio = 2.0 * (1.0 + nu) / (SHELL_SHEAR_FACTOR * (1.0 - nu)) - 1.0;
  if (exact) return thickness * thickness / 12.0;
  return std::max(thickness * thickness / 12.0,
                  SHELL_ROTARY_MARGIN * length * length / (4.0 * ratio));
}

Shell4rBlock::Shell4rBlock(std::vector<Index> element_index, const std::vector<Index>& connectivity,
                           const std::vector<ShellProperties>& properties, Index node_count)
    : m_element_index(std::move(element_index)) {
  const Index n = size();
  for (const ShellProperties& p : properties)
    m_points = std::max(m_points, std::min(p.integration_points, SHELL_MAX_POINTS));
  BatchLayout layout = make_batches(connectivity, 4, node_count, W);
  m_color_batches = std::move(layout.color_batches);
  m_lane_owner = std::move(layout.lane_owner);
  const auto n_batches = static_cast<std::size_t>(m_color_batches.back());
  m_conn.assign(n_batches * 4 * W, 0);
  m_const.assign(n_batches * N_CONST * W, 0.0);
  m_zeta.assign(n_batches * m_points * W, 0.0);
  m_weight.assign(n_batches * m_points * W, 0.0);
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
      Real* c = &m_const[b * N_CONST * W + l];
      c[Q11 * W] = q11;
      c[Q12 * W] = nu * q11;
      c[SHEAR * W] = g;
      c[SHEAR_T * W] = SHELL_SHEAR_FACTOR * g;
      c[NU_RATIO * W] = nu / (1.0 - nu);
      c[DT_SPEED * W] = std::sqrt(q11 / p.density) * std::sqrt(1.0 + std::max(nu, 0.0));
      c[HG_MODULUS * W] = SHELL_HOURGLASS_STIFFNESS * p.hourglass_scale * p.young;
      const bool physical = p.hourglass == ShellHourglass::Physical;
      c[HG_OLD * W] = physical ? 0.0 : c[HG_MODULUS * W];
      c[HG_PHYS * W] = physical ? p.hourglass_scale : 0.0;
      c[PHYS_ON * W] = physical ? 1.0 : 0.0;
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
        m_zeta[(b * m_points + k) * W + l] = zeta[k];
        m_weight[(b * m_points + k) * W + l] = weight[k];
      }
    }
  std::vector<const Plasticity*> lane_law(n_batches * W, nullptr);
  for (std::size_t s = 0; s < lane_law.size(); ++s) {
    const Index owner = m_lane_owner[s];
    lane_law[s] = properties[owner != NO_INDEX ? owner : m_lane_owner[s - s % W]].plastic;
  }
  m_plastic = ShellPlasticState(lane_law, m_points);
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
    const Real share = m_const[(b * N_CONST + DENSITY) * W + l] * t * area / 4.0;
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

void Shell4rBlock::internal_forces(const NodalVectors& position, const NodalVectors& velocity_half,
                                   const NodalVectors& angular_velocity_half, Real dt,
                                   NodalVectors& force, NodalVectors& moment,
                                   ShellStepTotals& totals) {
  const int parts = std::max(1, omp_get_max_threads());
  own_partition(parts, static_cast<Index>(position.rows()));
  partitioned_pass(
      parts, static_cast<Index>(m_boundary_nodes.size()),
      [&](int p) {
        forces_of_part(p, position, velocity_half, angular_velocity_half, dt, force, moment);
      },
      [&](Index k) { add_boundary_forces(k, m_boundary_nodes[k], force, moment); });
  add_totals(totals);
}

void Shell4rBlock::own_partition(int parts, Index node_count) {
  if (m_own_partition && m_parts == parts) return;
  std::vector<Index> node_part(node_count, UNTOUCHED);
  mark_nodes(parts, node_part);
  const BoundaryNodes boundary = boundary_nodes(node_part);
  set_partition(parts, boundary);
  m_boundary_nodes = boundary.nodes;
  m_own_partition = true;
}

void Shell4rBlock::mark_nodes(int parts, std::vector<Index>& node_part) const {
  mark_part_nodes(m_conn, m_lane_owner, m_color_batches, 4, W, parts, node_part);
}

void Shell4rBlock::set_partition(int parts, const BoundaryNodes& boundary) {
  m_parts = parts;
  m_own_partition = false;
  m_exchange = CornerExchange(m_conn, m_lane_owner, 4, W, boundary);
  m_exchange_force.assign(static_cast<std::size_t>(m_exchange.size()) * 6, 0.0);
}

void Shell4rBlock::forces_of_part(int part, const NodalVectors& position,
                                  const NodalVectors& velocity_half,
                                  const NodalVectors& angular_velocity_half, Real dt,
                                  NodalVectors& force, NodalVectors& moment) {
  const Index nn = static_cast<Index>(position.rows());
  const Real* const p[3] = {position.data(), position.data() + nn, position.data() + 2 * nn};
  const Real* const v[3] = {velocity_half.data(), velocity_half.data() + nn,
                            velocity_half.data() + 2 * nn};
  const Real* const w[3] = {angular_velocity_half.data(), angular_velocity_half.data() + nn,
                            angular_velocity_half.data() + 2 * nn};
  Real* const f[3] = {force.data(), force.data() + nn, force.data() + 2 * nn};
  Real* const m[3] = {moment.data(), moment.data() + nn, moment.data() + 2 * nn};
  for (int c = 0; c < color_count(); ++c) {
    const auto [first, last] = part_batches(m_color_batches, c, part, m_parts);
    for (Index b = first; b < last; ++b) {
      if (m_plastic.batch_plastic(static_cast<std::size_t>(b)))
        compute_batch<true>(b, p, v, w, dt, f, m);
      else
        compute_batch<false>(b, p, v, w, dt, f, m);
    }
  }
}

void Shell4rBlock::add_totals(ShellStepTotals& totals) const {
  const Index n_batches = m_color_batches.back();
  for (Index b = 0; b < n_batches; ++b) {
    totals.strain_energy_increment += m_batch_energy[b * 3 + 0];
    totals.hourglass_energy_increment += m_batch_energy[b * 3 + 1];
    totals.plastic_energy_increment += m_batch_energy[b * 3 + 2];
    totals.merge(m_batch_dt[b], m_batch_critical[b], m_batch_failed[b]);
  }
}

template <bool PLASTIC>
void Shell4rBlock::compute_batch(Index batch, const Real* const p[3], const Real* const v[3],
                                 const Real* const w[3], Real dt, Real* const f[3],
                                 Real* const m[3]) {
  const std::size_t b = static_cast<std::size_t>(batch);
  const Index* conn = &m_conn[b * 4 * W];
  const Real* cst = &m_const[b * N_CONST * W];
  auto constant = [&](Constant k) { return simd::load(cst + k * W); };

  V3<Vec> x[4], vel[4], om[4];
  for (int a = 0; a < 4; ++a) {
    const Index* idx = conn + a * W;
    x[a] = {simd::gather(p[0], idx), simd::gather(p[1], idx), simd::gather(p[2], idx)};
    vel[a] = {simd::gather(v[0], idx), simd::gather(v[1], idx), simd::gather(v[2], idx)};
    om[a] = {simd::gather(w[0], idx), simd::gather(w[1], idx), simd::gather(w[2], idx)};
  }

  // Rates on the mid-increment geometry: exactly strain free for rigid rotations.
  V3<Vec> xm[4];
  for (int a = 0; a < 4; ++a) xm[a] = x[a] - (0.5 * dt) * vel[a];
  const QuadFrame<Vec> fm = quad_frame(xm);
  QuadCombos<Vec> vx, vy, vz, tx, ty, tz;
  local_combos(fm, vel, vx, vy, vz);
  local_combos(fm, om, tx, ty, tz);
  const V3<Vec> om_sum = om[0] + om[1] + om[2] + om[3];
  const Vec tbx = 0.25 * dot(fm.e1, om_sum), tby = 0.25 * dot(fm.e2, om_sum);
  // Velocities of the projections of the (warped) nodes onto the element plane.
  const Vec zh = fm.warp;
  const QuadCombos<Vec> ux = {vx.d02 - zh * ty.d02, vx.d13 + zh * ty.d13, vx.hg - 4.0 * zh * tby};
  const QuadCombos<Vec> uy = {vy.d02 + zh * tx.d02, vy.d13 - zh * tx.d13, vy.hg + 4.0 * zh * tbx};

  const Vec dxx = grad_x(fm, ux), dyy = grad_y(fm, uy);
  const Vec gxy = grad_x(fm, uy) + grad_y(fm, ux);
  const Vec kxx = grad_x(fm, ty), kyy = -grad_y(fm, tx);
  const Vec kxy = grad_y(fm, ty) - grad_x(fm, tx);
  Vec gxz = grad_x(fm, vz) + tby, gyz = grad_y(fm, vz) - tbx;
  // Physical form: the transverse shear is the assumed strain of the edge shears
  // (shell4r_hourglass.hpp) instead of the one-point value; PHYS_ON selects it per lane.
  const unsigned char forms = m_batch_forms[b];
  EdgeShear<Vec> edge{};
  if (forms & FORM_PHYS) {
    Vec wz[4], thx[4], thy[4], s[4];
    for (int a = 0; a < 4; ++a) {
      wz[a] = dot(fm.e3, vel[a]);
      thx[a] = dot(fm.e1, om[a]);
      thy[a] = dot(fm.e2, om[a]);
    }
    edge_shear_rates(quad_edges(fm, xm), wz, thx, thy, s);
    edge = edge_shear(fm, quad_natural(fm), s);
    if (forms == FORM_PHYS) {
      gxz = edge.gxz;
      gyz = edge.gyz;
    } else {
      const Vec on = constant(PHYS_ON);
      gxz += on * (edge.gxz - gxz);
      gyz += on * (edge.gyz - gyz);
    }
  }

  // Plane stress: the thickness follows the in-plane dilatation of the reference surface,
  // ε̇_zz = −ν/(1−ν)(d_xx + d_yy + z_ref(κ_xx + κ_yy)). It is advanced before the resultants:
  // the strain increments see the mid-increment thickness (as the rates see the mid-increment
  // geometry) and the resultants at t_{n+1} the end thickness, so N and M are functions of the
  // state at t_{n+1}. Resultants taken with the thickness of t_n lag the stresses by one
  // increment; in compressed walls (tr N < 0) that lag does negative work on every membrane
  // vibration, ∝ ν/(1−ν)·|σ|/E·ωΔt per cycle, and a crushed tube gains energy until it fails.
  const Vec q11 = constant(Q11), q12 = constant(Q12), g = constant(SHEAR);
  const Vec offset = constant(OFFSET);
  const Vec t_old = simd::load(&m_thickness[b * W]);
  Vec t = t_old * (1.0 - constant(NU_RATIO) * dt * (dxx + dyy - offset * t_old * (kxx + kyy)));
  simd::store(&m_thickness[b * W], t);
  const Vec t_mid = 0.5 * (t_old + t);
  // Through-thickness integration (z from the reference surface, which is OFFSET·t above
  // the mid-surface), plane stress.
  Vec nxx = simd::splat(0.0), nyy = nxx, nxy = nxx, mxx = nxx, myy = nxx, mxy = nxx;
  Vec work = simd::splat(0.0);  // strain energy increment per unit area
  // Plastic batches: dissipation per unit area and Σ weight · Δε33ᵖ over the section points.
  Vec plastic_work = simd::splat(0.0), thinning = simd::splat(0.0);
  for (int k = 0; k < m_points; ++k) {
    const Vec zeta = 0.5 * simd::load(&m_zeta[(b * m_points + k) * W]) - offset;
    const Vec weight = simd::load(&m_weight[(b * m_points + k) * W]);
    const Vec zk = t_mid * zeta, tw = t_mid * weight;  // mid-increment: strain and work
    const Vec zk_n = t * zeta, tw_n = t * weight;      // end of increment: resultants
    const Vec exx = dt * (dxx + zk * kxx), eyy = dt * (dyy + zk * kyy);
    const Vec exy = dt * (gxy + zk * kxy);
    Real* s = &m_stress[(b * m_points + k) * 3 * W];
    const Vec sxx = simd::load(s), syy = simd::load(s + W), sxy = simd::load(s + 2 * W);
    Vec sxx_n = sxx + q11 * exx + q12 * eyy;
    Vec syy_n = syy + q12 * exx + q11 * eyy;
    Vec sxy_n = sxy + g * exy;
    if constexpr (PLASTIC) {
      const Vec start[3] = {sxx, syy, sxy};
      plastic_work += tw * m_plastic.point_return(b, k, q11, q12, g, dt, weight, start, sxx_n,
                                                  syy_n, sxy_n, thinning);
    }
    simd::store(s, sxx_n);
    simd::store(s + W, syy_n);
    simd::store(s + 2 * W, sxy_n);
    nxx += tw_n * sxx_n;
    nyy += tw_n * syy_n;
    nxy += tw_n * sxy_n;
    mxx += (tw_n * zk_n) * sxx_n;
    myy += (tw_n * zk_n) * syy_n;
    mxy += (tw_n * zk_n) * sxy_n;
    work += (0.5 * tw) * ((sxx + sxx_n) * exx + (syy + syy_n) * eyy + (sxy + sxy_n) * exy);
  }
  if constexpr (PLASTIC) {
    // Plastic incompressibility: Δε33 = −ν/(1−ν)(Δε11ᵉ + Δε22ᵉ) − (Δε11ᵖ + Δε22ᵖ). The update
    // above took the elastic term on the total strain Δεᵉ + Δεᵖ, so the plastic part adds
    // (1 − ν/(1−ν)) Δε33ᵖ, Δε33ᵖ averaged through the thickness with the weights. N scales with
    // t and M with t², so the resultants follow the end thickness as in the elastic case.
    const Vec r = 1.0 + (1.0 - constant(NU_RATIO)) * thinning;
    t = t * r;
    simd::store(&m_thickness[b * W], t);
    const Vec r2 = r * r;
    nxx *= r;
    nyy *= r;
    nxy *= r;
    mxx *= r2;
    myy *= r2;
    mxy *= r2;
  }
  Real* shear = &m_shear[b * 2 * W];
  const Vec kg = constant(SHEAR_T);
  const Vec txz = simd::load(shear), tyz = simd::load(shear + W);
  const Vec txz_n = txz + (kg * dt) * gxz, tyz_n = tyz + (kg * dt) * gyz;
  simd::store(shear, txz_n);
  simd::store(shear + W, tyz_n);
  work += (0.5 * dt) * t_mid * ((txz + txz_n) * gxz + (tyz + tyz_n) * gyz);
  const Vec qx = t * txz_n, qy = t * tyz_n;

  // Hourglass resultants (accumulated in the corotational frame). In-plane patterns: stiffness
  // form in both forms; bending and transverse shear: the form of the lane (the other form's
  // coefficients are zero on it), each evaluated only when a lane of the batch uses it.
  const Vec bb = 2.0 * (fm.b1a * fm.b1a + fm.b1b * fm.b1b + fm.b2a * fm.b2a + fm.b2b * fm.b2b);
  const Vec c_plane = constant(HG_MODULUS) * t * fm.area * bb * 0.25;
  Real* hstore = &m_hourglass[b * N_HOURGLASS * W];
  Vec hq[N_HOURGLASS];
  for (Vec& h : hq) h = simd::splat(0.0);
  Vec hg_work = simd::splat(0.0);
  // Advances resultant h by Δ = dt·(its rate of change) and adds its work over `rate`.
  auto store = [&](int h, Vec increment, Vec rate) {
    const Vec old = simd::load(hstore + h * W);
    hq[h] = old + increment;
    simd::store(hstore + h * W, hq[h]);
    hg_work += (0.5 * dt) * (old + hq[h]) * rate;
  };
  auto advance = [&](int h, Vec stiffness, Vec rate) { store(h, (stiffness * dt) * rate, rate); };
  advance(0, c_plane, hourglass_rate(fm, ux));
  advance(1, c_plane, hourglass_rate(fm, uy));
  const Vec rate_tx = hourglass_rate(fm, tx), rate_ty = hourglass_rate(fm, ty);
  if (forms & FORM_OLD) {
    const Vec bend = constant(HG_OLD) * t * t * t * (1.0 / 12.0);
    const Vec c_rot = bend * fm.area * bb * 0.25;
    advance(2, bend * bb, hourglass_rate(fm, vz));
    advance(3, c_rot, rate_tx);
    advance(4, c_rot, rate_ty);
  }
  const QuadFrame<Vec> fe = quad_frame(x);
  // Shear resultants acting through the one-point shear (stiffness-form lanes) and through
  // the edge shears (physical lanes, with the linear-part resultants).
  Vec qx_point = qx, qy_point = qy;
  Vec hz[4], hbx[4], hby[4];  // physical form: normal forces and β-forces per node
  for (int a = 0; a < 4; ++a) hz[a] = hbx[a] = hby[a] = simd::splat(0.0);
  if (forms & FORM_PHYS) {
    const Vec scale = constant(HG_PHYS);
    const QuadNatural<Vec> nat = quad_natural(fm);
    const Vec shear_k = (scale * constant(SHEAR_T)) * t * fm.area * (1.0 / 3.0);
    advance(5, shear_k * nat.aa, edge.g_xi);
    advance(6, shear_k * nat.cc, edge.g_eta);
    // Bending: q̇ = (γ·θy, −γ·θx)/4, Ṁ = K_b q̇.
    const Vec q1 = 0.25 * rate_ty, q2 = -0.25 * rate_tx;
    Vec k1, k2;
    bending_hourglass_apply(nat, constant(POISSON), q1, q2, k1, k2);
    const Vec bend_k = (scale * q11) * t * t * t * (1.0 / 36.0) * fm.area;
    store(7, (bend_k * dt) * k1, q1);
    store(8, (bend_k * dt) * k2, q2);
    Vec qx_edge = qx, qy_edge = qy;
    if (forms == FORM_PHYS) {
      qx_point = qy_point = simd::splat(0.0);
    } else {
      const Vec on = constant(PHYS_ON);
      qx_edge = on * qx;
      qy_edge = on * qy;
      qx_point = qx - qx_edge;
      qy_point = qy - qy_edge;
    }
    edge_shear_forces(fe, quad_natural(fe), quad_edges(fe, x), qx_edge, qy_edge, hq[5], hq[6], hz,
                      hbx, hby);
  }

  // Forces and moments on x_{n+1}.
  const Vec area = fe.area;
  const Vec ba[2] = {fe.b1a, fe.b1b}, bc[2] = {fe.b2a, fe.b2b};
  const Vec gam[4] = {1.0 - fe.sa, -1.0 - fe.sb, 1.0 + fe.sa, -1.0 + fe.sb};
  V3<Vec> fn[4], mn[4];
  for (int a = 0; a < 4; ++a) {
    const Vec b1 = B_SIGN[a] * ba[a % 2], b2 = B_SIGN[a] * bc[a % 2];
    const Vec fbx = area * (b1 * nxx + b2 * nxy) + gam[a] * hq[0];
    const Vec fby = area * (b2 * nyy + b1 * nxy) + gam[a] * hq[1];
    Vec fz = area * (b1 * qx_point + b2 * qy_point);
    const Vec za = GAMMA[a] * fe.warp;
    Vec mx = area * (-b2 * myy - b1 * mxy - 0.25 * qy_point);
    Vec my = area * (b1 * mxx + b2 * mxy + 0.25 * qx_point);
    if (forms & FORM_OLD) {
      fz = fz + gam[a] * hq[2];
      mx = mx + gam[a] * hq[3];
      my = my + gam[a] * hq[4];
    }
    mx = mx + za * fby;
    my = my - za * fbx;
    if (forms & FORM_PHYS) {
      // β = (θy, −θx): a β-force (bx, by) is the moment (−by, bx).
      const Vec quarter = 0.25 * gam[a];
      fz += hz[a];
      mx -= hby[a] + quarter * hq[8];
      my += hbx[a] + quarter * hq[7];
    }
    fn[a] = fbx * fe.e1 + fby * fe.e2 + fz * fe.e3;
    mn[a] = mx * fe.e1 + my * fe.e2;
  }

  // Stable increment of the one-point quad: its breathing mode has ω = 2 c √(1+ν) / h on a
  // square; L = √2 A / (longer diagonal) is h on a square and shorter on skewed elements.
  // A quad crushed to a sliver is faster than L says: the increment is also held to the
  // proven membrane bound of shell4r_increment.hpp (the same on a square).
  const Vec length = 1.41421356237309515 * area / fe.diagonal;
  Vec dt_e = length / constant(DT_SPEED);
  {
    const Vec rho = constant(DENSITY);
    const Vec omega2 =
        shell_membrane_omega2(fe, q11 / rho, constant(POISSON), constant(HG_MODULUS) / rho);
    dt_e = simd::min(dt_e, 2.0 / simd::sqrt(simd::max(omega2, simd::splat(1e-300))));
  }
  if (m_rotary_exact) {
    // ROTARY INERTIA=EXACT: the fastest transverse-shear mode, a tilt of the normal against
    // the rotations, ω² = κ_s G (4/L² + 12/t0²)/ρ (shell4r.hpp) with a margin, may set the
    // increment.
    const Vec t0 = constant(THICKNESS0);
    const Vec omega2 = constant(ROT_SPEED2) * (4.0 / (length * length) + 12.0 / (t0 * t0));
    dt_e = simd::min(dt_e, 2.0 / simd::sqrt(simd::max(omega2, simd::splat(1e-300))));
  }
  Vec strain_inc = fm.area * work;
  Vec plastic_inc = simd::splat(0.0);
  if constexpr (PLASTIC) {
    // The trapezoidal work is the total; ALLSE keeps the recoverable part.
    plastic_inc = fm.area * plastic_work;
    strain_inc -= plastic_inc;
  }

  // A node pushed across the diagonal of its neighbours folds the element over at that corner
  // while its area stays positive (the frame follows the diagonals): a fold past
  // SHELL_FOLD_LIMIT, det J < −τ |J_ξ| |J_η|, squared without a root.
  Vec fold[4];
  {
    Vec det[4], columns[4];
    quad_corner_jacobians(fe, det, columns);
    for (int k = 0; k < 4; ++k)
      fold[k] = det[k] * simd::abs(det[k]) + (SHELL_FOLD_LIMIT * SHELL_FOLD_LIMIT) * columns[k];
  }
  Real e_strain = 0.0, e_hg = 0.0, e_plastic = 0.0, best_dt = std::numeric_limits<Real>::infinity();
  Index critical = NO_INDEX, failed = NO_INDEX;
  // Corners at nodes another thread also writes go to the exchange buffer instead.
  const Index* slots = m_exchange.batch_slots(batch);
  for (int l = 0; l < W; ++l) {
    const Index owner = m_lane_owner[b * W + l];
    if (owner == NO_INDEX) continue;
    for (int a = 0; a < 4; ++a) {
      if (slots != nullptr && slots[a * W + l] != NO_INDEX) {
        Real* e = &m_exchange_force[6 * static_cast<std::size_t>(slots[a * W + l])];
        e[0] = fn[a].x[l];
        e[1] = fn[a].y[l];
        e[2] = fn[a].z[l];
        e[3] = mn[a].x[l];
        e[4] = mn[a].y[l];
        e[5] = mn[a].z[l];
        continue;
      }
      const Index node = conn[a * W + l];
      f[0][node] += fn[a].x[l];
      f[1][node] += fn[a].y[l];
      f[2][node] += fn[a].z[l];
      m[0][node] += mn[a].x[l];
      m[1][node] += mn[a].y[l];
      m[2][node] += mn[a].z[l];
    }
    e_strain += strain_inc[l];
    e_hg += hg_work[l];
    if constexpr (PLASTIC) e_plastic += plastic_inc[l];
    const Index model_e = m_element_index[owner];
    bool folded = false;
    for (int k = 0; k < 4; ++k)
      folded |= fold[k][l] < 0.0 && (m_fold_exempt[b * W + l] >> k & 1u) == 0;
    if (!(area[l] > 0.0) || !(fm.area[l] > 0.0) || !std::isfinite(dt_e[l]) || folded) {
      if (failed == NO_INDEX || model_e < failed) failed = model_e;
    } else if (dt_e[l] < best_dt || (dt_e[l] == best_dt && model_e < critical)) {
      best_dt = dt_e[l];
      critical = model_e;
    }
  }
  m_batch_energy[b * 3 + 0] = e_strain;
  m_batch_energy[b * 3 + 1] = e_hg;
  m_batch_energy[b * 3 + 2] = e_plastic;
  m_batch_dt[b] = best_dt;
  m_batch_critical[b] = critical;
  m_batch_failed[b] = failed;
}

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
  for (Index i = 0; i < size(); ++i) {
    const ShellSectionOutput out = section_output(position, i);
    const std::size_t e = static_cast<std::size_t>(m_element_index[i]);
    for (int c = 0; c < 6; ++c) {
      bottom[e * 6 + c] = out.stress[0][c];
      stress[e * 6 + c] = out.stress[1][c];
      top[e * 6 + c] = out.stress[2][c];
    }
    thickness[e] = out.thickness;
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

#pragma once
/// \file The pieces of the S4R force kernel (Shell4rBlock::compute_batch, shell4r.cpp, the one
/// file that includes this): node gather, through-thickness integration, the physical form's
/// shear and bending hourglass, nodal forces, the stable increment and the per-batch
/// reductions, all inlined into the kernel.

#include <cmath>
#include <limits>
#include <type_traits>

#include "common/types.hpp"
#include "elements/parallel/kernel_inline.hpp"
#include "elements/parallel/simd.hpp"
#include "elements/shell/quad_shell_geometry.hpp"
#include "elements/shell/shell4r.hpp"
#include "elements/shell/shell4r_hourglass.hpp"
#include "elements/shell/shell4r_increment.hpp"
#include "elements/shell/shell4r_section.hpp"
#include "elements/vec3.hpp"

namespace xpl::elements {

using simd::Vec;

namespace shell4r_kernel {

constexpr int W = simd::W;

/// Node signs of the gradient operator: B_I = sign_I · (b_a for I = 0, 2; b_b for I = 1, 3).
constexpr Real B_SIGN[4] = {1.0, 1.0, -1.0, -1.0};
/// Hourglass pattern Γ.
constexpr Real GAMMA[4] = {1.0, -1.0, 1.0, -1.0};

/// The in-plane (N), bending (M) and transverse-shear (Q, through the one-point shear)
/// resultants of a batch, per unit length.
struct ShellResultants {
  Vec nxx, nyy, nxy, mxx, myy, mxy, qx, qy;
};

/// `v` as computed: GCC contracts a product and a sum of later statements into one
/// multiply-add (-ffp-contract=fast, its default for C++), and which product it keeps rounded
/// depends on the code around them. Where a run-time branch used to stand between them (a φ of
/// the two paths), this keeps the same product rounded, so the results keep their bits.
XPL_KERNEL_INLINE Vec rounded(Vec v) {
#if defined(__has_builtin)
#if __has_builtin(__builtin_assoc_barrier)
  return __builtin_assoc_barrier(v);
#endif
#endif
  return v;
}

/// Nodal forces `fn` and moments `mn` (global axes) of a batch on x_{n+1} (frame `fe`) from
/// its resultants `r`, its hourglass resultants `hq` and, on physical-form lanes, the normal
/// forces `hz` and β-forces `hbx`, `hby` of the edge shears; `old_form`, `phys_form`: whether
/// a lane of the batch uses the stiffness or the physical hourglass form. PHYS_ONLY: every lane
/// of the batch uses the physical form (`old_form` false, `phys_form` true), whose shear acts
/// through the edge shears alone: the one-point shear terms, exact zeros there (r.qx = r.qy =
/// 0, ShearForces), are left out (issue 38 item 3: with the run-time forms they kept GCC from
/// holding the loop in registers, about a tenth of the elastic pass's instructions).
template <bool PHYS_ONLY = false>
XPL_KERNEL_INLINE void corner_forces(const QuadFrame<Vec>& fe, const ShellResultants& r,
                                     const Vec hq[], const Vec hz[4], const Vec hbx[4],
                                     const Vec hby[4], bool old_form, bool phys_form, V3<Vec> fn[4],
                                     V3<Vec> mn[4]) {
  if constexpr (PHYS_ONLY) {
    old_form = false;
    phys_form = true;
  }
  const Vec area = fe.area;
  const Vec ba[2] = {fe.b1a, fe.b1b}, bc[2] = {fe.b2a, fe.b2b};
  const Vec gam[4] = {1.0 - fe.sa, -1.0 - fe.sb, 1.0 + fe.sa, -1.0 + fe.sb};
  for (int a = 0; a < 4; ++a) {
    const Vec b1 = B_SIGN[a] * ba[a % 2], b2 = B_SIGN[a] * bc[a % 2];
    const Vec fbx = area * (b1 * r.nxx + b2 * r.nxy) + gam[a] * hq[0];
    const Vec fby = area * (b2 * r.nyy + b1 * r.nxy) + gam[a] * hq[1];
    const Vec za = GAMMA[a] * fe.warp;
    Vec fz, mx, my;
    if constexpr (PHYS_ONLY) {
      fz = simd::splat(0.0);
      mx = rounded(area * (-b2 * r.myy - b1 * r.mxy));
      my = rounded(area * (b1 * r.mxx + b2 * r.mxy));
    } else {
      fz = area * (b1 * r.qx + b2 * r.qy);
      mx = area * (-b2 * r.myy - b1 * r.mxy - 0.25 * r.qy);
      my = area * (b1 * r.mxx + b2 * r.mxy + 0.25 * r.qx);
    }
    if (old_form) {
      fz = fz + gam[a] * hq[2];
      mx = mx + gam[a] * hq[3];
      my = my + gam[a] * hq[4];
    }
    mx = mx + za * fby;
    my = my - za * fbx;
    if (phys_form) {
      // β = (θy, −θx): a β-force (bx, by) is the moment (−by, bx).
      const Vec quarter = 0.25 * gam[a];
      fz += hz[a];
      mx -= hby[a] + quarter * hq[8];
      my += hbx[a] + quarter * hq[7];
    }
    fn[a] = fbx * fe.e1 + fby * fe.e2 + fz * fe.e3;
    mn[a] = mx * fe.e1 + my * fe.e2;
  }
}

/// The hourglass resultants of a batch as its kernel advances them: N values per lane, each
/// from its store at `stored` ([h][W], corotational frame, N or N·m), and their work over the
/// increment `dt` (J) in `work`. Resultants the batch does not use stay 0.
template <int N>
struct HourglassAdvance {
  Real* stored;
  Real dt;
  Vec value[N] = {};
  Vec work = simd::splat(0.0);

  /// Advances resultant h by `increment` (dt times its rate of change), stores it and adds its
  /// trapezoidal work over the generalised rate `rate`.
  XPL_KERNEL_INLINE void store(int h, Vec increment, Vec rate) {
    const Vec old = simd::load(stored + h * W);
    value[h] = old + increment;
    simd::store(stored + h * W, value[h]);
    work += (0.5 * dt) * (old + value[h]) * rate;
  }
  /// Advances resultant h at `stiffness` over `rate`: increment stiffness · dt · rate.
  XPL_KERNEL_INLINE void advance(int h, Vec stiffness, Vec rate) {
    store(h, (stiffness * dt) * rate, rate);
  }
};

/// The transverse shear resultants of a batch (N/m) as they reach the nodes: `qx`, `qy` through
/// the one-point shear (stiffness-form lanes), and on physical-form lanes through the edge
/// shears, the normal forces `hz` and β-forces `hbx`, `hby` per node (N, zero elsewhere).
struct ShearForces {
  Vec qx, qy;
  Vec hz[4] = {}, hbx[4] = {}, hby[4] = {};
};

/// Positions `x`, velocities `vel` and angular velocities `om` of the 4 corners of a batch
/// (component arrays p, v, w; corner node indices `conn`, [corner 4][W]).
XPL_KERNEL_INLINE void gather_nodes(const Index* conn, const Real* const p[3],
                                    const Real* const v[3], const Real* const w[3], V3<Vec> x[4],
                                    V3<Vec> vel[4], V3<Vec> om[4]) {
  for (int a = 0; a < 4; ++a) {
    const Index* idx = conn + a * W;
    x[a] = {simd::gather(p[0], idx), simd::gather(p[1], idx), simd::gather(p[2], idx)};
    vel[a] = {simd::gather(v[0], idx), simd::gather(v[1], idx), simd::gather(v[2], idx)};
    om[a] = {simd::gather(w[0], idx), simd::gather(w[1], idx), simd::gather(w[2], idx)};
  }
}

}  // namespace shell4r_kernel

template <bool PLASTIC>
ShellSectionResultants Shell4rBlock::section_resultants(std::size_t b, Real dt,
                                                        const ShellPlaneRates& r) {
  const Real* cst = &m_const[b * N_CONST * W];
  auto constant = [&](Constant k) { return simd::load(cst + k * W); };
  const Vec dxx = r.dxx, dyy = r.dyy, kxx = r.kxx, kyy = r.kyy;
  const Vec gxz = r.gxz, gyz = r.gyz;
  // Plane stress: the thickness follows the in-plane dilatation of the reference surface,
  // advanced before the resultants (strains at the mid-increment thickness, N and M at the end
  // one: shell4r.hpp, section_resultants).
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
  ShellSectionResultants out;  // the tangents of plastic batches below, the rest at the end
  // Plastic batches: Σ w r and Σ w ζ² r of the points' tangent ratios r, Σ w ζ², what the
  // returns took off the membrane resultants, Σ t w (σ_trial − σ) (the returned ones are N),
  // the flow stress (after the loop in perfectly plastic batches) and whether a point yielded.
  [[maybe_unused]] Vec tan_m = simd::splat(0.0), tan_b = tan_m, weight_b = tan_m, flow = tan_m;
  [[maybe_unused]] Vec returned_off[3] = {tan_m, tan_m, tan_m};
  [[maybe_unused]] bool batch_yielded = false;
  [[maybe_unused]] const bool one_yield = PLASTIC && m_plastic.batch_constant(b);
  // The batch's section rows ([m_points][W], contiguous in their SharedBlocks): one look-up
  // each (an integer division) rather than one per point.
  const Real* zetas = &m_zeta[b * m_points * W];
  const Real* weights = &m_weight[b * m_points * W];
  // One section point: RETURNS (plastic batches with a yielding point) tests its trial and
  // returns it where a lane yields; otherwise the trial is the stress.
  auto point = [&](int k, auto returns) __attribute__((always_inline)) {
    const Vec weight = simd::load(weights + k * W);
    Real* s = &m_stress[(b * m_points + k) * 3 * W];
    const shell4r_kernel::SectionTrial p =
        shell4r_kernel::section_trial(zetas, k, s, weight, offset, t_mid, t, dt, r, q11, q12, g);
    const Vec zeta = p.zeta, tw = p.tw, zk_n = p.zk_n, tw_n = p.tw_n;
    const Vec exx = p.exx, eyy = p.eyy, exy = p.exy;
    const Vec sxx = p.sxx, syy = p.syy, sxy = p.sxy;
    Vec sxx_n = p.sxx_n, syy_n = p.syy_n, sxy_n = p.sxy_n;
    if constexpr (PLASTIC) {
      Vec point_flow;  // σ_y at the end: max(σ_y, σ_vM) to the return's tolerance
      if constexpr (decltype(returns)::value) {
        const ShellPlasticState::YieldTest test = m_plastic.yield_test(b, k, sxx_n, syy_n, sxy_n);
        point_flow = test.yield;
        Vec ratio_k = simd::splat(1.0);
        if (simd::any(test.yielding)) {
          const Vec start[3] = {sxx, syy, sxy};
          const Vec trial[3] = {sxx_n, syy_n, sxy_n};
          Vec ratio;  // tangent ratio: 1 where the point stays elastic, about 0 where it flows
          plastic_work +=
              tw * m_plastic.yielding_return(b, k, test, q11, q12, g, dt, weight, start, sxx_n,
                                             syy_n, sxy_n, thinning, point_flow, ratio);
          returned_off[0] += tw_n * (trial[0] - sxx_n);
          returned_off[1] += tw_n * (trial[1] - syy_n);
          returned_off[2] += tw_n * (trial[2] - sxy_n);
          batch_yielded = true;
          ratio_k = ratio;
        }
        const Vec wz2 = weight * zeta * zeta;
        tan_m += weight * ratio_k;
        tan_b += wz2 * ratio_k;
        weight_b += wz2;
      } else {
        if (!one_yield) point_flow = m_plastic.static_yield(b, k);
      }
      if (!one_yield)
        flow += simd::select(simd::greater(weight, 0.0), weight * point_flow, simd::splat(0.0));
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
  };
  // Returns where a point yielded in the last pass or a trial yields now; else (most shells of
  // a crash model) the elastic loop, which the inlined returns would crowd out of registers.
  if (PLASTIC &&
      (m_plastic.yielded_last(b) ||
       shell4r_kernel::any_point_yields(m_plastic, b, m_points, &m_stress[b * m_points * 3 * W],
                                        zetas, offset, t_mid, t, dt, r, q11, q12, g))) {
    for (int k = 0; k < m_points; ++k) point(k, std::true_type{});
  } else {
    for (int k = 0; k < m_points; ++k) point(k, std::false_type{});
  }
  if constexpr (PLASTIC) {
    m_plastic.set_yielded_last(b, batch_yielded);
    if (one_yield) flow = shell4r_kernel::one_yield_flow(weights, m_points, m_plastic, b);
    shell4r_kernel::plastic_tangents(batch_yielded, tan_m, tan_b, weight_b, returned_off, nxx, nyy,
                                     nxy, flow, weights, m_points, out);
    if (batch_yielded) {  // else Δε33ᵖ = 0: the factor is exactly 1
      const Vec f = shell4r_kernel::plastic_thickness_factor(constant(NU_RATIO), thinning);
      t = t * f;
      simd::store(&m_thickness[b * W], t);
      shell4r_kernel::scale_resultants(f, nxx, nyy, nxy, mxx, myy, mxy);
    }
  }
  shell4r_kernel::transverse_shear(&m_shear[b * 2 * W], constant(SHEAR_T), dt, gxz, gyz, t_mid, t,
                                   work, out);
  out.t = t;
  out.nxx = nxx;
  out.nyy = nyy;
  out.nxy = nxy;
  out.mxx = mxx;
  out.myy = myy;
  out.mxy = mxy;
  out.work = work;
  out.plastic_work = plastic_work;
  return out;
}

template <bool PLASTIC>
void Shell4rBlock::physical_hourglass(std::size_t b, const QuadFrame<Vec>& fm,
                                      const QuadFrame<Vec>& fe, const V3<Vec> x[4],
                                      const EdgeShear<Vec>& edge, Vec rate_tx, Vec rate_ty,
                                      const ShellSectionResultants& sr,
                                      [[maybe_unused]] Vec plastic_on,
                                      shell4r_kernel::HourglassAdvance<N_HOURGLASS>& hg,
                                      shell4r_kernel::ShearForces& shear) {
  const Real* cst = &m_const[b * N_CONST * W];
  auto constant = [&](Constant k) { return simd::load(cst + k * W); };
  const Vec t = sr.t;
  const Vec scale = constant(HG_PHYS);
  const QuadNatural<Vec> nat = quad_natural(fm);
  const Vec shear_k = (scale * constant(SHEAR_T)) * t * fm.area * (1.0 / 3.0);
  hg.advance(5, shear_k * nat.aa, edge.g_xi);
  hg.advance(6, shear_k * nat.cc, edge.g_eta);
  // Bending: q̇ = (γ·θy, −γ·θx)/4, Ṁ = K_b q̇.
  const Vec q1 = 0.25 * rate_ty, q2 = -0.25 * rate_tx;
  Vec k1, k2;
  bending_hourglass_apply(nat, constant(POISSON), q1, q2, k1, k2);
  Vec bend_k = (scale * constant(Q11)) * t * t * t * (1.0 / 36.0) * fm.area;
  if constexpr (PLASTIC) {
    const Vec one = simd::splat(1.0);
    const Vec tangent = simd::max(sr.tangent_bending, simd::splat(SHELL_HOURGLASS_TANGENT_FLOOR));
    bend_k = bend_k * (one + plastic_on * (tangent - one));
  }
  hg.store(7, (bend_k * hg.dt) * k1, q1);
  hg.store(8, (bend_k * hg.dt) * k2, q2);
  Vec qx_edge = sr.qx, qy_edge = sr.qy;
  if (m_batch_forms[b] == FORM_PHYS) {
    shear.qx = shear.qy = simd::splat(0.0);
  } else {
    const Vec on = constant(PHYS_ON);
    qx_edge = on * sr.qx;
    qy_edge = on * sr.qy;
    shear.qx = sr.qx - qx_edge;
    shear.qy = sr.qy - qy_edge;
  }
  edge_shear_forces(fe, quad_natural(fe), quad_edges(fe, x), qx_edge, qy_edge, hg.value[5],
                    hg.value[6], shear.hz, shear.hbx, shear.hby);
}

template <bool PLASTIC>
void Shell4rBlock::finish_batch(Index batch, const QuadFrame<Vec>& fe, Vec mid_area, Vec work,
                                Vec plastic_work, Vec hg_work, const V3<Vec> fn[4],
                                const V3<Vec> mn[4], Real* const f[3], Real* const m[3]) {
  const std::size_t b = static_cast<std::size_t>(batch);
  const Index* conn = &m_conn[b * 4 * W];
  const Real* cst = &m_const[b * N_CONST * W];
  auto constant = [&](Constant k) { return simd::load(cst + k * W); };
  const Vec area = fe.area;
  // Stable increment of the one-point quad: its breathing mode has ω = 2 c √(1+ν) / h on a
  // square; L = √2 A / (longer diagonal) is h on a square and shorter on skewed elements.
  // A quad crushed to a sliver is faster than L says: the increment is also held to the
  // proven membrane bound of shell4r_increment.hpp (the same on a square).
  const Vec length = 1.41421356237309515 * area / fe.diagonal;
  Vec dt_e = length / constant(DT_SPEED);
  {
    const Vec rho = constant(DENSITY);
    const Vec omega2 = shell_membrane_omega2(fe, constant(Q11) / rho, constant(POISSON),
                                             constant(HG_MODULUS) / rho);
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
  Vec strain_inc = mid_area * work;
  Vec plastic_inc = simd::splat(0.0);
  if constexpr (PLASTIC) {
    // The trapezoidal work is the total; ALLSE keeps the recoverable part.
    plastic_inc = mid_area * plastic_work;
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
    if (!(area[l] > 0.0) || !(mid_area[l] > 0.0) || !std::isfinite(dt_e[l]) || folded) {
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

}  // namespace xpl::elements

#include "elements/shell/shell4r.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "elements/shell/quad_shell_geometry.hpp"
#include "elements/shell/shell4r_hourglass.hpp"
#include "elements/shell/shell4r_kernel.hpp"

namespace xpl::elements {

using shell4r_kernel::corner_forces;
using shell4r_kernel::gather_nodes;
using simd::Vec;

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
                                  NodalVectors& force, NodalVectors& moment, int phase) {
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
      if (!in_phase(m_batch_phase, phase, b)) continue;
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

namespace {

/// The two in-plane hourglass resultants of a plastic batch's lanes (physical form with
/// HG_PLASTIC, shell4r_hourglass.hpp; factors of exactly 1 elsewhere) advanced from their
/// stores at `hstore` over rates r0, r1 with stiffness k, relaxed by `relax`, and held to the
/// bound: the pattern's Gauss-point resultant norm (4 × the generalised resultant's) within
/// `limit` (SHELL_HOURGLASS_PLASTIC_BOUND σ_f t, +inf on other lanes). Stores them, puts them
/// in hq[0], hq[1] and adds their work over the increment to `work`.
XPL_KERNEL_INLINE void plastic_membrane_hourglass(Real* hstore, Vec r0, Vec r1, Vec k, Vec relax,
                                                  Vec limit, const QuadNatural<Vec>& nat,
                                                  Vec poisson, Vec area, Real dt, Vec hq[],
                                                  Vec& work) {
  const Vec o0 = simd::load(hstore), o1 = simd::load(hstore + simd::W);
  Vec n0 = relax * (o0 + (k * dt) * r0), n1 = relax * (o1 + (k * dt) * r1);
  const Vec norm = 4.0 * hourglass_field_norm(nat, poisson, area, n0, n1);
  const simd::Mask over = simd::greater(norm, limit);
  if (simd::any(over)) {
    const Vec f = simd::select(over, limit / simd::max(norm, limit), simd::splat(1.0));
    n0 = f * n0;
    n1 = f * n1;
  }
  hq[0] = n0;
  hq[1] = n1;
  simd::store(hstore, n0);
  simd::store(hstore + simd::W, n1);
  work += (0.5 * dt) * (o0 + n0) * r0;
  work += (0.5 * dt) * (o1 + n1) * r1;
}

}  // namespace

template <bool PLASTIC>
void Shell4rBlock::compute_batch(Index batch, const Real* const p[3], const Real* const v[3],
                                 const Real* const w[3], Real dt, Real* const f[3],
                                 Real* const m[3]) {
  const std::size_t b = static_cast<std::size_t>(batch);
  const Index* conn = &m_conn[b * 4 * W];
  const Real* cst = &m_const[b * N_CONST * W];
  auto constant = [&](Constant k) { return simd::load(cst + k * W); };

  V3<Vec> x[4], vel[4], om[4];
  gather_nodes(conn, p, v, w, x, vel, om);

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

  const ShellPlaneRates rates{dxx, dyy, gxy, kxx, kyy, kxy, gxz, gyz};
  const ShellSectionResultants sr = section_resultants<PLASTIC>(b, dt, rates);
  const Vec t = sr.t;

  // Hourglass resultants (accumulated in the corotational frame). In-plane patterns: stiffness
  // form in both forms; bending and transverse shear: the form of the lane (the other form's
  // coefficients are zero on it), each evaluated only when a lane of the batch uses it.
  const Vec bb = 2.0 * (fm.b1a * fm.b1a + fm.b1b * fm.b1b + fm.b2a * fm.b2a + fm.b2b * fm.b2b);
  const Vec c_plane = constant(HG_MODULUS) * t * fm.area * bb * 0.25;
  shell4r_kernel::HourglassAdvance<N_HOURGLASS> hg{&m_hourglass[b * N_HOURGLASS * W], dt};
  // Plastic batches, physical form: the hourglass follows the section's plastic state on the
  // lanes with HG_PLASTIC (shell4r_hourglass.hpp); other lanes get factors of exactly 1.
  [[maybe_unused]] const Vec plastic_on = PLASTIC ? constant(HG_PLASTIC) : simd::splat(0.0);
  if constexpr (PLASTIC) {
    const Vec one = simd::splat(1.0);
    // The bound: +inf on lanes without HG_PLASTIC (and in elastic batches).
    const Vec limit =
        simd::select(simd::greater(plastic_on, 0.0), (SHELL_HOURGLASS_PLASTIC_BOUND * t) * sr.flow,
                     simd::splat(std::numeric_limits<Real>::infinity()));
    plastic_membrane_hourglass(hg.stored, hourglass_rate(fm, ux), hourglass_rate(fm, uy),
                               c_plane * (one + plastic_on * (sr.tangent_membrane - one)),
                               one + plastic_on * (sr.membrane_return - one), limit,
                               quad_natural(fm), constant(POISSON), fm.area, dt, hg.value, hg.work);
  } else {
    hg.advance(0, c_plane, hourglass_rate(fm, ux));
    hg.advance(1, c_plane, hourglass_rate(fm, uy));
  }
  const Vec rate_tx = hourglass_rate(fm, tx), rate_ty = hourglass_rate(fm, ty);
  if (forms & FORM_OLD) {
    const Vec bend = constant(HG_OLD) * t * t * t * (1.0 / 12.0);
    const Vec c_rot = bend * fm.area * bb * 0.25;
    hg.advance(2, bend * bb, hourglass_rate(fm, vz));
    hg.advance(3, c_rot, rate_tx);
    hg.advance(4, c_rot, rate_ty);
  }
  const QuadFrame<Vec> fe = quad_frame(x);
  // Shear resultants acting through the one-point shear (stiffness-form lanes) and through
  // the edge shears (physical lanes, with the linear-part resultants).
  shell4r_kernel::ShearForces shear{sr.qx, sr.qy};
  if (forms & FORM_PHYS)
    physical_hourglass<PLASTIC>(b, fm, fe, x, edge, rate_tx, rate_ty, sr, plastic_on, hg, shear);

  // Forces and moments on x_{n+1}.
  V3<Vec> fn[4], mn[4];
  const shell4r_kernel::ShellResultants resultants{sr.nxx, sr.nyy, sr.nxy,   sr.mxx,
                                                   sr.myy, sr.mxy, shear.qx, shear.qy};
  // Batches of the physical form alone: the corner loop without the forms' run-time branches
  // (bitwise the same forces in elastic batches; in plastic ones GCC contracts the products
  // otherwise, a round-off change).
  if (forms == FORM_PHYS)
    corner_forces<true>(fe, resultants, hg.value, shear.hz, shear.hbx, shear.hby, false, true, fn,
                        mn);
  else
    corner_forces(fe, resultants, hg.value, shear.hz, shear.hbx, shear.hby, forms & FORM_OLD,
                  forms & FORM_PHYS, fn, mn);

  finish_batch<PLASTIC>(batch, fe, fm.area, sr.work, sr.plastic_work, hg.work, fn, mn, f, m);
}

}  // namespace xpl::elements

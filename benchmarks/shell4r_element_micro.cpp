/// The elastic S4R element pass (issue 38 item 3): the production kernel
/// (Shell4rBlock::internal_forces, elements/shell/) against the fastest form of the same
/// computation we can write, on a mesh of random warped quads with random velocities.
///
/// The fastest form computes the same S4R (mid-increment rates, Simpson section, physical
/// hourglass of the elastic section, forces on x_{n+1}, stable increment and fold check) for
/// a block of one section in the physical form, with everything the production kernel keeps
/// general taken out: the section constants are scalars hoisted out of the batch loop, the
/// 5 Simpson points are unrolled with their positions and weights as constants, no per-batch
/// form branches, only the 6 hourglass resultants of the physical form are stored, and the
/// validity, fold and increment checks of the lanes are vector masks with the per-lane work
/// (the scatter, the energy sums) left for a branch-free lane loop. Its arithmetic is written
/// in the production's order, and it uses the production's batch layout (make_batches), so the
/// two give the same forces, moments, energies and increment bit for bit; `check` verifies it
/// (and a relative 1e-12 in case a compiler reorders).
///
/// Usage: shell4r_element_micro MODE [N (60)] [INCREMENTS (100)]
///   MODE prod | fast: N × N random elements, INCREMENTS passes of that kernel alone (for
///   callgrind: the instruction count of a run with fewer increments subtracted gives the
///   count per element-increment); check: both kernels, forces compared after every pass;
///   plate | plastic [YIELD]: the production kernel on the stretched plate of
///   shell4r_stretched_plate.hpp, elastic or perfectly plastic (issue 38 item 1).
/// Built with the benchmarks (cmake -DXPL_BUILD_BENCHMARKS=ON), target shell4r_element_micro.

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "common/types.hpp"
#include "elements/parallel/element_coloring.hpp"
#include "elements/parallel/simd.hpp"
#include "elements/shell/quad_shell_geometry.hpp"
#include "elements/shell/shell4r.hpp"
#include "elements/shell/shell4r_hourglass.hpp"
#include "elements/shell/shell4r_increment.hpp"
#include "elements/vec3.hpp"
#include "shell4r_stretched_plate.hpp"

using namespace xpl;
using namespace xpl::elements;
using simd::Vec;

namespace {

constexpr int W = simd::W;
constexpr int POINTS = 5;

/// The section constants of ShellProperties, as the production's set-up computes them.
struct Section {
  Real q11, q12, g, shear_t, nu_ratio, dt_speed, hg_modulus, hg_phys, poisson, offset, density;
  Real zeta[POINTS], weight[POINTS];  ///< 0.5 ζ − offset and the Simpson weights
  explicit Section(const ShellProperties& p) {
    const Real nu = p.poisson;
    q11 = p.young / (1.0 - nu * nu);
    q12 = nu * q11;
    g = p.young / (2.0 * (1.0 + nu));
    shear_t = SHELL_SHEAR_FACTOR * g;
    nu_ratio = nu / (1.0 - nu);
    dt_speed = shell_wave_speed(p);
    hg_modulus = SHELL_HOURGLASS_STIFFNESS * p.hourglass_scale * p.young;
    hg_phys = p.hourglass_scale;
    poisson = nu;
    offset = p.offset;
    density = p.density;
    const Real h = 2.0 / (POINTS - 1);
    for (int k = 0; k < POINTS; ++k) {
      const Real w = (k == 0 || k == POINTS - 1) ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
      zeta[k] = 0.5 * (-1.0 + k * h) - offset;
      weight[k] = 0.5 * w * h / 3.0;
    }
  }
};

/// The fastest form: state in the production's AoSoA batches, the 6 physical resultants.
class FastS4R {
 public:
  FastS4R(const std::vector<Index>& conn, const ShellProperties& p, Index node_count) : m_s(p) {
    BatchLayout layout = make_batches(conn, 4, node_count, W);
    m_color_batches = layout.color_batches;
    m_owner = layout.lane_owner;
    const std::size_t nb = static_cast<std::size_t>(layout.batch_count());
    m_conn.assign(nb * 4 * W, 0);
    for (std::size_t b = 0; b < nb; ++b)
      for (int l = 0; l < W; ++l) {
        const Index o = m_owner[b * W + l];
        const Index e = o != NO_INDEX ? o : m_owner[b * W];
        for (int a = 0; a < 4; ++a) m_conn[(b * 4 + a) * W + l] = conn[e * 4 + a];
      }
    m_thickness.assign(nb * W, p.thickness);
    m_stress.assign(nb * POINTS * 3 * W, 0.0);
    m_shear.assign(nb * 2 * W, 0.0);
    m_hourglass.assign(nb * 6 * W, 0.0);
    m_energy.assign(nb * 2, 0.0);
    m_dt.assign(nb, 0.0);
    m_critical.assign(nb, NO_INDEX);
    m_failed.assign(nb, NO_INDEX);
    m_fold_exempt.assign(nb * W, 0);
  }

  void pass(const NodalVectors& position, const NodalVectors& velocity, const NodalVectors& angular,
            Real dt, NodalVectors& force, NodalVectors& moment, ShellStepTotals& totals) {
    const Index nn = static_cast<Index>(position.rows());
    const Real* const p[3] = {position.data(), position.data() + nn, position.data() + 2 * nn};
    const Real* const v[3] = {velocity.data(), velocity.data() + nn, velocity.data() + 2 * nn};
    const Real* const w[3] = {angular.data(), angular.data() + nn, angular.data() + 2 * nn};
    Real* const f[3] = {force.data(), force.data() + nn, force.data() + 2 * nn};
    Real* const m[3] = {moment.data(), moment.data() + nn, moment.data() + 2 * nn};
    const Index nb = m_color_batches.back();
    for (Index b = 0; b < nb; ++b) batch(static_cast<std::size_t>(b), p, v, w, dt, f, m);
    for (Index b = 0; b < nb; ++b) {
      totals.strain_energy_increment += m_energy[b * 2];
      totals.hourglass_energy_increment += m_energy[b * 2 + 1];
      totals.merge(m_dt[b], m_critical[b], m_failed[b]);
    }
  }

 private:
  [[gnu::noinline]] void batch(std::size_t b, const Real* const p[3], const Real* const v[3],
                               const Real* const w[3], Real dt, Real* const f[3], Real* const m[3]);

  Section m_s;
  std::vector<Index> m_color_batches, m_owner, m_conn, m_critical, m_failed;
  std::vector<Real> m_thickness, m_stress, m_shear, m_hourglass, m_energy, m_dt;
  std::vector<unsigned char> m_fold_exempt;  ///< [b][W]: corners not checked (none here)
};

/// `v` never fused into a later multiply-add (as shell4r_kernel::rounded()).
inline Vec rounded(Vec v) {
#if defined(__has_builtin)
#if __has_builtin(__builtin_assoc_barrier)
  return __builtin_assoc_barrier(v);
#endif
#endif
  return v;
}

/// Whether every lane of `m` is set.
inline bool all_set(simd::Mask m) {
  std::int64_t r = -1;
  for (int l = 0; l < W; ++l) r &= m[l];
  return r != 0;
}

inline Vec gather(const Real* base, const Index* idx) {
  return simd::gather(base, idx);
}

void FastS4R::batch(std::size_t b, const Real* const p[3], const Real* const v[3],
                    const Real* const w[3], Real dt, Real* const f[3], Real* const m[3]) {
  const Section& c = m_s;
  const Index* conn = &m_conn[b * 4 * W];
  V3<Vec> x[4], vel[4], om[4];
  for (int a = 0; a < 4; ++a) {
    const Index* idx = conn + a * W;
    x[a] = {gather(p[0], idx), gather(p[1], idx), gather(p[2], idx)};
    vel[a] = {gather(v[0], idx), gather(v[1], idx), gather(v[2], idx)};
    om[a] = {gather(w[0], idx), gather(w[1], idx), gather(w[2], idx)};
  }
  // Rates on the mid-increment geometry.
  V3<Vec> xm[4];
  for (int a = 0; a < 4; ++a) xm[a] = x[a] - (0.5 * dt) * vel[a];
  const QuadFrame<Vec> fm = quad_frame(xm);
  QuadCombos<Vec> vx, vy, vz, tx, ty, tz;
  local_combos(fm, vel, vx, vy, vz);
  local_combos(fm, om, tx, ty, tz);
  const V3<Vec> om_sum = om[0] + om[1] + om[2] + om[3];
  const Vec tbx = 0.25 * dot(fm.e1, om_sum), tby = 0.25 * dot(fm.e2, om_sum);
  const Vec zh = fm.warp;
  const QuadCombos<Vec> ux = {vx.d02 - zh * ty.d02, vx.d13 + zh * ty.d13, vx.hg - 4.0 * zh * tby};
  const QuadCombos<Vec> uy = {vy.d02 + zh * tx.d02, vy.d13 - zh * tx.d13, vy.hg + 4.0 * zh * tbx};
  const Vec dxx = grad_x(fm, ux), dyy = grad_y(fm, uy);
  const Vec gxy = grad_x(fm, uy) + grad_y(fm, ux);
  const Vec kxx = grad_x(fm, ty), kyy = -grad_y(fm, tx);
  const Vec kxy = grad_y(fm, ty) - grad_x(fm, tx);
  // Assumed-strain transverse shear from the edge shears.
  Vec wz[4], thx[4], thy[4], s[4];
  for (int a = 0; a < 4; ++a) {
    wz[a] = dot(fm.e3, vel[a]);
    thx[a] = dot(fm.e1, om[a]);
    thy[a] = dot(fm.e2, om[a]);
  }
  edge_shear_rates(quad_edges(fm, xm), wz, thx, thy, s);
  const QuadNatural<Vec> nat = quad_natural(fm);
  const EdgeShear<Vec> edge = edge_shear(fm, nat, s);
  const Vec gxz = edge.gxz, gyz = edge.gyz;

  // Section: thickness first, then the 5 Simpson points unrolled.
  const Real* tp = &m_thickness[b * W];
  const Vec t_old = simd::load(tp);
  const Vec t = t_old * (1.0 - c.nu_ratio * dt * (dxx + dyy - c.offset * t_old * (kxx + kyy)));
  simd::store(&m_thickness[b * W], t);
  const Vec t_mid = 0.5 * (t_old + t);
  Vec nxx = simd::splat(0.0), nyy = nxx, nxy = nxx, mxx = nxx, myy = nxx, mxy = nxx;
  Vec work = simd::splat(0.0);
#pragma GCC unroll 5
  for (int k = 0; k < POINTS; ++k) {
    const Real zeta = c.zeta[k], weight = c.weight[k];
    const Vec zk = t_mid * zeta, tw = t_mid * weight;
    const Vec zk_n = t * zeta, tw_n = t * weight;
    const Vec exx = dt * (dxx + zk * kxx), eyy = dt * (dyy + zk * kyy);
    const Vec exy = dt * (gxy + zk * kxy);
    Real* sp = &m_stress[(b * POINTS + k) * 3 * W];
    const Vec sxx = simd::load(sp), syy = simd::load(sp + W), sxy = simd::load(sp + 2 * W);
    const Vec sxx_n = sxx + c.q11 * exx + c.q12 * eyy;
    const Vec syy_n = syy + c.q12 * exx + c.q11 * eyy;
    const Vec sxy_n = sxy + c.g * exy;
    simd::store(sp, sxx_n);
    simd::store(sp + W, syy_n);
    simd::store(sp + 2 * W, sxy_n);
    nxx += tw_n * sxx_n;
    nyy += tw_n * syy_n;
    nxy += tw_n * sxy_n;
    const Vec twz = tw_n * zk_n;
    mxx += twz * sxx_n;
    myy += twz * syy_n;
    mxy += twz * sxy_n;
    work += (0.5 * tw) * ((sxx + sxx_n) * exx + (syy + syy_n) * eyy + (sxy + sxy_n) * exy);
  }
  Real* sh = &m_shear[b * 2 * W];
  const Vec txz = simd::load(sh), tyz = simd::load(sh + W);
  const Vec txz_n = txz + (c.shear_t * dt) * gxz, tyz_n = tyz + (c.shear_t * dt) * gyz;
  simd::store(sh, txz_n);
  simd::store(sh + W, tyz_n);
  work += (0.5 * dt) * t_mid * ((txz + txz_n) * gxz + (tyz + tyz_n) * gyz);
  const Vec qx = t * txz_n, qy = t * tyz_n;

  // Hourglass resultants: in-plane (stiffness form), shear and bending (physical form).
  Real* hs = &m_hourglass[b * 6 * W];
  Vec hq[6], hg_work = simd::splat(0.0);
  auto advance = [&](int h, Vec increment, Vec rate) {
    const Vec old = simd::load(hs + h * W);
    hq[h] = old + increment;
    simd::store(hs + h * W, hq[h]);
    hg_work += (0.5 * dt) * (old + hq[h]) * rate;
  };
  const Vec bb = 2.0 * (fm.b1a * fm.b1a + fm.b1b * fm.b1b + fm.b2a * fm.b2a + fm.b2b * fm.b2b);
  const Vec c_plane = c.hg_modulus * t * fm.area * bb * 0.25;
  const Vec rate_x = hourglass_rate(fm, ux), rate_y = hourglass_rate(fm, uy);
  advance(0, (c_plane * dt) * rate_x, rate_x);
  advance(1, (c_plane * dt) * rate_y, rate_y);
  const Vec rate_tx = hourglass_rate(fm, tx), rate_ty = hourglass_rate(fm, ty);
  const Vec shear_k = (c.hg_phys * c.shear_t) * t * fm.area * (1.0 / 3.0);
  const Vec k_xi = shear_k * nat.aa, k_eta = shear_k * nat.cc;
  advance(2, (k_xi * dt) * edge.g_xi, edge.g_xi);
  advance(3, (k_eta * dt) * edge.g_eta, edge.g_eta);
  const Vec q1 = 0.25 * rate_ty, q2 = -0.25 * rate_tx;
  Vec k1, k2;
  bending_hourglass_apply(nat, simd::splat(c.poisson), q1, q2, k1, k2);
  const Vec bend_k = (c.hg_phys * c.q11) * t * t * t * (1.0 / 36.0) * fm.area;
  advance(4, (bend_k * dt) * k1, q1);
  advance(5, (bend_k * dt) * k2, q2);

  // Forces and moments on x_{n+1}.
  const QuadFrame<Vec> fe = quad_frame(x);
  Vec hz[4], hbx[4], hby[4];
  edge_shear_forces(fe, quad_natural(fe), quad_edges(fe, x), qx, qy, hq[2], hq[3], hz, hbx, hby);
  const Vec area = fe.area;
  const Vec ba[2] = {fe.b1a, fe.b1b}, bc[2] = {fe.b2a, fe.b2b};
  const Vec gam[4] = {1.0 - fe.sa, -1.0 - fe.sb, 1.0 + fe.sa, -1.0 + fe.sb};
  constexpr Real SIGN[4] = {1.0, 1.0, -1.0, -1.0}, GAMMA[4] = {1.0, -1.0, 1.0, -1.0};
  V3<Vec> fn[4], mn[4];
  for (int a = 0; a < 4; ++a) {
    const Vec b1 = SIGN[a] * ba[a % 2], b2 = SIGN[a] * bc[a % 2];
    const Vec fbx = area * (b1 * nxx + b2 * nxy) + gam[a] * hq[0];
    const Vec fby = area * (b2 * nyy + b1 * nxy) + gam[a] * hq[1];
    // The one-point shear carries nothing on physical lanes (its terms are exact zeros).
    const Vec fz = hz[a];
    const Vec za = GAMMA[a] * fe.warp;
    // Kept rounded as the production's (shell4r_kernel::rounded()): the same bits.
    Vec mx = rounded(area * (-b2 * myy - b1 * mxy));
    Vec my = rounded(area * (b1 * mxx + b2 * mxy));
    mx = mx + za * fby;
    my = my - za * fbx;
    const Vec quarter = 0.25 * gam[a];
    mx -= hby[a] + quarter * hq[5];
    my += hbx[a] + quarter * hq[4];
    fn[a] = fbx * fe.e1 + fby * fe.e2 + fz * fe.e3;
    mn[a] = mx * fe.e1 + my * fe.e2;
  }

  // Stable increment, fold check and validity as masks; the lanes scatter.
  const Vec length = 1.41421356237309515 * area / fe.diagonal;
  Vec dt_e = length / c.dt_speed;
  const Vec omega2 =
      shell_membrane_omega2(fe, simd::splat(c.q11 / c.density), simd::splat(c.poisson),
                            simd::splat(c.hg_modulus / c.density));
  dt_e = simd::min(dt_e, 2.0 / simd::sqrt(simd::max(omega2, simd::splat(1e-300))));
  const Vec strain_inc = fm.area * work;
  Vec det[4], columns[4];
  quad_corner_jacobians(fe, det, columns);
  Vec fold[4];
  for (int k = 0; k < 4; ++k)
    fold[k] = det[k] * simd::abs(det[k]) + (SHELL_FOLD_LIMIT * SHELL_FOLD_LIMIT) * columns[k];
  // Every lane valid and unfolded (the rule): one mask, one test.
  const Vec inf = simd::splat(std::numeric_limits<Real>::infinity());
  const simd::Mask ok =
      (simd::min(simd::min(fold[0], fold[1]), simd::min(fold[2], fold[3])) >= 0.0) & (area > 0.0) &
      (fm.area > 0.0) & (dt_e < inf);
  const bool all_ok = all_set(ok);
  const Index* owner = &m_owner[b * W];
  Real e_strain = 0.0, e_hg = 0.0, best = std::numeric_limits<Real>::infinity();
  Index critical = NO_INDEX, failed = NO_INDEX;
  for (int l = 0; l < W; ++l) {
    const Index o = owner[l];
    if (o == NO_INDEX) continue;
    for (int a = 0; a < 4; ++a) {
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
    bool bad = false;
    if (!all_ok) {  // the exception: the lane's own checks, fold exemptions included
      bool folded = false;
      for (int k = 0; k < 4; ++k)
        folded |= fold[k][l] < 0.0 && (m_fold_exempt[b * W + l] >> k & 1u) == 0;
      bad = !(area[l] > 0.0) || !(fm.area[l] > 0.0) || !std::isfinite(dt_e[l]) || folded;
    }
    if (bad) {
      if (failed == NO_INDEX || o < failed) failed = o;
    } else if (dt_e[l] < best || (dt_e[l] == best && o < critical)) {
      best = dt_e[l];
      critical = o;
    }
  }
  m_energy[b * 2] = e_strain;
  m_energy[b * 2 + 1] = e_hg;
  m_dt[b] = best;
  m_critical[b] = critical;
  m_failed[b] = failed;
}

/// N × N quads on the unit square, nodes moved at random in the plane by up to 0.2 h and out
/// of it by up to 0.1 h (warped, skewed, tapered), random velocities and spins.
struct RandomPlate {
  NodalVectors x, v, w;
  std::vector<Index> conn;
  RandomPlate(int n, unsigned seed) {
    std::mt19937_64 gen(seed);
    std::uniform_real_distribution<Real> u(-1.0, 1.0);
    const int row = n + 1;
    const Real h = 1.0 / n;
    x.resize(row * row, 3);
    v.resize(row * row, 3);
    w.resize(row * row, 3);
    for (int j = 0; j < row; ++j)
      for (int i = 0; i < row; ++i) {
        const int k = i + row * j;
        x(k, 0) = (i + 0.2 * u(gen)) * h;
        x(k, 1) = (j + 0.2 * u(gen)) * h;
        x(k, 2) = 0.1 * h * u(gen);
        for (int d = 0; d < 3; ++d) {
          v(k, d) = u(gen);
          w(k, d) = 30.0 * u(gen);
        }
      }
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Index k = i + row * j;
        conn.insert(conn.end(), {k, k + 1, k + 1 + row, k + row});
      }
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s prod|fast|check|plate|plastic [N] [INCREMENTS] [YIELD]\n",
                 argv[0]);
    return 2;
  }
  const char* mode = argv[1];
  const int n = argc > 2 ? std::atoi(argv[2]) : 60;
  const int increments = argc > 3 ? std::atoi(argv[3]) : 100;
  if (std::strcmp(mode, "plate") == 0 || std::strcmp(mode, "plastic") == 0)
    return micro::run_stretched(std::strcmp(mode, "plastic") == 0, n, increments,
                                argc > 4 ? std::atof(argv[4]) : 50e6);
  RandomPlate plate(n, 38);
  ShellProperties prop;
  prop.density = 7850.0;
  prop.young = 200e9;
  prop.poisson = 0.3;
  prop.thickness = 0.01;
  prop.integration_points = POINTS;
  const Index nn = static_cast<Index>(plate.x.rows());
  const Index ne = static_cast<Index>(plate.conn.size() / 4);
  std::vector<Index> index(ne);
  for (Index e = 0; e < ne; ++e) index[e] = e;
  const Real dt = 1e-7;
  const bool prod = std::strcmp(mode, "fast") != 0, fast = std::strcmp(mode, "prod") != 0;
  Shell4rBlock block(index, plate.conn, std::vector<ShellProperties>(ne, prop), nn);
  FastS4R fast_block(plate.conn, prop, nn);
  NodalVectors fp(nn, 3), mp(nn, 3), ff(nn, 3), mf(nn, 3), x = plate.x;
  double worst = 0.0;
  long bitwise_diff = 0;
  for (int inc = 0; inc < increments; ++inc) {
    // The nodes move with their velocities: the state of every element changes.
    x += dt * plate.v;
    ShellStepTotals tp, tf;
    if (prod) {
      fp.setZero();
      mp.setZero();
      block.internal_forces(x, plate.v, plate.w, dt, fp, mp, tp);
    }
    if (fast) {
      ff.setZero();
      mf.setZero();
      fast_block.pass(x, plate.v, plate.w, dt, ff, mf, tf);
    }
    if (prod && fast) {
      const double scale_f = fp.cwiseAbs().maxCoeff(), scale_m = mp.cwiseAbs().maxCoeff();
      worst = std::max({worst, (fp - ff).cwiseAbs().maxCoeff() / scale_f,
                        (mp - mf).cwiseAbs().maxCoeff() / scale_m});
      for (Index i = 0; i < nn; ++i)
        for (int d = 0; d < 3; ++d) bitwise_diff += (fp(i, d) != ff(i, d)) + (mp(i, d) != mf(i, d));
      bitwise_diff += (tp.strain_energy_increment != tf.strain_energy_increment) +
                      (tp.hourglass_energy_increment != tf.hourglass_energy_increment);
      if (inc == increments - 1)
        std::printf("increment %d: strain %.17g / %.17g, hourglass %.17g / %.17g\n", inc,
                    tp.strain_energy_increment, tf.strain_energy_increment,
                    tp.hourglass_energy_increment, tf.hourglass_energy_increment);
    }
  }
  if (const char* dump = std::getenv("XPL_MICRO_DUMP")) {
    // The last pass's forces and moments, raw, to compare builds bit for bit.
    const NodalVectors& fd = prod ? fp : ff;
    const NodalVectors& md = prod ? mp : mf;
    if (std::FILE* out = std::fopen(dump, "wb")) {
      std::fwrite(fd.data(), sizeof(Real), fd.size(), out);
      std::fwrite(md.data(), sizeof(Real), md.size(), out);
      std::fclose(out);
    }
  }
  if (prod && fast) {
    std::printf(
        "%d elements, %d increments: largest relative force/moment difference %.3g, "
        "%ld values not bitwise equal\n",
        ne, increments, worst, bitwise_diff);
    return worst <= 1e-12 ? 0 : 1;
  }
  std::printf("%s: %d elements, %d increments, f[0] %.6g\n", mode, ne, increments,
              prod ? fp(0, 0) : ff(0, 0));
  return 0;
}

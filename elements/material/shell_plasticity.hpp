#pragma once
/// \file Plane-stress J2 plasticity of the S4R section points: the closest-point return in
/// the plane-stress subspace (Simo & Taylor 1986; Simo & Hughes, Computational Inelasticity,
/// §3.4) and the plastic state of a shell block's section points.
///
/// Stress vector σ = (σxx, σyy, σxy), engineering shear strain. The yield condition is
/// σᵀPσ = ⅔ σ_y² with P = ⅓[[2,−1,0],[−1,2,0],[0,0,6]], i.e. the von Mises ellipse
/// σxx² − σxxσyy + σyy² + 3σxy² = σ_y², and σ33 = 0 holds by construction (the return never
/// leaves the plane-stress subspace; no 3D return with σ33 zeroed afterwards). The backward-
/// Euler return σ = (I + Δγ C P)⁻¹ σ_trial is diagonal in the common eigenbasis of the
/// plane-stress elasticity C and P:
///   (σxx+σyy)/√2 scaled by 1/(1 + Δγ E/(3(1−ν))),
///   (σyy−σxx)/√2 and σxy scaled by 1/(1 + 2GΔγ),
/// so the consistency condition is one scalar equation in Δγ, solved by safeguarded Newton,
/// finished by bisection where Newton does not converge (steep laws: plasticity_root.hpp).
/// The transverse shear stresses stay elastic (as in Belytschko–Tsay codes): they are not
/// part of the yield condition.

#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "common/types.hpp"
#include "elements/material/plane_stress_polynomial.hpp"
#include "elements/material/plasticity.hpp"
#include "elements/parallel/kernel_inline.hpp"
#include "elements/parallel/simd.hpp"

namespace xpl::elements {

/// A trial this little outside the yield surface (relative, on σ²) counts as inside: the
/// stress of a point returned in the last increment lies on the surface to round-off, and a
/// zero-strain pass (dt = 0) must not send it through the return again.
inline constexpr Real SHELL_YIELD_TOLERANCE = 1e-12;

/// Result of the plane-stress return of one section point.
struct PlaneStressReturn {
  Real sxx = 0.0, syy = 0.0, sxy = 0.0;  ///< returned stress, Pa
  Real peeq_increment = 0.0;             ///< Δε̄ᵖ ≥ 0, -
  Real yield_stress = 0.0;               ///< σ_y at the end (with the rate factor), Pa
  Real static_yield = 0.0;               ///< σ_y(ε̄ᵖ_{n+1}, 0), Pa: the next trial's test
  /// Plastic thickness strain Δε33ᵖ = −(Δε11ᵖ + Δε22ᵖ) (plastic incompressibility), -.
  Real thickness_strain = 0.0;
  Real dissipation = 0.0;  ///< σ_y Δε̄ᵖ = σ : Δεᵖ, J/m^3
};

/// Plane-stress J2 return of one section point from the elastic trial stress
/// (σxx, σyy, σxy) (Pa), with plane-stress moduli `q11` = E/(1−ν²), `q12` = νE/(1−ν²),
/// `shear` = G (Pa), plastic strain `peeq` = ε̄ᵖ_n and increment `dt` (s; used by rate laws
/// only, ε̇ᵖ = Δε̄ᵖ/dt). Solves ‖σ(Δγ)‖_vM = σ_y(ε̄ᵖ_n + ⅔Δγ‖σ(Δγ)‖_vM, Δε̄ᵖ/dt) to a
/// relative residual of 1e-13; a trial inside σ_y(ε̄ᵖ_n, 0) is returned unchanged.
PlaneStressReturn plane_stress_return(const Plasticity& law, Real q11, Real q12, Real shear,
                                      Real sxx, Real syy, Real sxy, Real peeq, Real dt);

/// The end of the return of a batch's lanes.
struct PlaneStressLanes {
  simd::Vec sxx, syy, sxy;  ///< returned stress (the trial in lanes not returned), Pa
  simd::Vec dpeeq;          ///< Δε̄ᵖ (0 in lanes not returned), -
  simd::Vec yield;          ///< σ_y at the end (with the rate factor), Pa
  simd::Vec dgamma;         ///< Δγ (0 in lanes not returned)
};

/// The safeguarded Newton return of the lanes in `rest`, finished by bisection where it does
/// not converge (plasticity_root.hpp), written into those lanes of `r`: the lanes in `linear`
/// (a subset) on their segment σ_y = seg_stress + seg_slope Δε̄ᵖ, again through flow_stress
/// where ε̄ᵖ passes the segment's end `seg_end`, the others through flow_stress (laws[l],
/// ε̄ᵖ_n = peeq[l]). Out of line: the kernels' common case never calls it.
void newton_return_lanes(const Plasticity* const* laws, simd::Mask rest, simd::Mask linear,
                         simd::Vec seg_stress, simd::Vec seg_slope, simd::Vec seg_end,
                         simd::Vec q11, simd::Vec q12, simd::Vec shear, simd::Vec sxx,
                         simd::Vec syy, simd::Vec sxy, simd::Vec peeq, Real dt,
                         PlaneStressLanes& r);

/// The plane-stress return of the lanes in `active` from the trial (sxx, syy, sxy): those in
/// `linear` (rate-free tables; σ_y = seg_stress + seg_slope Δε̄ᵖ up to ε̄ᵖ = seg_end) by the
/// polynomial return (plane_stress_polynomial.hpp), inline; the rest by newton_return_lanes:
/// the other laws, the linear lanes the polynomial return leaves (`failed`), and through
/// flow_stress those whose ε̄ᵖ passed the segment's end (a table break crossed within the
/// increment). `laws()` gives the lanes' laws, asked for only when the Newton return runs.
template <class Laws>
XPL_KERNEL_INLINE PlaneStressLanes plane_stress_lanes(Laws laws, simd::Mask active,
                                                      simd::Mask linear, simd::Vec seg_stress,
                                                      simd::Vec seg_slope, simd::Vec seg_end,
                                                      simd::Vec q11, simd::Vec q12, simd::Vec shear,
                                                      simd::Vec sxx, simd::Vec syy, simd::Vec sxy,
                                                      simd::Vec peeq, Real dt) {
  const PolynomialReturn p =
      polynomial_return(linear, seg_stress, seg_slope, q11, q12, shear, sxx, syy, sxy);
  const simd::Vec sum = sxx + syy, diff = sxx - syy;
  PlaneStressLanes r;
  r.sxx = simd::select(linear, 0.5 * (sum * p.f1 + diff * p.f2), sxx);
  r.syy = simd::select(linear, 0.5 * (sum * p.f1 - diff * p.f2), syy);
  r.sxy = simd::select(linear, sxy * p.f2, sxy);
  r.dpeeq = p.dpeeq;
  r.yield = p.yield;
  r.dgamma = p.dgamma;
  const simd::Mask crossed = linear & ~p.failed & simd::greater(peeq + p.dpeeq, seg_end);
  const simd::Mask rest = (active & ~linear) | p.failed | crossed;
  if (simd::any(rest)) [[unlikely]]
    newton_return_lanes(laws(), rest, p.failed, seg_stress, seg_slope, seg_end, q11, q12, shear,
                        sxx, syy, sxy, peeq, dt, r);
  return r;
}

/// The von Mises product of two plane stresses a, b (Pa²): a·b = a_xx b_xx − ½(a_xx b_yy +
/// a_yy b_xx) + a_yy b_yy + 3 a_xy b_xy, so a·a = σ_vM(a)².
XPL_KERNEL_INLINE simd::Vec von_mises_product(simd::Vec axx, simd::Vec ayy, simd::Vec axy,
                                              simd::Vec bxx, simd::Vec byy, simd::Vec bxy) {
  return axx * bxx - 0.5 * (axx * byy + ayy * bxx) + ayy * byy + 3.0 * (axy * bxy);
}

/// Plastic state of the section points of a batched shell block: equivalent plastic strain,
/// the static yield stress per point, and the laws of the plastic lanes.
/// Empty (no arrays, no work) when no element of the block is plastic.
class ShellPlasticState {
 public:
  static constexpr int W = simd::W;

  ShellPlasticState() = default;
  /// `lane_law`: per batch lane ([b][W]) the plastic law of its element, nullptr where
  /// elastic; `points` = section points per element of the block (max).
  ShellPlasticState(std::span<const Plasticity* const> lane_law, int points);

  bool empty() const { return m_laws.empty(); }
  /// Whether any lane of batch b is plastic.
  bool batch_plastic(std::size_t b) const { return !empty() && m_batch_plastic[b] != 0; }
  /// Whether a section point of plastic batch b yielded in its last pass: a hint for the next
  /// one (where none did, the S4R kernel tests every point before it loops; where one did,
  /// it goes straight to the loop with the returns). Never part of the results.
  bool yielded_last(std::size_t b) const { return m_batch_yielded[b] != 0; }
  void set_yielded_last(std::size_t b, bool yielded) {
    m_batch_yielded[b] = static_cast<unsigned char>(yielded);
  }
  /// Whether the lanes of batch b are all perfectly plastic at one yield stress (rate-free
  /// tables of one point: a segment of slope 0 that never ends). Their points keep ε̄ᵖ alone:
  /// no stored yield stress, no segment index (issue 38 item 1: a third of the bytes a
  /// yielding batch read and wrote).
  bool batch_constant(std::size_t b) const { return !std::isnan(m_constant_yield[b]); }

  /// Plane-stress return of section point k of batch b, in place on the trial stresses
  /// (Pa) of the increment from the stresses `start` (σxx, σyy, σxy at t_n, Pa): one SIMD
  /// yield test, then the scalar return only in the lanes that yield. Returns the plastic
  /// work ½(σ_n + σ_{n+1}) : Δεᵖ (J/m^3) and adds Δε33ᵖ to `thickness_strain` weighted by
  /// `weight`, both zero in the lanes that stay elastic. `flow`, where given, receives the
  /// lanes' flow stress at the end (Pa): σ_y with the rate factor where the point yields (its
  /// σ_vM, to the return's tolerance), σ_y(ε̄ᵖ_n, 0) where it stays elastic (≥ its σ_vM to
  /// SHELL_YIELD_TOLERANCE), +inf in elastic lanes. `tangent`, where given, receives the
  /// points' tangent ratio: the returned stress increment along the elastic one in the von
  /// Mises product, over the elastic one's square, in [0, 1]; 1 where the point stays elastic
  /// (the S4R physical hourglass follows it). Returns whether a lane yields through `yielded`
  /// where given. Inline (below): the S4R kernel's common case, all lanes on a table segment,
  /// runs without a call.
  XPL_KERNEL_INLINE simd::Vec point_return(std::size_t b, int k, simd::Vec q11, simd::Vec q12,
                                           simd::Vec shear, Real dt, simd::Vec weight,
                                           const simd::Vec start[3], simd::Vec& sxx, simd::Vec& syy,
                                           simd::Vec& sxy, simd::Vec& thickness_strain,
                                           simd::Vec* flow = nullptr, simd::Vec* tangent = nullptr,
                                           bool* yielded = nullptr);

  /// The yield test of point_return alone: σ_y(ε̄ᵖ_n, 0) of section point k of batch b per
  /// lane (+inf in elastic lanes) and the lanes whose trial (σxx, σyy, σxy) lies outside it by
  /// more than SHELL_YIELD_TOLERANCE. Where no lane yields, point_return leaves the stresses
  /// and the state alone, returns 0 and gives the tangent ratio 1 and the flow stress `yield`:
  /// a kernel can test first and keep the trial stresses in registers.
  struct YieldTest {
    simd::Vec yield;
    simd::Mask yielding;
  };
  XPL_KERNEL_INLINE YieldTest yield_test(std::size_t b, int k, simd::Vec sxx, simd::Vec syy,
                                         simd::Vec sxy) const {
    const simd::Vec y =
        batch_constant(b) ? simd::splat(m_constant_yield[b]) : simd::load(&m_yield[row(b, k)]);
    const simd::Vec vm2 = sxx * sxx - sxx * syy + syy * syy + 3.0 * (sxy * sxy);
    return {y, simd::greater(vm2, (y * y) * (1.0 + SHELL_YIELD_TOLERANCE))};
  }
  /// The rest of point_return where `test` (yield_test of the same trial) has a yielding
  /// lane: the return in place, Δε33ᵖ into `thickness_strain`, the flow stress and tangent
  /// ratio into `flow` and `tangent`; returns the plastic work.
  XPL_KERNEL_INLINE simd::Vec yielding_return(std::size_t b, int k, const YieldTest& test,
                                              simd::Vec q11, simd::Vec q12, simd::Vec shear,
                                              Real dt, simd::Vec weight, const simd::Vec start[3],
                                              simd::Vec& sxx, simd::Vec& syy, simd::Vec& sxy,
                                              simd::Vec& thickness_strain, simd::Vec& flow,
                                              simd::Vec& tangent);

  /// σ_y(ε̄ᵖ, 0) (Pa) of section point k of batch b per lane after its last return (the next
  /// trial's yield test); +inf in elastic lanes.
  simd::Vec static_yield(std::size_t b, int k) const {
    return batch_constant(b) ? simd::splat(m_constant_yield[b]) : simd::load(&m_yield[row(b, k)]);
  }
  /// ε̄ᵖ (-) of section point k of batch b, lane l; 0 where elastic.
  Real peeq(std::size_t b, int k, std::size_t l) const;
  /// Sets ε̄ᵖ (≥ 0) of section point k of batch b, lane l (an imported state); the static
  /// yield stress follows. Elastic lanes are left alone.
  void set_peeq(std::size_t b, int k, std::size_t l, Real value);

 private:
  /// The rare end of point_return: σ_y of the `other` lanes with a rate law, the segments of
  /// the lanes that `passed` their segment's end.
  [[gnu::noinline]] void finish_point(std::size_t b, std::size_t r, simd::Mask other,
                                      simd::Mask passed, simd::Vec peeq_end);
  /// The laws of the lanes of batch b (elastic lanes: law 0, never asked for).
  void lane_laws(std::size_t b, const Plasticity* laws[W]) const {
    for (std::size_t l = 0; l < W; ++l) {
      const int law = m_lane_law[b * W + l];
      laws[l] = &m_laws[static_cast<std::size_t>(law < 0 ? 0 : law)];
    }
  }
  std::size_t row(std::size_t b, int k) const {
    return (b * static_cast<std::size_t>(m_points) + static_cast<std::size_t>(k)) * W;
  }

  int m_points = 0;
  std::vector<Plasticity> m_laws;              ///< distinct laws of the block
  std::vector<int> m_lane_law;                 ///< [b][W] index into m_laws, −1 elastic
  std::vector<unsigned char> m_batch_plastic;  ///< [b] any lane plastic
  /// [b] a point yielded in the batch's last pass (yielded_last). Each batch is one thread's
  /// in a pass, so threads write distinct bytes.
  std::vector<unsigned char> m_batch_yielded;
  std::vector<Real> m_peeq;  ///< [b][points][W] ε̄ᵖ, -
  /// [b] σ_y (Pa) of the batches whose lanes are all perfectly plastic at it (batch_constant);
  /// NaN in the others.
  std::vector<Real> m_constant_yield;
  /// [b][points][W] σ_y(ε̄ᵖ, 0), Pa; +inf elastic. Empty when every plastic batch is
  /// batch_constant (its rows unused: the other batches' are all the arrays below need).
  std::vector<Real> m_yield;
  /// [b][W] −1 where the lane's law is a rate-free table (its flow stress piecewise linear in
  /// ε̄ᵖ: the polynomial return), else 0.
  std::vector<std::int64_t> m_lane_linear;
  /// [b][points][W] (empty with m_yield) tabular laws: index into the segment table of the segment
  /// holding ε̄ᵖ (the last point ε_i ≤ ε̄ᵖ), kept up as ε̄ᵖ grows so that a return does not search the
  /// table; 0 (a segment of slope 0 that never ends) for the other laws.
  std::vector<Index> m_segment;
  /// The segments of the tabular laws one after the other, after the entry 0 above: slope
  /// (Pa) and the ε̄ᵖ where it ends (the next table point; +inf on a law's last, constant part).
  std::vector<Real> m_segment_slope, m_segment_end;
  std::vector<Index> m_law_segment;  ///< per law: index of its first segment (0 untabulated)
};

XPL_KERNEL_INLINE simd::Vec ShellPlasticState::point_return(
    std::size_t b, int k, simd::Vec q11, simd::Vec q12, simd::Vec shear, Real dt, simd::Vec weight,
    const simd::Vec start[3], simd::Vec& sxx, simd::Vec& syy, simd::Vec& sxy,
    simd::Vec& thickness_strain, simd::Vec* flow, simd::Vec* tangent, bool* yielded) {
  const YieldTest test = yield_test(b, k, sxx, syy, sxy);
  const bool any_yielding = simd::any(test.yielding);
  if (yielded != nullptr) *yielded = any_yielding;
  simd::Vec flow_end = test.yield, ratio = simd::splat(1.0);
  simd::Vec dissipation = simd::splat(0.0);
  if (any_yielding)
    dissipation = yielding_return(b, k, test, q11, q12, shear, dt, weight, start, sxx, syy, sxy,
                                  thickness_strain, flow_end, ratio);
  if (flow != nullptr) *flow = flow_end;
  if (tangent != nullptr) *tangent = ratio;
  return dissipation;
}

XPL_KERNEL_INLINE simd::Vec ShellPlasticState::yielding_return(
    std::size_t b, int k, const YieldTest& test, simd::Vec q11, simd::Vec q12, simd::Vec shear,
    Real dt, simd::Vec weight, const simd::Vec start[3], simd::Vec& sxx, simd::Vec& syy,
    simd::Vec& sxy, simd::Vec& thickness_strain, simd::Vec& flow, simd::Vec& tangent) {
  using simd::Vec;
  const std::size_t r = row(b, k);
  // Perfectly plastic batches (the common case of crash decks) read no state but ε̄ᵖ, and that
  // only where a lane yields.
  const bool constant = batch_constant(b);
  const Vec y = test.yield;
  const simd::Mask yielding = test.yielding;
  Vec dissipation = simd::splat(0.0);
  // The elastic stress increment of the tangent ratio.
  const Vec trial[3] = {sxx - start[0], syy - start[1], sxy - start[2]};
  // Rate-free tables on the segment of ε̄ᵖ_n: σ_y = y + slope Δε̄ᵖ (y = σ_y(ε̄ᵖ_n), kept up
  // by the returns) up to ε̄ᵖ = end, slope and end from the segment table.
  const simd::Mask linear = constant ? yielding : simd::load_mask(&m_lane_linear[b * W]) & yielding;
  const Index* segment = constant ? nullptr : &m_segment[r];
  Vec slope, end;
  bool uniform = true;  // the lanes on one segment (one law on one part of it): no gather
  for (std::size_t l = 1; l < W && !constant; ++l) uniform &= segment[l] == segment[0];
  if (constant) [[likely]] {
    slope = simd::splat(0.0);
    end = simd::splat(std::numeric_limits<Real>::infinity());
  } else if (uniform) [[likely]] {
    slope = simd::splat(m_segment_slope[static_cast<std::size_t>(segment[0])]);
    end = simd::splat(m_segment_end[static_cast<std::size_t>(segment[0])]);
  } else {
    slope = simd::gather(m_segment_slope.data(), segment);
    end = simd::gather(m_segment_end.data(), segment);
  }
  const Vec peeq = simd::load(&m_peeq[r]);
  const Plasticity* laws[W];
  const PlaneStressLanes ret = plane_stress_lanes(
      [&] {
        lane_laws(b, laws);
        return laws;
      },
      yielding, linear, y, slope, end, q11, q12, shear, sxx, syy, sxy, peeq, dt);
  sxx = ret.sxx;
  syy = ret.syy;
  sxy = ret.sxy;
  const Vec peeq_end = peeq + ret.dpeeq;
  simd::store(&m_peeq[r], peeq_end);
  // Δεᵖ = Δγ P σ: Δε11ᵖ + Δε22ᵖ = Δγ (σxx + σyy)/3, so Δε33ᵖ = −Δγ (σxx + σyy)/3.
  thickness_strain -= weight * ret.dgamma * (sxx + syy) * (1.0 / 3.0);
  // The plastic work ½(σ_n + σ_{n+1}) : Δεᵖ with Δεᵖ = Δγ P σ_{n+1} (engineering shear):
  // with the trapezoidal stress work, ALLSE is the elastic energy of the stress state
  // (return_work() of the hex points, radial_return_lanes.hpp, says why).
  const Vec work = (0.5 / 3.0) * ret.dgamma *
                   ((start[0] + sxx) * (2.0 * sxx - syy) + (start[1] + syy) * (2.0 * syy - sxx) +
                    6.0 * (start[2] + sxy) * sxy);
  dissipation = simd::select(yielding, work, dissipation);
  // The next trial's test: σ_y(ε̄ᵖ_{n+1}, 0), the end yield stress itself without a rate law
  // (finish_point takes the rate factor out where there is one).
  const Vec end_yield = simd::select(yielding, ret.yield, y);
  if (!constant) simd::store(&m_yield[r], end_yield);
  flow = end_yield;
  {
    const Vec along = von_mises_product(sxx - start[0], syy - start[1], sxy - start[2], trial[0],
                                        trial[1], trial[2]);
    const Vec trial2 =
        von_mises_product(trial[0], trial[1], trial[2], trial[0], trial[1], trial[2]);
    const Vec ratio =
        simd::min(simd::max(along / simd::max(trial2, simd::splat(1e-300)), simd::splat(0.0)),
                  simd::splat(1.0));
    tangent = simd::select(yielding & simd::greater(trial2, 0.0), ratio, simd::splat(1.0));
  }
  if (constant) return dissipation;  // every lane linear, on a segment that never ends
  const simd::Mask other = yielding & ~linear;
  const simd::Mask passed = linear & simd::greater_equal(peeq_end, end);
  if (simd::any(other | passed)) [[unlikely]]
    finish_point(b, r, other, passed, peeq_end);
  return dissipation;
}

}  // namespace xpl::elements

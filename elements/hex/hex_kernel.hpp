#pragma once
/// \file The pieces of the force kernel both hex kinds compute alike (hex8r.cpp, hex8.cpp), on
/// a batch of simd::W lanes: the Jaumann-rate elastic update, the stress power, the bulk
/// viscosity with the stable increment it damps. Force-inlined into the kernels, so that a
/// kernel compiles as one function, as it did when they were written out in each.

#include <cmath>

#include "common/types.hpp"
#include "elements/hex/hex8_geometry.hpp"
#include "elements/parallel/kernel_inline.hpp"
#include "elements/parallel/simd.hpp"
#include "elements/vec3.hpp"

namespace xpl::elements::hex_kernel {

using simd::Vec;

/// Rate of deformation (d00 d11 d22 d01 d02 d12) and spin (w01 w02 w12) of a velocity
/// gradient L, the volumetric part of D shifted by `shift` on the diagonal (C3D8's mean
/// dilatation; 0 for C3D8R).
struct Rates {
  Vec d[6];
  Vec w[3];
};
XPL_KERNEL_INLINE Rates rates(const Vec L[3][3], Vec shift) {
  Rates r;
  r.d[0] = L[0][0] + shift;
  r.d[1] = L[1][1] + shift;
  r.d[2] = L[2][2] + shift;
  r.d[3] = 0.5 * (L[0][1] + L[1][0]);
  r.d[4] = 0.5 * (L[0][2] + L[2][0]);
  r.d[5] = 0.5 * (L[1][2] + L[2][1]);
  r.w[0] = 0.5 * (L[0][1] - L[1][0]);
  r.w[1] = 0.5 * (L[0][2] - L[2][0]);
  r.w[2] = 0.5 * (L[1][2] - L[2][1]);
  return r;
}
/// As above without a shift.
XPL_KERNEL_INLINE Rates rates(const Vec L[3][3]) {
  Rates r;
  r.d[0] = L[0][0];
  r.d[1] = L[1][1];
  r.d[2] = L[2][2];
  r.d[3] = 0.5 * (L[0][1] + L[1][0]);
  r.d[4] = 0.5 * (L[0][2] + L[2][0]);
  r.d[5] = 0.5 * (L[1][2] + L[2][1]);
  r.w[0] = 0.5 * (L[0][1] - L[1][0]);
  r.w[1] = 0.5 * (L[0][2] - L[2][0]);
  r.w[2] = 0.5 * (L[1][2] - L[2][1]);
  return r;
}

/// Jaumann-rate elastic update σ_{n+1} = σ_n + Δt (λ tr(D) I + 2μ D + Wσ − σW) of the stress
/// `s` (s0 s1 s2 = 11 22 33, s3 = 12, s4 = 13, s5 = 23) into `sn`; `lt` = λ tr(D).
XPL_KERNEL_INLINE void jaumann_update(const Vec s[6], const Rates& r, Vec lt, Vec two_mu, Real dt,
                                      Vec sn[6]) {
  const Vec w01 = r.w[0], w02 = r.w[1], w12 = r.w[2];
  // R = Wσ (σ symmetric); Wσ − σW = R + Rᵀ.
  const Vec r00 = w01 * s[3] + w02 * s[4];
  const Vec r11 = -w01 * s[3] + w12 * s[5];
  const Vec r22 = -w02 * s[4] - w12 * s[5];
  const Vec r01 = w01 * s[1] + w02 * s[5], r10 = -w01 * s[0] + w12 * s[4];
  const Vec r02 = w01 * s[5] + w02 * s[2], r20 = -w02 * s[0] - w12 * s[3];
  const Vec r12 = -w01 * s[4] + w12 * s[2], r21 = -w02 * s[3] - w12 * s[1];
  sn[0] = s[0] + dt * (lt + two_mu * r.d[0] + 2.0 * r00);
  sn[1] = s[1] + dt * (lt + two_mu * r.d[1] + 2.0 * r11);
  sn[2] = s[2] + dt * (lt + two_mu * r.d[2] + 2.0 * r22);
  sn[3] = s[3] + dt * (two_mu * r.d[3] + r01 + r10);
  sn[4] = s[4] + dt * (two_mu * r.d[4] + r02 + r20);
  sn[5] = s[5] + dt * (two_mu * r.d[5] + r12 + r21);
}

/// (σ_n + σ_{n+1}) : D, twice the mid-increment stress power per unit volume (Pa/s).
XPL_KERNEL_INLINE Vec stress_power2(const Vec s[6], const Vec sn[6], const Rates& r) {
  return (s[0] + sn[0]) * r.d[0] + (s[1] + sn[1]) * r.d[1] + (s[2] + sn[2]) * r.d[2] +
         2.0 * ((s[3] + sn[3]) * r.d[3] + (s[4] + sn[4]) * r.d[4] + (s[5] + sn[5]) * r.d[5]);
}

/// Characteristic length, bulk viscosity and stable increment of a batch.
struct BulkViscosity {
  Vec area;    ///< √A²_max, the largest face (mode-space measure), m²
  Vec length;  ///< L_e = V / A_max, m
  Vec sv;      ///< bulk-viscosity pressure (tensile-positive), Pa
  Vec dt_e;    ///< element stable increment with the viscosity's damping ξ, s
};
/// At x_{n+1} (modes `ax`, volume `vol`) with the volumetric rate `tr` (1/s), the lanes'
/// density, wave speed c_d and factor poisson_dt_factor(ν), and b1, b2 of the step.
XPL_KERNEL_INLINE BulkViscosity bulk_viscosity(const V3<Vec> ax[8], Vec vol, Vec tr, Vec density,
                                               Vec wave, Vec dt_factor, Real b1, Real b2) {
  BulkViscosity v;
  v.area = simd::sqrt(max_face_area_squared(ax));
  v.length = vol / v.area;
  const Vec compress = simd::min(tr, simd::splat(0.0));
  const Vec b2l = b2 * v.length;
  v.sv = b1 * density * wave * v.length * tr - density * b2l * b2l * compress * compress;
  // Stable increment with bulk-viscosity damping ξ (Abaqus-style estimate).
  const Vec xi = b1 - b2 * b2 * (v.length / wave) * compress;
  v.dt_e = dt_factor * (v.length / wave) * (simd::sqrt(1.0 + xi * xi) - xi);
  return v;
}

/// Bulk-viscosity work over the increment by the trapezoidal rule, as every other term of the
/// balance: the pressure of the last call (`before`, [W], replaced by `sv`) acted over this
/// increment too (ALLKE = ½ v(n−½)·M·v(n+½) counts it so). This increment's pressure alone
/// overstates the damping of a mode at ω by about (ωΔt)²/4 of it.
XPL_KERNEL_INLINE Vec viscous_work(Real* before, Vec sv, Real dt, Vec volm, Vec tr) {
  const Vec work = dt * volm * (0.5 * (simd::load(before) + sv)) * tr;
  simd::store(before, sv);
  return work;
}

}  // namespace xpl::elements::hex_kernel

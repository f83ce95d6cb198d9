#pragma once
/// \file Upper bound on the largest membrane frequency of the one-point S4R (issue 32 item 5).
///
/// The stable-increment length L = √2 A / (longer diagonal) of shell4r.cpp gives the breathing
/// mode of a square exactly, but on a quad crushed to a sliver it is optimistic: on a 10 × 2
/// rectangle the largest membrane frequency is 1.22 × 2 c √(1+ν) / L, more than the safety
/// factor 0.9 covers, and a single free element of that shape blows up in two increments
/// (tests/solver/test_shell_stability.cpp). The bound below is exact for the constant-strain
/// part and proven for the in-plane hourglass part; the element takes the smaller increment.
///
/// Constant strain: with the lumped mass m = ρ t A / 4 per node and K = t A Bᵀ Q B (Q the
/// plane-stress law), ω² = (4/ρ) λ_max(Bᵀ Q B). The displacement of each direction enters only
/// through its projection on span(B1, B2); in the principal axes of their Gram matrix G
/// (trace T = Σ_I |∇N_I|², determinant D = |B1|²|B2|² − (B1·B2)²) the normal strains give
///   λ_max = (Q11/2) (T + √(T² − 4 (1 − ν²) D)),
/// and the shear strains (1 − ν) Q11 T / 2, never more. On a square of side h this is
/// Q11 (1+ν)/h², the breathing mode of the L measure.
///
/// In-plane hourglass (stiffness form, both hourglass forms): K_h = c γ γᵀ in each direction,
/// c = κE t A T/4, with the Flanagan–Belytschko vector γ = Γ − w, w = h_x B1 + h_y B2 in
/// span(B1, B2), and Γ = (1, −1, 1, −1) orthogonal to span(B1, B2). Since
/// (Γ − w)(Γ − w)ᵀ ≤ 2 ΓΓᵀ + 2 w wᵀ and K + 2c w wᵀ acts in span(B1, B2) while 2c ΓΓᵀ acts
/// on Γ, orthogonal to it (and the mass is a multiple of the identity),
///   ω² ≤ max(ω_cs² + 2 (c/m) |w|², 8 c/m),  c/m = κ E T / ρ.
/// On a parallelogram (w = 0) this is max(ω_cs², ω_h²), the exact answer; a square keeps its
/// increment. The bound ignores, as the L measure does, that the mass was lumped on the
/// reference area and thickness: t A stays t₀ A₀ under plastic flow (incompressible), and
/// elastic changes of t A are of the order of the elastic strains.
///
/// Rotational modes (physical hourglass form): the scaled rotary inertia of shell4r.hpp keeps
/// the tilt mode of a square below its breathing mode, but the edge shears of the
/// assumed-strain transverse shear see the rotations through the edge vectors. On a
/// parallelogram of angle θ between its natural axes X_ξ, X_η the rotation patterns linear in
/// ξ or η (β = ξ b) have ω² = κ_s G / (3 ρ r² sin²θ), 1/(3 sin²θ) times the tilt's rotational
/// part, and a taper X_h (x = … + X_h ξη) couples them with the centre shear. The factor
/// shell_rotary_shape_factor() on r² = max(t²/12, c_ν L²) covers both (not on
/// ROTARY INERTIA=EXACT, whose increment has its own bound); it is 1 on
/// rectangles, squares and mildly distorted quads (sin²θ ≥ 2/3 and no taper), so regular
/// meshes keep their inertia bit for bit. Its coefficients were fitted to the 12 × 12
/// out-of-plane eigenproblem of the element on a random set of convex quads (aspect up to 20,
/// angles down to 2°, tapers up to 0.95; tests/elements/test_shell4r_hourglass.cpp): the
/// least factor that keeps every mode within the increment (ω Δt_e ≤ 2) was at most 0.84 of
/// this one on thin elements (fit 2026-12-06). This is a verified, not a proven, bound: a
/// closed-form proof of the 12 × 12 problem is still to do. All functions are templates over the
/// lane type (`Real` or `simd::Vec`).

#include "elements/shell/quad_shell_geometry.hpp"
#include "elements/shell/shell4r_hourglass.hpp"

namespace xpl::elements {

/// Upper bound on ω² (1/s²) of the membrane of a one-point quad of frame f: `q11_rho` =
/// E/((1−ν²)ρ), `nu` = ν, `hourglass_rho` = κE/ρ of the in-plane hourglass stiffness (m²/s²).
template <class T>
inline T shell_membrane_omega2(const QuadFrame<T>& f, T q11_rho, T nu, T hourglass_rho) {
  const T g11 = 2.0 * (f.b1a * f.b1a + f.b1b * f.b1b);
  const T g22 = 2.0 * (f.b2a * f.b2a + f.b2b * f.b2b);
  const T g12 = 2.0 * (f.b1a * f.b2a + f.b1b * f.b2b);
  const T trace = g11 + g22;
  const T cross = f.b1a * f.b2b - f.b1b * f.b2a;
  const T det = 4.0 * cross * cross;  // |B1|²|B2|² − (B1·B2)², = 1/A²
  const T root = simd::sqrt(simd::max(trace * trace - 4.0 * (1.0 - nu * nu) * det, T{}));
  const T constant_strain = 2.0 * q11_rho * (trace + root);
  const T ww = f.hx * f.hx * g11 + 2.0 * f.hx * f.hy * g12 + f.hy * f.hy * g22;
  const T c_m = hourglass_rho * trace;
  return simd::max(constant_strain + 2.0 * c_m * ww, 8.0 * c_m);
}

/// Factor (≥ 1) on the rotary inertia per unit mass of an S4R of frame f and corners p:
/// max(1, (2/3) max(|∇ξ|² |X_ξ|², |∇η|² |X_η|²) + 5 |X_h|² (|∇ξ|² + |∇η|²)), where
/// |∇ξ| |X_ξ| = 1 / sin θ on a parallelogram and X_h is the taper (see the file comment).
template <class T>
inline T shell_rotary_shape_factor(const QuadFrame<T>& f, const V3<T> p[4]) {
  const QuadNatural<T> n = quad_natural(f);
  const QuadEdges<T> e = quad_edges(f, p);
  // X_ξ = (d01 + d32)/4, X_η = (d03 + d12)/4.
  const T xi_x = 0.25 * (e.x[0] + e.x[2]), xi_y = 0.25 * (e.y[0] + e.y[2]);
  const T eta_x = 0.25 * (e.x[3] + e.x[1]), eta_y = 0.25 * (e.y[3] + e.y[1]);
  const T skew =
      simd::max(n.aa * (xi_x * xi_x + xi_y * xi_y), n.cc * (eta_x * eta_x + eta_y * eta_y));
  const T taper = (f.hx * f.hx + f.hy * f.hy) / 16.0 * (n.aa + n.cc);
  return simd::max((2.0 / 3.0) * skew + 5.0 * taper, T{1.0});
}

}  // namespace xpl::elements

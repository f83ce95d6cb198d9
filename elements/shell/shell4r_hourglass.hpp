#pragma once
/// \file Physical hourglass stabilisation of the bending and transverse-shear patterns of the
/// one-point S4R (the default form; `*SECTION CONTROLS, HOURGLASS=STIFFNESS` selects the
/// older Flanagan–Belytschko stiffness form instead, see shell4r.hpp).
///
/// The one-point element sees the constant part of every strain field. The stabilisation
/// adds the energy of the parts it misses, taken from the physics of the bilinear element
/// (in the spirit of Belytschko–Leviathan's physically stabilised shell) in the centre
/// Jacobian J = [X_ξ X_η], with a = ∇ξ and c = ∇η (the rows of J⁻¹):
///
/// - Bending: rotations θ give the rotation vector field β = (θ_y, −θ_x) with β = linear +
///   q ξη, q = Σ γ_I β_I / 4 (γ the hourglass vector, orthogonal to every linear field).
///   The curvature κ = sym ∇β has the linear part sym(q ⊗ (η a + ξ c)), whose energy,
///   integrated exactly, is ½ qᵀ K_b q with
///     K_b = D A/3 [ (1−ν)/2 (|a|² + |c|²) I + (1+ν)/2 (a aᵀ + c cᵀ) ],  D = E t³/12(1−ν²).
///   Linear rotation fields (constant curvature and twist) have q = 0: no hourglass energy.
/// - Transverse shear (assumed strain, as Bathe–Dvorkin's MITC4): the tangential shear of
///   each edge I→J,
///     s_IJ = w_J − w_I + ½ (β_I + β_J) · (x_J − x_I),
///   is exactly zero for any quadratic deflection with Kirchhoff rotations β = −∇w (the
///   trapezoidal rule integrates the linear ∇w along the edge exactly) and for rigid
///   motions. The covariant shear γ_ξ is linear in η between the edges η = ±1 and γ_η linear
///   in ξ between ξ = ±1. The element's centre shear is taken from them (this replaces the
///   one-point shear of the stiffness form), γ̄ = J⁻ᵀ ((s_01 + s_32)/4, (s_03 + s_12)/4),
///   and the linear parts g_ξ = (s_32 − s_01)/4 − γ̄·X_h, g_η = (s_12 − s_03)/4 − γ̄·X_h
///   (X_h = Σ Γ_I x_I / 4, the taper: a constant shear gives g = 0 on any quad) store
///     ½ κ_s G t A/3 (|a|² g_ξ² + |c|² g_η²).
///   A pure twist or constant curvature gives zero shear on any element, and everything is
///   a function of the edge shears, which neighbours share: two constraints per element in
///   the thin limit, so distorted meshes do not lock.
/// Both are kept as resultants in the corotational frame and advanced in rate form like the
/// stresses (stiffness form, elastic moduli). In-plane hourglass patterns keep the
/// Flanagan–Belytschko stiffness form of the older control in both forms.
/// Plastic sections (physical form, unless PLASTIC HOURGLASS=ELASTIC): the in-plane increments
/// are scaled by the section's membrane tangent ratio, the stored in-plane resultants relax with
/// the membrane return ratio and stay within SHELL_HOURGLASS_PLASTIC_BOUND σ_f t (Gauss-point
/// norm, hourglass_field_norm()), and the bending increments are scaled by the bending tangent
/// ratio, at least SHELL_HOURGLASS_TANGENT_FLOOR (shell4r.hpp). Everything the resultants take
/// or give back is hourglass energy (ALLAE), the part removed by a relaxation or the bound
/// included: the work is taken over the increment against the end resultants.
/// All functions are templates over the lane type (`Real` or `simd::Vec`).

#include "elements/shell/quad_shell_geometry.hpp"

namespace xpl::elements {

/// Local (x̂, ŷ) components of the four edges d01 = x1 − x0, d12, d32 = x2 − x3, d03.
template <class T>
struct QuadEdges {
  T x[4], y[4];
};

template <class T>
inline QuadEdges<T> quad_edges(const QuadFrame<T>& f, const V3<T> p[4]) {
  const V3<T> d[4] = {p[1] - p[0], p[2] - p[1], p[2] - p[3], p[3] - p[0]};
  QuadEdges<T> e;
  for (int k = 0; k < 4; ++k) {
    e.x[k] = dot(f.e1, d[k]);
    e.y[k] = dot(f.e2, d[k]);
  }
  return e;
}

/// |∇ξ|² and |∇η|², and ∇ξ, ∇η, from the one-point gradient operator.
template <class T>
struct QuadNatural {
  T ax, ay, cx, cy;  ///< a = ∇ξ, c = ∇η, 1/m
  T aa, cc;          ///< |a|², |c|²
};

template <class T>
inline QuadNatural<T> quad_natural(const QuadFrame<T>& f) {
  QuadNatural<T> n;
  n.ax = 2.0 * (f.b1b - f.b1a);
  n.ay = 2.0 * (f.b2b - f.b2a);
  n.cx = -2.0 * (f.b1a + f.b1b);
  n.cy = -2.0 * (f.b2a + f.b2b);
  n.aa = n.ax * n.ax + n.ay * n.ay;
  n.cc = n.cx * n.cx + n.cy * n.cy;
  return n;
}

/// Tangential shear rates of the four edges, s[k] for the edges of QuadEdges (01, 12, 32, 03),
/// s_IJ = w_J − w_I + ½ (β_I + β_J)·d_IJ with β·d = θy dx − θx dy, from the local nodal rates
/// w_I (normal velocity), θx_I, θy_I.
template <class T>
inline void edge_shear_rates(const QuadEdges<T>& e, const T w[4], const T thx[4], const T thy[4],
                             T s[4]) {
  constexpr int from[4] = {0, 1, 3, 0}, to[4] = {1, 2, 2, 3};
  for (int k = 0; k < 4; ++k) {
    const int i = from[k], j = to[k];
    s[k] = (w[j] - w[i]) + 0.5 * ((thy[i] + thy[j]) * e.x[k] - (thx[i] + thx[j]) * e.y[k]);
  }
}

/// The assumed-strain transverse shear of the element from its edge shears s: the centre
/// shear γ̄ = J⁻ᵀ (γ̄_ξ, γ̄_η), γ̄_ξ = (s01 + s32)/4, γ̄_η = (s03 + s12)/4 (exact for a
/// constant shear on any quad), and the linear parts g_ξ = (s32 − s01)/4 − γ̄·X_h,
/// g_η = (s12 − s03)/4 − γ̄·X_h (zero for a constant shear on any quad).
template <class T>
struct EdgeShear {
  T gxz, gyz;  ///< centre shear γ̄ (local axes)
  T g_xi, g_eta;
};

template <class T>
inline EdgeShear<T> edge_shear(const QuadFrame<T>& f, const QuadNatural<T>& n, const T s[4]) {
  EdgeShear<T> out;
  const T cxi = 0.25 * (s[0] + s[2]), ceta = 0.25 * (s[3] + s[1]);
  out.gxz = cxi * n.ax + ceta * n.cx;
  out.gyz = cxi * n.ay + ceta * n.cy;
  const T taper = 0.25 * (out.gxz * f.hx + out.gyz * f.hy);
  out.g_xi = 0.25 * (s[2] - s[0]) - taper;
  out.g_eta = 0.25 * (s[1] - s[3]) - taper;
  return out;
}

/// Nodal normal forces fz_I and β-forces (bx, by), pairing with β = (θy, −θx), of the
/// conjugates of the assumed-strain shear: the centre shear resultant (qx, qy) (per unit
/// length, acting on the area A) and the linear-part resultants Q_ξ, Q_η, on the element of
/// frame f, natural gradients n and edges e: the energy rate A q·γ̄ + Q_ξ g_ξ + Q_η g_η is
/// written as Σ C_k s_k and each edge shear is spread on its nodes.
template <class T>
inline void edge_shear_forces(const QuadFrame<T>& f, const QuadNatural<T>& n, const QuadEdges<T>& e,
                              T qx, T qy, T q_xi, T q_eta, T fz[4], T bx[4], T by[4]) {
  // ∂γ̄/∂γ̄_ξ = a, ∂γ̄/∂γ̄_η = c: the conjugate of γ̄_ξ is (A q − (Q_ξ + Q_η) X_h)·a.
  const T sum = q_xi + q_eta;
  const T vx = f.area * qx - 0.25 * sum * f.hx, vy = f.area * qy - 0.25 * sum * f.hy;
  const T p_xi = 0.25 * (vx * n.ax + vy * n.ay), p_eta = 0.25 * (vx * n.cx + vy * n.cy);
  const T c[4] = {p_xi - 0.25 * q_xi, p_eta + 0.25 * q_eta, p_xi + 0.25 * q_xi,
                  p_eta - 0.25 * q_eta};
  constexpr int from[4] = {0, 1, 3, 0}, to[4] = {1, 2, 2, 3};
  for (int a = 0; a < 4; ++a) fz[a] = bx[a] = by[a] = T{};
  for (int k = 0; k < 4; ++k) {
    const int i = from[k], j = to[k];
    fz[j] += c[k];
    fz[i] -= c[k];
    const T hx = 0.5 * c[k] * e.x[k], hy = 0.5 * c[k] * e.y[k];
    bx[i] += hx;
    by[i] += hy;
    bx[j] += hx;
    by[j] += hy;
  }
}

/// Bending hourglass stiffness K_b / (D A/3) applied to q: returns K q / (D A/3).
template <class T>
inline void bending_hourglass_apply(const QuadNatural<T>& n, T nu, T q1, T q2, T& k1, T& k2) {
  const T iso = 0.5 * (1.0 - nu) * (n.aa + n.cc);
  const T qa = n.ax * q1 + n.ay * q2, qc = n.cx * q1 + n.cy * q2;
  const T half = 0.5 * (1.0 + nu);
  k1 = iso * q1 + half * (n.ax * qa + n.cx * qc);
  k2 = iso * q2 + half * (n.ay * qa + n.cy * qc);
}

/// Largest von Mises norm, per unit width (N/m for forces, N for moments), of the linear
/// resultant field of a pattern at the four 2 × 2 Gauss points, from the generalised resultant
/// (r1, r2) conjugate to the pattern's amplitude h (q of the bending form): the field the fully
/// integrated element carries for the same energy, r = (k A/3) B h with B of
/// bending_hourglass_apply(), so k h = (3/A) B⁻¹ r, and the resultant amplitudes along ξ and η
/// are m_a = P sym(k h ⊗ a), m_c = P sym(k h ⊗ c), P the plane-stress law over its modulus
/// ([1 ν 0; ν 1 0; 0 0 1−ν] on xx, yy, xy). A Gauss point (±1/√3, ±1/√3) holds (±m_a ± m_c)/√3.
template <class T>
inline T hourglass_field_norm(const QuadNatural<T>& n, T nu, T area, T r1, T r2) {
  const T iso = 0.5 * (1.0 - nu) * (n.aa + n.cc), half = 0.5 * (1.0 + nu);
  const T b11 = iso + half * (n.ax * n.ax + n.cx * n.cx);
  const T b12 = half * (n.ax * n.ay + n.cx * n.cy);
  const T b22 = iso + half * (n.ay * n.ay + n.cy * n.cy);
  const T s = 3.0 / (area * (b11 * b22 - b12 * b12));
  const T g1 = s * (b22 * r1 - b12 * r2), g2 = s * (b11 * r2 - b12 * r1);
  // m_a ± m_c = P sym(g ⊗ (a ± c)).
  auto norm2 = [&](T dx, T dy) {
    const T kxx = g1 * dx, kyy = g2 * dy, kxy = 0.5 * (g1 * dy + g2 * dx);
    const T mxx = kxx + nu * kyy, myy = kyy + nu * kxx, mxy = (1.0 - nu) * kxy;
    return mxx * mxx - mxx * myy + myy * myy + 3.0 * (mxy * mxy);
  };
  const T plus = norm2(n.ax + n.cx, n.ay + n.cy), minus = norm2(n.ax - n.cx, n.ay - n.cy);
  return simd::sqrt(simd::max(plus, minus) * (1.0 / 3.0));
}

}  // namespace xpl::elements

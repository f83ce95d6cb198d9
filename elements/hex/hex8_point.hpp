#pragma once
/// \file Integration-point kinematics of the fully integrated hex (C3D8, hex8.cpp): the
/// Jacobian of the trilinear map at a Gauss point in mode space, its cofactor columns, and the
/// nodal-force modes of a stress there. Shared by the force pass and the stiffness product.

#include <cmath>

#include "elements/hex/hex8_geometry.hpp"
#include "elements/hex/hex8r_gather.hpp"
#include "elements/parallel/simd.hpp"
#include "elements/vec3.hpp"

namespace xpl::elements {

/// Natural coordinates of one 2×2×2 Gauss point (weight 1).
struct GaussPoint {
  Real xi, eta, zeta;
};

/// Gauss point q = i + 2j + 4k (ξ fastest), coordinates ±1/√3.
inline GaussPoint gauss_point(int q) {
  const Real g = 1.0 / std::sqrt(3.0);
  return {(q & 1) ? g : -g, (q & 2) ? g : -g, (q & 4) ? g : -g};
}

/// Columns ∂x/∂ξ, ∂x/∂η, ∂x/∂ζ at `p` of the field with modes `a` (x = Σ_k a_k m_k with the
/// monomials 1 ξ η ζ ξη ηζ ζξ ξηζ of hex8_geometry.hpp).
template <class T>
inline void jacobian_columns(const V3<T> a[8], const GaussPoint& p, V3<T> c[3]) {
  c[0] = a[1] + p.eta * a[4] + p.zeta * a[6] + (p.eta * p.zeta) * a[7];
  c[1] = a[2] + p.xi * a[4] + p.zeta * a[5] + (p.xi * p.zeta) * a[7];
  c[2] = a[3] + p.eta * a[5] + p.xi * a[6] + (p.xi * p.eta) * a[7];
}

/// Cofactor columns n_a of the Jacobian at a point (det J · J⁻ᵀ = [n_ξ n_η n_ζ]) and det J.
template <class T>
struct PointFrame {
  V3<T> n[3];
  T det;
};

template <class T>
inline PointFrame<T> point_frame(const V3<T> a[8], const GaussPoint& p) {
  V3<T> c[3];
  jacobian_columns(a, p, c);
  PointFrame<T> f;
  f.n[0] = cross(c[1], c[2]);
  f.n[1] = cross(c[2], c[0]);
  f.n[2] = cross(c[0], c[1]);
  f.det = dot(c[0], f.n[0]);
  return f;
}

/// Adds the force modes of the symmetric tensor `s` (11 22 33 12 13 23) at point `p` with frame
/// `f`: F_k += s Σ_a n_a ∂m_k/∂ξ_a (k = 1..7), i.e. ∫ s ∇N_I dV = ⅛ Σ_k Λ_kI F_k at one point.
template <class T>
inline void add_deviatoric_forces(const T s[6], const PointFrame<T>& f, const GaussPoint& p,
                                  V3<T> F[8]) {
  V3<T> u[3];
  for (int a = 0; a < 3; ++a) {
    const V3<T>& n = f.n[a];
    u[a] = {s[0] * n.x + s[3] * n.y + s[4] * n.z, s[3] * n.x + s[1] * n.y + s[5] * n.z,
            s[4] * n.x + s[5] * n.y + s[2] * n.z};
  }
  F[1] = F[1] + u[0];
  F[2] = F[2] + u[1];
  F[3] = F[3] + u[2];
  F[4] = F[4] + (p.eta * u[0] + p.xi * u[1]);
  F[5] = F[5] + (p.zeta * u[1] + p.eta * u[2]);
  F[6] = F[6] + (p.zeta * u[0] + p.xi * u[2]);
  F[7] = F[7] + ((p.eta * p.zeta) * u[0] + (p.xi * p.zeta) * u[1] + (p.xi * p.eta) * u[2]);
}

}  // namespace xpl::elements

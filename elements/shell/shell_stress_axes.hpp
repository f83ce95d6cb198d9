#pragma once
/// \file A shell's stress row from its local axes to the global axes, for output (the XDMF
/// copies of S, S_SNEG and S_SPOS): the frame the element computes its stresses in
/// (quad_frame of the current corner positions).

#include <algorithm>

#include "common/types.hpp"
#include "elements/shell/quad_shell_geometry.hpp"

namespace xpl::elements {

/// The stress row `local` (Abaqus order S11 S22 S33 S12 S13 S23, axes e1 e2 e3 of `f`) in
/// global axes (Abaqus order): σ_ij = Σ_ab E_ai σ_ab E_bj with E the rows e1, e2, e3.
inline void shell_stress_to_global(const QuadFrame<Real>& f, const Real* local, Real* global) {
  const Real E[3][3] = {
      {f.e1.x, f.e1.y, f.e1.z}, {f.e2.x, f.e2.y, f.e2.z}, {f.e3.x, f.e3.y, f.e3.z}};
  const Real L[3][3] = {{local[0], local[3], local[4]},
                        {local[3], local[1], local[5]},
                        {local[4], local[5], local[2]}};
  Real G[3][3] = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) G[i][j] += E[a][i] * L[a][b] * E[b][j];
  const Real out[6] = {G[0][0], G[1][1], G[2][2], G[0][1], G[0][2], G[1][2]};
  std::copy(out, out + 6, global);
}

/// The stress row `local` of the shell with corners `p` (current positions) in global axes.
inline void shell_stress_to_global(const V3<Real> p[4], const Real* local, Real* global) {
  shell_stress_to_global(quad_frame(p), local, global);
}

}  // namespace xpl::elements

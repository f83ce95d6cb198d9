#pragma once
/// \file The kinetic energy of one nodal update as two sums over its DOFs (docs/theory/energy.md,
/// "What ALLKE measures"). With v⁻ the velocity at the mirror time t_n − Δt(n+½)/2 and v⁺ = v(n+½),
/// the energy central differences conserve is ½ v⁻·M·v⁺ = ⅛ (v⁻ + v⁺)·M·(v⁻ + v⁺) − ⅛ (v⁺ −
/// v⁻)·M·(v⁺ − v⁻): the first part is ALLKE, ½ v(t_n)·M·v(t_n) with v(t_n) = ½(v⁻ + v⁺) = v(n−½) +
/// ½Δt(n−½) a(n), never negative; the second, ALLKD, is the O(Δt²) rest, −⅛ Δt(n+½)² a(n)·M·a(n).

#include "common/types.hpp"

namespace xpl {

/// Σ m (v⁻ + v⁺)² and Σ m (v⁺ − v⁻)² over DOFs (or the same with a body's mass matrix),
/// kg m²/s² (or their rotational counterparts, kg m² rad²/s²).
struct KineticSums {
  Real centred = 0.0;  ///< Σ m (v⁻ + v⁺)²: 8 ALLKE
  Real spread = 0.0;   ///< Σ m (v⁺ − v⁻)²: −8 times the ALLKD of the update

  /// Adds one DOF of mass (or inertia) `m` with velocities `before` = v⁻ and `after` = v⁺.
  void add(Real m, Real before, Real after) {
    centred += m * (before + after) * (before + after);
    spread += m * (after - before) * (after - before);
  }
  KineticSums& operator+=(const KineticSums& other) {
    centred += other.centred;
    spread += other.spread;
    return *this;
  }
  KineticSums& operator-=(const KineticSums& other) {
    centred -= other.centred;
    spread -= other.spread;
    return *this;
  }
};

}  // namespace xpl

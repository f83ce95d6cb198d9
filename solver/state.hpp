#pragma once
/// \file The evolving solution: nodal fields, element output fields, energies, clock.

#include <vector>

#include "common/types.hpp"

namespace xpl {

/// Whole-model energy balance (Abaqus names in comments), J.
struct Energies {
  Real kinetic = 0.0;  ///< ALLKE, ½ v(t_n)·M·v(t_n) ≥ 0 (solver/kinetic_sums.hpp)
  /// ALLKD, the rest of the kinetic energy central differences conserve: ½ v⁻·M·v(n+½) −
  /// ALLKE = −⅛ Δt(n+½)² a·M·a, less what the changes of the increment have moved in and
  /// out of that term (docs/theory/energy.md, "What ALLKE measures"); O(Δt²), ≤ 0 at a constant
  /// increment.
  Real kinetic_defect = 0.0;
  Real strain = 0.0;         ///< ALLSE, recoverable strain energy
  Real plastic = 0.0;        ///< ALLPD, plastic dissipation ∫σ_y dε̄ᵖ dV
  Real artificial = 0.0;     ///< ALLAE, hourglass energy
  Real viscous = 0.0;        ///< ALLVD, bulk-viscosity dissipation
  Real external_work = 0.0;  ///< ALLWK, work of loads and of reactions at prescribed DOFs
  Real friction = 0.0;       ///< ALLFD, frictional dissipation
  /// ALLPW, energy taken up by the contact penalties: minus the work the penalty forces have
  /// done on the nodes (the energy of the compressed springs, ≥ 0 while they are loaded, back
  /// to ~0 after a rebound). Abaqus reports the same quantity with the opposite sign as the
  /// work of the penalties; xpl keeps it positive so that it adds to ETOTAL like ALLIE.
  Real contact = 0.0;
  /// ALLIE = ALLSE + ALLPD + ALLAE.
  Real internal() const { return strain + plastic + artificial; }
  /// ETOTAL = ALLKE + ALLKD + ALLIE + ALLVD + ALLFD + ALLPW − ALLWK; constant for a correct,
  /// stable run.
  Real total() const {
    return kinetic + kinetic_defect + internal() + viscous + friction + contact - external_work;
  }
};

/// State of a run at the end of an increment (time t_n).
struct State {
  NodalVectors reference;      ///< reference coordinates X (n_nodes × 3), m
  NodalVectors position;       ///< current coordinates x_n (n_nodes × 3), m
  NodalVectors velocity;       ///< v_n at whole time steps (n_nodes × 3), m/s
  NodalVectors velocity_half;  ///< v_{n+1/2} (n_nodes × 3), m/s
  NodalVectors acceleration;   ///< a_n (n_nodes × 3), m/s^2
  NodalVectors reaction;       ///< reaction forces at prescribed DOFs (n_nodes × 3), N
  std::vector<Real> mass;      ///< lumped nodal mass (n_nodes), kg

  // Rotational DOFs: allocated (n_nodes × 3) only when the model has shells, else 0 rows.
  // Nodes that belong to no shell keep zeros.
  NodalVectors rotation;               ///< UR, rotation vector of each node (finite), rad
  NodalVectors angular_velocity;       ///< VR at whole steps, rad/s
  NodalVectors angular_velocity_half;  ///< ω_{n+1/2}, rad/s
  NodalVectors reaction_moment;        ///< RM at prescribed rotational DOFs, N·m
  std::vector<Real> rotary_inertia;    ///< lumped, scaled (see the shell element), kg·m^2

  /// Cauchy stress per element, filled before each field frame (n_elements × 6, row-major,
  /// Abaqus order S11 S22 S33 S12 S13 S23), Pa. Solids: global axes. Shells: the middle
  /// section point, in the shell's local axes (Abaqus default: local 1 = projection of the
  /// global x axis on the shell, local 2 = n × 1), S33 = 0, S13/S23 = transverse shear.
  std::vector<Real> stress;
  /// Shell section stresses at the bottom (SNEG) and top (SPOS) section points, same layout
  /// as `stress`; rows of non-shell elements are NaN. Empty unless the model has shells.
  std::vector<Real> stress_bottom, stress_top;
  /// Current shell thickness STH (n_elements), m; NaN for non-shell elements. Empty unless
  /// the model has shells.
  std::vector<Real> thickness;
  /// Current element volume, filled with `stress` (n_elements), m^3.
  std::vector<Real> volume;
  /// Accumulated hourglass resultants (n_elements × elements::HOURGLASS_STATE_WIDTH, each
  /// block's own layout: Hex8rBlock/Shell4rBlock::gather_hourglass_state; 0 for elements
  /// without), filled with `stress` on models with C3D8R or S4R elements, else empty: the
  /// state --import needs to continue a run with the same hourglass forces.
  std::vector<Real> hourglass_state;
  /// Equivalent plastic strain PEEQ (n_elements), -: 0 for elastic elements; shells: the
  /// largest of their section points. Filled before a frame that asks for it (plastic models).
  std::vector<Real> peeq;
  /// Shell PEEQ at the bottom (SNEG), middle and top (SPOS) section points (n_elements each),
  /// -: 0 for elastic shells, NaN for non-shell elements. Filled with `peeq` on models with
  /// plastic shells only, else empty.
  std::vector<Real> peeq_bottom, peeq_middle, peeq_top;

  // Contact output per node, filled before a frame that asks for it (zero away from contact).
  // The node's total contact force F (as slave and as face corner) split along its outward
  // normal n: CNORMF = (F·n) n, CSHEARF = F − CNORMF; CPRESS = −F·n / A and CSHEAR =
  // CSHEARF / A with A the tributary area (|F·n| / A on double-sided shell nodes).
  std::vector<Real> contact_pressure;  ///< CPRESS (n_nodes), Pa
  NodalVectors contact_shear;          ///< CSHEAR (n_nodes × 3), Pa
  std::vector<Real> contact_status;    ///< CSTATUS (n_nodes): 0 open, 1 slipping, 2 sticking
  NodalVectors contact_normal_force;   ///< CNORMF (n_nodes × 3), N
  NodalVectors contact_shear_force;    ///< CSHEARF (n_nodes × 3), N

  Energies energies;
  Real time = 0.0;       ///< total time t_n, s
  Real step_time = 0.0;  ///< time since the start of the current step, s
  Real dt = 0.0;         ///< the increment that led to t_n, s
  long increment = 0;    ///< total increment count
  int step = 0;          ///< zero-based step index

  /// Displacement u = x − X of node i, component c.
  Real displacement(Index i, int c) const { return position(i, c) - reference(i, c); }
};

}  // namespace xpl

#pragma once
/// \file The evolving solution: nodal fields, energies, clock.

#include <vector>

#include "common/types.hpp"

namespace xpl {

/// Whole-model energy balance (Abaqus names in comments), J.
struct Energies {
  Real kinetic = 0.0;  ///< ALLKE, ½ v(t_n)·M·v(t_n) ≥ 0 (solver/motion/kinetic_sums.hpp)
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

  // The output-only fields (stresses, PEEQ, contact output, ...) are not part of the
  // solution: the OutputDriver owns them (FrameFields, solver/output/frame_fields.hpp).

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

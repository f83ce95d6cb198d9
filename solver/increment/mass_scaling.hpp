#pragma once
/// \file `*FIXED MASS SCALING` (SPEC S4): the lumped masses (and the shells' rotary inertia) of
/// chosen elements scaled once, before the first increment, so that their stable increment rises.
///
/// FACTOR=f multiplies the element mass by f (the element increment rises by √f); DT=Δt with
/// TYPE=BELOW MIN brings every element whose stable increment Δt_e is below Δt up to it (factor
/// (Δt/Δt_e)²), TYPE=UNIFORM scales the whole set by the one factor that lifts its smallest Δt_e
/// to Δt. Δt_e is the element-by-element estimate the solver uses at rest (before the step's
/// scale factor and the safety factor; bulk viscosity b1 of the first step included; the global
/// estimate may still shorten the increment on meshes with few neighbours). The added mass is
/// part of the nodal mass from the first increment on: it moves with the nodes, so it is in
/// ALLKE and does no work of its own (ALLMW = 0).

#include <string>
#include <vector>

#include "solver/model/model.hpp"
#include "solver/motion/rigid_bodies.hpp"

namespace xpl {

/// What the scaling did, for the .msg and .sta files.
struct MassScalingReport {
  std::vector<std::string> messages;  ///< one per definition, then the total
  std::string summary;                ///< one line for the .sta file; empty without scaling
  Real added_mass = 0.0;              ///< kg
  /// Mass factor of each element (n_elements; empty without scaling): the element blocks take
  /// density × factor, so that the lumped mass, the wave speed of the stable-increment estimate
  /// and the bulk viscosity are those of the heavier element.
  std::vector<Real> factor;
};

/// The mass factors of the first step's `*FIXED MASS SCALING` definitions for the deformable
/// elements in the configuration `reference`, with their report.
MassScalingReport fixed_mass_scaling(const Model& model, const RigidBodies& rigid,
                                     const NodalVectors& reference);

}  // namespace xpl

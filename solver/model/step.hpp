#pragma once
/// \file A step of a Model (model.hpp): its time and increment controls, boundary
/// conditions, loads and amplitudes, contact in effect, output requests and mass scaling.

#include <optional>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "common/types.hpp"
#include "solver/model/contact_definitions.hpp"
#include "solver/model/mesh.hpp"

namespace xpl {

/// `*AMPLITUDE, NAME=, DEFINITION=TABULAR[, TIME=STEP TIME|TOTAL TIME]`: piecewise linear,
/// held constant before the first and after the last point.
struct Amplitude {
  std::string name;  ///< upper-case name
  std::vector<Real> time;
  std::vector<Real> value;
  bool total_time = false;  ///< false: abscissa is step time (the Abaqus default)
  SourceLocation where;
  /// Value at time t (step or total time, as `total_time` says).
  Real evaluate(Real t) const;
};

/// Whether a boundary condition prescribes displacement or velocity.
enum class BoundaryType { Displacement, Velocity };

/// One prescribed degree-of-freedom range on one node (sets are expanded by io).
/// DOFs use Abaqus numbering 1..6; 4..6 act on the rotations of shell nodes and are ignored
/// (with a .msg note) on nodes that have no rotational DOFs.
struct BoundaryCondition {
  Index node = NO_INDEX;
  int first_dof = 1;
  int last_dof = 1;
  Real value = 0.0;  ///< magnitude (displacement or velocity), times the amplitude
  BoundaryType type = BoundaryType::Displacement;
  Index amplitude = NO_INDEX;  ///< NO_INDEX: the step's default amplitude
  SourceLocation where;
};

/// `*CLOAD`: a concentrated force on one node and DOF (sets expanded by io).
struct ConcentratedLoad {
  Index node = NO_INDEX;
  int dof = 1;       ///< 1..3
  Real value = 0.0;  ///< N, times the amplitude
  Index amplitude = NO_INDEX;
  SourceLocation where;
};

/// A pressure on one element face (`*DLOAD` P / Pn, `*DSLOAD` P on an element-based
/// surface), following the current geometry. Positive pressure pushes against the face's
/// outward normal: into a solid; for a shell, `*DLOAD P` and SPOS push along −n, SNEG along +n.
struct PressureLoad {
  ElementFace face;
  Real value = 0.0;  ///< Pa, times the amplitude
  Index amplitude = NO_INDEX;
  SourceLocation where;
};

/// `*DLOAD` GRAV: a body force ρ·g·direction on the elements of a set (all elements when
/// `element_set` is NO_INDEX), N/kg times the amplitude.
struct GravityLoad {
  Index element_set = NO_INDEX;
  Real magnitude = 0.0;            ///< m/s^2
  Real direction[3] = {0, 0, -1};  ///< unit vector (normalised by io)
  Index amplitude = NO_INDEX;
  SourceLocation where;
};

/// `*OUTPUT, FIELD|HISTORY` with the `*NODE OUTPUT`, `*ELEMENT OUTPUT`, `*ENERGY OUTPUT`
/// requests that follow it.
struct OutputRequest {
  enum class Kind { Field, History };
  Kind kind = Kind::Field;
  /// Exactly one of these is positive. Defaults (neither given): field NUMBER INTERVAL=20,
  /// history NUMBER INTERVAL=200 (as Abaqus/Explicit).
  int number_interval = 0;
  Real time_interval = 0.0;
  /// Node variables, upper case: field U V A RF UR VR RM; history also components U1..RF3,
  /// UR1..RM3. As in Abaqus, U/V/RF on shell models also write UR/VR/RM.
  std::vector<std::string> node_variables;
  Index node_set = NO_INDEX;  ///< NO_INDEX: all nodes (field) / none (history)
  /// Element variables, upper case: S, EVOL, MISES, STH (shell thickness), ...
  std::vector<std::string> element_variables;
  Index element_set = NO_INDEX;
  /// Whole-model energies (history): ALLKE ALLSE ALLAE ALLIE ALLVD ALLWK ETOTAL, and with
  /// contact ALLFD (frictional dissipation) and ALLPW (work of contact penalties); `energy`
  /// with an empty list means all of them.
  bool energy = false;
  std::vector<std::string> energy_variables;
  /// Contact variables (`*CONTACT OUTPUT`, field), upper case: CSTRESS (contact pressure and
  /// shear stress), CSTATUS, CFORCE; over the whole contact domain.
  std::vector<std::string> contact_variables;
  SourceLocation where;
};

/// `*FIXED MASS SCALING, FACTOR=, DT=, TYPE=, ELSET=` (SPEC S4): the masses of the elements of a
/// set (all deformable elements without ELSET=) scaled once, at the start of the analysis (xpl
/// accepts it in the first step only), FACTOR first, then DT.
struct FixedMassScaling {
  /// How DT= scales: BelowMin brings every element whose stable increment is below DT up to it
  /// (factor (DT/Δt_e)²); Uniform scales the whole set by one factor so that its smallest
  /// element increment becomes DT (no scaling where it is already above).
  enum class Type { BelowMin, Uniform };
  Real factor = 1.0;       ///< FACTOR=, > 0 (1: none)
  std::optional<Real> dt;  ///< DT=, s: the element stable increment (before the scale factor)
  Type type = Type::BelowMin;
  Index element_set = NO_INDEX;  ///< NO_INDEX: every deformable element
  SourceLocation where;
};

/// How a step's increment follows the stable increment (`*DYNAMIC, EXPLICIT`); the increment
/// itself is chosen by solver/increment/increment_control.hpp.
struct IncrementControls {
  std::optional<Real> fixed;  ///< `*DYNAMIC, EXPLICIT, DIRECT USER CONTROL`: this increment, s
  /// Fourth value of the `*DYNAMIC, EXPLICIT` data line: the increment never exceeds it, s.
  std::optional<Real> max;
  Real scale_factor = 1.0;  ///< multiplies the stable increment (S2)
};

/// One `*STEP ... *END STEP` block with `*DYNAMIC, EXPLICIT`.
struct Step {
  std::string name;
  SourceLocation where;
  Real time_period = 0.0;       ///< s
  IncrementControls increment;  ///< scale factor, maximum or fixed increment
  Real bulk_linear = 0.06;      ///< `*BULK VISCOSITY` b1 (Abaqus default)
  Real bulk_quadratic = 1.2;    ///< `*BULK VISCOSITY` b2 (Abaqus default)
  bool ramp_amplitude = false;  ///< `*STEP, AMPLITUDE=RAMP`; default STEP for explicit
  /// Boundary conditions given in this step. Those of earlier steps stay active unless this
  /// step has `*BOUNDARY, OP=NEW` (then `boundaries_reset`). Later entries for the same
  /// node and DOF replace earlier ones.
  std::vector<BoundaryCondition> boundaries;
  bool boundaries_reset = false;
  std::vector<ConcentratedLoad> loads;  ///< same propagation rule as boundaries
  bool loads_reset = false;
  /// Pressures of `*DLOAD`/`*DSLOAD`, same propagation rule (a later entry for the same face
  /// replaces an earlier one; OP=NEW on either keyword clears all earlier pressures).
  std::vector<PressureLoad> pressures;
  bool pressures_reset = false;
  /// Gravity of `*DLOAD` GRAV lines, same propagation rule (keyed by element set).
  std::vector<GravityLoad> gravity;
  /// `*DLOAD, OP=NEW` in this step: gravity of earlier steps is removed (it also sets
  /// `pressures_reset`; `*DSLOAD, OP=NEW` sets only that).
  bool gravity_reset = false;
  /// General contact in effect from this step on, when the step has `*CONTACT`: complete, i.e.
  /// the definition of the latest earlier step with `*CONTACT` plus this step's options
  /// (`*CONTACT, OP=NEW`: this step's options only; no inclusions then means no general
  /// contact). Empty when the step has no `*CONTACT` (contact of an earlier step carries
  /// over, as Abaqus does).
  std::optional<GeneralContact> contact;
  std::vector<ContactPair> contact_pairs;  ///< `*CONTACT PAIR` given in this step
  /// `*DIAGNOSTICS` given in this step; those of earlier steps (or the model data) apply
  /// otherwise (Model::diagnostics_of).
  std::optional<Diagnostics> diagnostics;
  std::vector<OutputRequest> outputs;
  /// `*FIXED MASS SCALING` definitions (first step only), applied in this order.
  std::vector<FixedMassScaling> mass_scaling;
};

}  // namespace xpl

#pragma once
/// \file The properties of a Model (model.hpp): materials, section controls (hourglass)
/// and the solid and shell sections that give them to elements.

#include <optional>
#include <string>

#include "common/error.hpp"
#include "common/types.hpp"
#include "elements/material/plasticity.hpp"

namespace xpl {

/// Isotropic linear elastic material with density (consistent units, e.g. SI), optionally
/// J2-plastic with isotropic hardening (`*PLASTIC`, `*RATE DEPENDENT`).
struct Material {
  std::string name;    ///< upper-case name
  Real density = 0.0;  ///< mass density, kg/m^3
  Real young = 0.0;    ///< Young's modulus E, Pa
  Real poisson = 0.0;  ///< Poisson's ratio ν, -1 < ν < 0.5
  bool has_density = false;
  bool has_elastic = false;
  /// `*PLASTIC` (with `*RATE DEPENDENT` folded in); empty for an elastic material, which
  /// then does no plasticity work at all.
  std::optional<elements::Plasticity> plastic;
  SourceLocation plastic_where;  ///< the *PLASTIC line (when plastic)
  SourceLocation where;          ///< the *MATERIAL line
};

/// Hourglass control of reduced-integration elements (`*SECTION CONTROLS, HOURGLASS=`).
enum class HourglassType {
  Stiffness,       ///< Flanagan–Belytschko stiffness form
  Viscous,         ///< Flanagan–Belytschko viscous form
  RelaxStiffness,  ///< Abaqus' integral-viscoelastic form; xpl runs it as Stiffness (noted in .msg)
  /// The physical stabilisations, the default of both elements when HOURGLASS= is not given:
  /// S4R's of the bending and transverse-shear patterns (shell4r_hourglass.hpp), C3D8R's
  /// enhanced assumed-strain form (elements/hex/hex8r_enhanced.hpp).
  Enhanced,
};

/// `*SECTION CONTROLS, NAME=...`.
struct SectionControls {
  std::string name;
  HourglassType hourglass = HourglassType::Enhanced;
  /// Whether HOURGLASS= was given: C3D8R and S4R use their physical forms unless STIFFNESS,
  /// VISCOUS or RELAX STIFFNESS asks for an older one.
  bool hourglass_given = false;
  Real stiffness_scale = 1.0;  ///< multiplies the default hourglass stiffness coefficient
  Real viscous_scale = 1.0;    ///< multiplies the default hourglass viscosity coefficient
  /// `PLASTIC HOURGLASS=ELASTIC`: S4R's physical form keeps its hourglass resultants elastic
  /// in yielding sections (issue 21's form) instead of following the section's plastic state.
  bool plastic_hourglass_elastic = false;
  SourceLocation where;
};

/// `*SOLID SECTION, ELSET=, MATERIAL=[, CONTROLS=]`.
struct SolidSection {
  Index element_set = NO_INDEX;  ///< into Model::element_sets
  Index material = NO_INDEX;     ///< into Model::materials
  Index controls = NO_INDEX;     ///< into Model::section_controls, NO_INDEX = defaults
  SourceLocation where;
};

/// `*SHELL SECTION, ELSET=, MATERIAL=[, OFFSET=][, CONTROLS=]` with the data line
/// `thickness[, integration points]` (Simpson's rule through the thickness).
struct ShellSection {
  Index element_set = NO_INDEX;  ///< into Model::element_sets
  Index material = NO_INDEX;     ///< into Model::materials
  Index controls = NO_INDEX;     ///< into Model::section_controls, NO_INDEX = defaults
  Real thickness = 0.0;          ///< initial shell thickness, m (> 0)
  int integration_points = 5;    ///< through the thickness, odd, >= 1
  /// Position of the reference surface (the nodes) measured from the mid-surface, as a
  /// fraction of the thickness along the shell normal: OFFSET=SPOS is 0.5, SNEG is -0.5,
  /// MIDSURFACE (default) is 0.
  Real offset = 0.0;
  /// ROTARY INERTIA=EXACT: the physical rotary inertia t²/12 per unit mass, the element's
  /// stable increment then including its rotational (transverse-shear) mode; ISOTROPIC
  /// (default, false): scaled up where that mode would set the increment (shell4r.hpp).
  bool rotary_exact = false;
  SourceLocation where;
};

}  // namespace xpl

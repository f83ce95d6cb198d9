#pragma once
/// \file Units: xpl, like Abaqus, has none built in. It computes with the numbers of the deck,
/// which must be in one consistent system (force = mass × length / time²). What it does know
/// is how to *label* them: a deck may state its system in a comment that Abaqus ignores,
/// `** xpl: UNITS=MM-T-S` (an xpl extension; Abaqus has no keyword that states a unit system,
/// and its `*PHYSICAL CONSTANTS` sets constants, not units), and the result files then label
/// every field and history series in that system (MPa, mm, mJ). A deck that states nothing is
/// labelled SI, said to be assumed, unless its material data cannot be SI (a density of
/// 7.85e-9 is steel in t/mm³): its labels then name the dimension only ("[stress]"), never
/// a unit the numbers are not in.

#include <array>
#include <string>
#include <string_view>

#include "common/error.hpp"

namespace xpl {

/// A consistent system of units: the base units, the units derived from them, and one of
/// each base unit in SI (to test whether material data fit the system).
struct UnitSystem {
  std::string_view name;    ///< as a deck states it ("MM-T-S")
  std::string_view length;  ///< "mm"
  std::string_view mass;    ///< "t"
  std::string_view time;    ///< "s"
  std::string_view force;   ///< "N"
  std::string_view stress;  ///< "MPa"
  std::string_view energy;  ///< "mJ"
  double length_si;         ///< one length unit in m
  double mass_si;           ///< one mass unit in kg
  double time_si;           ///< one time unit in s
};

/// The systems a deck may state. The first is SI.
inline constexpr std::array<UnitSystem, 6> UNIT_SYSTEMS = {{
    {"SI", "m", "kg", "s", "N", "Pa", "J", 1.0, 1.0, 1.0},
    {"MM-T-S", "mm", "t", "s", "N", "MPa", "mJ", 1e-3, 1e3, 1.0},
    {"MM-KG-MS", "mm", "kg", "ms", "kN", "GPa", "J", 1e-3, 1.0, 1e-3},
    {"MM-G-MS", "mm", "g", "ms", "N", "MPa", "mJ", 1e-3, 1e-3, 1e-3},
    {"CGS", "cm", "g", "s", "dyn", "dyn/cm^2", "erg", 1e-2, 1e-3, 1.0},
    // Mass in lbf s²/in (a "slinch"), so that force is lbf and stress psi.
    {"IN-LBF-S", "in", "lbf s^2/in", "s", "lbf", "psi", "in lbf", 0.0254, 175.126835, 1.0},
}};

/// The system named `name` (case-insensitive), or nullptr.
const UnitSystem* find_unit_system(std::string_view name);

/// The names of UNIT_SYSTEMS, for messages: "SI, MM-T-S, ...".
std::string unit_system_names();

/// `si_unit` (an SI unit expression of the output tables: "m", "m/s^2", "N m", "Pa", "J",
/// "s", "rad", "" for none) in `system`: "m/s^2" → "mm/s^2", "Pa" → "MPa". Tokens other than
/// m, kg, s, N, Pa, J (rad) are kept.
std::string unit_in(std::string_view si_unit, const UnitSystem& system);

/// The dimension of `si_unit` without a unit: "Pa" → "[stress]", "m/s" → "[length]/[time]".
std::string dimension_of(std::string_view si_unit);

/// How the numbers of one model are labelled (Model::units).
struct ModelUnits {
  /// The system the deck states; nullptr when it states none.
  const UnitSystem* stated = nullptr;
  SourceLocation where;  ///< the statement (when stated)
  /// Not stated, and the material data do not fit SI: labels name dimensions only.
  bool dimensions_only = false;
  /// Why the labels are what they are, in a sentence for the .msg file and the .h5 (the
  /// systems the material data fit, when that matters).
  std::string explanation;

  /// The system whose labels are written: the stated one, else SI (assumed).
  const UnitSystem& labels() const { return stated != nullptr ? *stated : UNIT_SYSTEMS[0]; }
  /// The label of a quantity whose SI unit is `si_unit` (unit_in or dimension_of).
  std::string label(std::string_view si_unit) const;
  /// "MM-T-S", "SI (assumed)" or "unstated" (dimensions only).
  std::string system_name() const;
  /// "length mm, mass t, time s, force N, stress MPa, energy mJ" (with "SI assumed" or the
  /// dimension-only wording when not stated).
  std::string summary() const;
};

}  // namespace xpl

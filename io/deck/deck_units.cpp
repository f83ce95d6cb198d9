#include "io/deck/deck_units.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace xpl::io {

namespace {

constexpr const char* DIRECTIVE = "** xpl";  // the messages add the colon
/// Bounds of real material data in SI (settle_units).
constexpr double DENSITY_MIN = 0.1, DENSITY_MAX = 1e7;        // kg/m^3
constexpr double WAVE_SPEED_MIN = 0.1, WAVE_SPEED_MAX = 1e5;  // m/s

std::string located(const SourceLocation& where) {
  return where.file + ":" + std::to_string(where.line);
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

/// Whether material `m` (deck numbers) has SI density and wave speed in bounds when read in
/// `system`.
bool fits(const Material& m, const UnitSystem& system) {
  if (!m.has_density || !(m.density > 0.0)) return true;
  const double density = m.density * system.mass_si / std::pow(system.length_si, 3);
  if (!(density >= DENSITY_MIN && density <= DENSITY_MAX)) return false;
  if (!m.has_elastic || !(m.young > 0.0)) return true;
  const double speed = std::sqrt(m.young / m.density) * system.length_si / system.time_si;
  return speed >= WAVE_SPEED_MIN && speed <= WAVE_SPEED_MAX;
}

bool model_fits(const Model& model, const UnitSystem& system) {
  for (const Material& m : model.materials)
    if (!fits(m, system)) return false;
  return true;
}

/// "material STEEL: density 7.85e-09, wave speed sqrt(E/density) 5.17e+06" of the first
/// material that does not fit `system`.
std::string evidence(const Model& model, const UnitSystem& system) {
  for (const Material& m : model.materials) {
    if (fits(m, system)) continue;
    std::string text = "material " + m.name + ": density " + number(m.density);
    if (m.has_elastic && m.young > 0.0 && m.density > 0.0)
      text += ", wave speed sqrt(E/density) " + number(std::sqrt(m.young / m.density));
    return text;
  }
  return "";
}

/// "MM-T-S" or "MM-T-S or MM-G-MS": the systems the material data fit, "" for none.
std::string fitting_systems(const Model& model) {
  std::string text;
  for (const UnitSystem& s : UNIT_SYSTEMS)
    if (model_fits(model, s)) text += (text.empty() ? "" : " or ") + std::string(s.name);
  return text;
}

}  // namespace

void read_directives(const std::vector<DeckDirective>& directives, Model& model,
                     InputErrors& errors) {
  const std::string expected = "expected UNITS=system, one of " + unit_system_names();
  for (const DeckDirective& d : directives) {
    std::vector<std::string> fields;
    std::size_t start = 0;
    for (std::size_t i = 0; i <= d.text.size(); ++i) {
      if (i < d.text.size() && d.text[i] != ',') continue;
      fields.push_back(d.text.substr(start, i - start));
      start = i + 1;
    }
    for (const std::string& field : fields) {
      const DeckParameter p = parse_parameter(field);
      if (p.name.empty() && fields.size() > 1) continue;  // "UNITS=SI," ends with a comma
      if (p.name != "UNITS" || !p.has_value) {
        errors.add(d.where, DIRECTIVE,
                   "unknown setting '" + escape_control(field) +
                       "' (a comment that starts with 'xpl:' holds settings for xpl)",
                   expected);
        continue;
      }
      const UnitSystem* system = find_unit_system(p.value);
      if (system == nullptr) {
        errors.add(d.where, DIRECTIVE, "unknown unit system '" + escape_control(p.value) + "'",
                   expected + " (length-mass-time)");
      } else if (model.units.stated != nullptr && model.units.stated != system) {
        errors.add(d.where, DIRECTIVE,
                   "UNITS=" + std::string(system->name) + " after UNITS=" +
                       std::string(model.units.stated->name) + " at " + located(model.units.where),
                   "expected one unit system for the whole deck");
      } else if (model.units.stated == nullptr) {
        model.units.stated = system;
        model.units.where = d.where;
      }
    }
  }
}

void settle_units(Model& model) {
  ModelUnits& units = model.units;
  const std::string statement = "** xpl: UNITS=";
  if (units.stated != nullptr) {
    units.explanation = "units stated at " + located(units.where) + ": " + units.summary();
    if (!model_fits(model, *units.stated)) {
      const std::string others = fitting_systems(model);
      model.deck_messages.push_back(
          {true,
           located(units.where) + ": " + DIRECTIVE + ": UNITS=" + std::string(units.stated->name) +
               ", but the material data do not fit it (" + evidence(model, *units.stated) +
               (others.empty() ? "" : "; they fit " + others) + "): the results are labelled " +
               std::string(units.stated->name) + " as stated; check the deck's numbers"});
    }
    return;
  }
  if (model_fits(model, UNIT_SYSTEMS[0])) {
    units.explanation = units.summary() + "; state the system with '" + statement + "SYSTEM' (" +
                        unit_system_names() + ")";
    return;
  }
  units.dimensions_only = true;
  const std::string others = fitting_systems(model);
  units.explanation = units.summary();
  model.deck_messages.push_back(
      {true, "the deck does not state its units and its material data are not SI (" +
                 evidence(model, UNIT_SYSTEMS[0]) +
                 "): the results are labelled by dimension only ([length], [stress], ...)" +
                 (others.empty()
                      ? std::string("")
                      : "; the data fit " + others + ": add a comment line '" + statement +
                            others.substr(0, others.find(' ')) + "' to the deck to label them")});
}

}  // namespace xpl::io

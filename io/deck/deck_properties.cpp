/// \file Property keywords: *MATERIAL, *DENSITY, *ELASTIC, *SECTION CONTROLS, *AMPLITUDE,
/// *INITIAL CONDITIONS. Sections are in deck_sections.cpp.

#include "io/deck/deck_handlers.hpp"

namespace xpl::io {

void read_material(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"NAME"}});
  expect_no_data(deck, block);
  const std::optional<std::string> name = required_name(deck, keyword, "NAME");
  if (!name) return;
  if (deck.model.find_material(*name) != NO_INDEX) {
    error(deck, keyword.where, keyword, "material " + *name + " is defined twice",
          "expected each material name once");
    return;
  }
  Material material;
  material.name = *name;
  material.where = keyword.where;
  deck.model.materials.push_back(material);
  deck.material = static_cast<Index>(deck.model.materials.size() - 1);
}

void read_density(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {});
  if (deck.material == NO_INDEX) {
    error(deck, keyword.where, keyword, "no material to attach to",
          "expected *DENSITY right after *MATERIAL, NAME=...");
    return;
  }
  Material& material = deck.model.materials[static_cast<std::size_t>(deck.material)];
  if (material.has_density) {
    error(deck, keyword.where, keyword, "material " + material.name + " already has a density",
          "expected one *DENSITY per material");
    return;
  }
  if (block.data.size() != 1) {
    error(deck, keyword.where, keyword,
          "found " + std::to_string(block.data.size()) + " data lines",
          "expected one data line with the density");
    return;
  }
  const DeckDataLine& line = block.data.front();
  material.has_density = true;  // even if bad (reported here): no "has no density" follow-up
  check_field_count(deck, line, keyword, 1, "the density only (no temperature dependence)");
  const std::optional<Real> rho = real_field(deck, line, keyword, 0, "density");
  if (!rho) return;
  if (*rho <= 0.0) {
    error(deck, line.where(), keyword, "density " + number_text(*rho) + " is not positive",
          "expected a density > 0");
    return;
  }
  material.density = *rho;
}

void read_elastic(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"TYPE"}});
  const std::string type = optional_name(keyword, "TYPE");
  if (!type.empty() && type != "ISOTROPIC") {
    error(deck, keyword.where, keyword, "elastic type " + type + " is not supported yet",
          "supported: TYPE=ISOTROPIC");
    if (deck.material != NO_INDEX)  // no "has no elastic data" follow-up
      deck.model.materials[static_cast<std::size_t>(deck.material)].has_elastic = true;
    return;
  }
  if (deck.material == NO_INDEX) {
    error(deck, keyword.where, keyword, "no material to attach to",
          "expected *ELASTIC right after *MATERIAL, NAME=...");
    return;
  }
  Material& material = deck.model.materials[static_cast<std::size_t>(deck.material)];
  if (material.has_elastic) {
    error(deck, keyword.where, keyword, "material " + material.name + " already has elastic data",
          "expected one *ELASTIC per material");
    return;
  }
  if (block.data.size() != 1) {
    error(deck, keyword.where, keyword,
          "found " + std::to_string(block.data.size()) + " data lines",
          "expected one data line: E, nu");
    return;
  }
  const DeckDataLine& line = block.data.front();
  material.has_elastic = true;  // even if bad (reported here): no follow-up error
  check_field_count(deck, line, keyword, 2, "E, nu (no temperature dependence)");
  const std::optional<Real> young = real_field(deck, line, keyword, 0, "Young's modulus");
  const std::optional<Real> poisson = real_field(deck, line, keyword, 1, "Poisson's ratio");
  if (!young || !poisson) return;
  bool ok = true;
  if (*young <= 0.0) {
    error(deck, line.where(), keyword,
          "Young's modulus " + number_text(*young) + " is not positive", "expected E > 0");
    ok = false;
  }
  if (!(*poisson > -1.0 && *poisson < 0.5)) {
    error(deck, line.where(), keyword,
          "Poisson's ratio " + number_text(*poisson) + " is out of range",
          "expected -1 < nu < 0.5");
    ok = false;
  }
  if (!ok) return;
  material.young = *young;
  material.poisson = *poisson;
}

void read_section_controls(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"NAME"}, {"HOURGLASS"}, {"PLASTIC HOURGLASS"}});
  const std::optional<std::string> name = required_name(deck, keyword, "NAME");
  SectionControls controls;
  const std::string hourglass = optional_name(keyword, "HOURGLASS");
  // Without HOURGLASS= the controls keep the physical default (HourglassType::Enhanced).
  if (hourglass == "STIFFNESS") {
    controls.hourglass = HourglassType::Stiffness;
  } else if (hourglass == "VISCOUS") {
    controls.hourglass = HourglassType::Viscous;
  } else if (hourglass == "RELAX STIFFNESS") {
    controls.hourglass = HourglassType::RelaxStiffness;
  } else if (hourglass == "ENHANCED") {
    controls.hourglass = HourglassType::Enhanced;
  } else if (!hourglass.empty()) {
    error(deck, keyword.where, keyword, "hourglass control " + hourglass + " is not supported",
          "expected HOURGLASS=ENHANCED, STIFFNESS, VISCOUS or RELAX STIFFNESS");
    return;
  }
  controls.hourglass_given = !hourglass.empty();
  // S4R's physical form on a plastic material: TANGENT (the default) or ELASTIC.
  const std::string plastic = optional_name(keyword, "PLASTIC HOURGLASS");
  if (plastic == "ELASTIC") {
    controls.plastic_hourglass_elastic = true;
  } else if (!plastic.empty() && plastic != "TANGENT") {
    error(deck, keyword.where, keyword,
          "plastic hourglass control " + plastic + " is not supported",
          "expected PLASTIC HOURGLASS=TANGENT or ELASTIC");
    // Kept with the default, so that its sections do not report them undefined as well.
  }
  // Abaqus/Explicit puts several scale factors on the data line. The first scales the
  // hourglass resistance of the displacement dofs, whichever form (stiffness or viscous) is
  // active, so it goes to both scales. The others (rotational and out-of-plane hourglass,
  // bulk viscosity factors, ...) concern dofs or options xpl does not have: they are checked
  // to be numbers and otherwise ignored.
  if (block.data.size() > 1)
    error(deck, block.data[1].where(), keyword, "unexpected second data line",
          "expected at most one data line of scale factors");
  if (!block.data.empty()) {
    const DeckDataLine& line = block.data.front();
    const std::optional<Real> scale =
        real_field(deck, line, keyword, 0, "hourglass scale factor", 1.0);
    for (std::size_t i = 1; i < line.fields.size(); ++i)
      real_field(deck, line, keyword, i, "scale factor " + std::to_string(i + 1), 1.0);
    if (scale && *scale <= 0.0) {
      error(deck, line.where(), keyword,
            "hourglass scale factor " + number_text(*scale) + " is not positive",
            "expected a factor > 0");
    } else if (scale) {
      controls.stiffness_scale = *scale;
      controls.viscous_scale = *scale;
    }
  }
  if (!name) return;
  for (const SectionControls& other : deck.model.section_controls) {
    if (other.name == *name) {
      error(deck, keyword.where, keyword, "section controls " + *name + " are defined twice",
            "expected each name once");
      return;
    }
  }
  controls.name = *name;
  controls.where = keyword.where;
  deck.model.section_controls.push_back(controls);
}

void read_amplitude(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"NAME"}, {"DEFINITION"}, {"TIME"}});
  const std::optional<std::string> name = required_name(deck, keyword, "NAME");
  const std::string definition = optional_name(keyword, "DEFINITION");
  if (!definition.empty() && definition != "TABULAR") {
    error(deck, keyword.where, keyword,
          "amplitude definition " + definition + " is not supported yet",
          "supported: DEFINITION=TABULAR");
    return;
  }
  Amplitude amplitude;
  const std::string time = optional_name(keyword, "TIME");
  if (time == "TOTAL TIME") {
    amplitude.total_time = true;
  } else if (!time.empty() && time != "STEP TIME") {
    error(deck, keyword.where, keyword, "bad TIME=" + time,
          "expected TIME=STEP TIME or TOTAL TIME");
    return;
  }
  bool ok = true;
  for (const DeckDataLine& line : block.data) {
    if (line.fields.size() % 2 != 0) {
      error(deck, line.where(), keyword,
            "odd number of values (" + std::to_string(line.fields.size()) + ")",
            "expected pairs: time, amplitude, time, amplitude, ...");
      ok = false;
      continue;
    }
    for (std::size_t i = 0; i + 1 < line.fields.size(); i += 2) {
      const std::optional<Real> t = real_field(deck, line, keyword, i, "time");
      const std::optional<Real> a = real_field(deck, line, keyword, i + 1, "amplitude value");
      if (!t || !a) {
        ok = false;
        continue;
      }
      if (!amplitude.time.empty() && *t < amplitude.time.back()) {
        error(deck, line.where(), keyword,
              "time " + number_text(*t) + " is before the previous " +
                  number_text(amplitude.time.back()),
              "expected times that do not decrease");
        ok = false;
      }
      amplitude.time.push_back(*t);
      amplitude.value.push_back(*a);
    }
  }
  if (ok && amplitude.time.empty()) {
    error(deck, keyword.where, keyword, "no data points",
          "expected data lines t1, a1, t2, a2, ...");
    return;
  }
  if (!name) return;
  if (deck.model.find_amplitude(*name) != NO_INDEX) {
    error(deck, keyword.where, keyword, "amplitude " + *name + " is defined twice",
          "expected each amplitude name once");
    return;
  }
  amplitude.name = *name;
  amplitude.where = keyword.where;
  deck.model.amplitudes.push_back(std::move(amplitude));
}

namespace {

/// `TYPE=ROTATING VELOCITY`: "node or set, ω, a_x, a_y, a_z" and a second line
/// "b_x, b_y, b_z" (Abaqus' two-line form), or all eight values on one line.
void read_rotating_velocity(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  const char* expected =
      "expected node or node set, angular velocity, x, y, z of axis point a, then a line "
      "x, y, z of axis point b (or all eight values on one line)";
  for (std::size_t i = 0; i < block.data.size(); ++i) {
    const DeckDataLine line = block.data[i];
    std::optional<DeckDataLine> second;
    if (line.fields.size() == 5 && i + 1 < block.data.size() &&
        block.data[i + 1].fields.size() == 3) {
      second = block.data[++i];
    } else if (line.fields.size() != 8) {
      error(deck, line.where(), keyword,
            "found " + std::to_string(line.fields.size()) + " values" +
                (line.fields.size() == 5 ? " and no line with point b" : ""),
            expected);
      continue;
    }
    PendingVelocity pending;
    pending.rotating = true;
    bool ok = true;
    const std::optional<Real> omega = real_field(deck, line, keyword, 1, "angular velocity");
    ok = ok && omega.has_value();
    const char* names[3] = {"x", "y", "z"};
    for (int c = 0; c < 3; ++c) {
      const std::optional<Real> a =
          real_field(deck, line, keyword, 2 + c, std::string("axis point a ") + names[c]);
      const std::optional<Real> b =
          second ? real_field(deck, *second, keyword, c, std::string("axis point b ") + names[c])
                 : real_field(deck, line, keyword, 5 + c, std::string("axis point b ") + names[c]);
      if (!a || !b) {
        ok = false;
        continue;
      }
      pending.a[c] = *a;
      pending.b[c] = *b;
    }
    if (!ok) continue;
    if (pending.a == pending.b) {
      error(deck, (second ? *second : line).where(), keyword,
            "axis points a and b coincide, so there is no axis",
            "expected two different points on the axis of rotation");
      continue;
    }
    pending.omega = *omega;
    pending.target = reference(line, keyword, 0);
    deck.velocities.push_back(pending);
  }
}

}  // namespace

void read_initial_conditions(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"TYPE"}});
  const std::optional<std::string> type = required_name(deck, keyword, "TYPE");
  if (!type) return;
  if (*type == "ROTATING VELOCITY") {
    read_rotating_velocity(deck, block);
    return;
  }
  if (*type != "VELOCITY") {
    error(deck, keyword.where, keyword, "initial condition type " + *type + " is not supported yet",
          "supported: TYPE=VELOCITY, TYPE=ROTATING VELOCITY");
    return;
  }
  for (const DeckDataLine& line : block.data) {
    check_field_count(deck, line, keyword, 3, "node or node set, dof, velocity");
    const std::optional<long long> dof = integer_field(deck, line, keyword, 1, "dof");
    const std::optional<Real> value = real_field(deck, line, keyword, 2, "velocity");
    if (!dof || !value) continue;
    if (*dof < 1 || *dof > 6) {
      error(deck, line.where(), keyword, "dof " + std::to_string(*dof) + " is out of range",
            "expected dof 1, 2 or 3 (translation, m/s) or 4, 5 or 6 (rotation of a shell node, "
            "rad/s)");
      continue;
    }
    PendingVelocity pending;
    pending.target = reference(line, keyword, 0);
    pending.dof = static_cast<int>(*dof);
    pending.value = *value;
    deck.velocities.push_back(pending);
  }
}

}  // namespace xpl::io

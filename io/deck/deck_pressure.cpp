/// \file Distributed loads: *DLOAD (element or element set, P on shells, P1..P6 on solid faces;
/// GRAV on an element set or the whole model) and *DSLOAD (P on an element-based surface),
/// resolved into one PressureLoad per face and one GravityLoad per GRAV line.

#include <cmath>

#include "io/deck/deck_handlers.hpp"
#include "io/deck/deck_numbers.hpp"

namespace xpl::io {

namespace {

constexpr const char* DLOAD_TYPES =
    "supported: P on S4R elements (face SPOS), P1..P6 on C3D8R elements (faces S1..S6), GRAV "
    "(gravity)";

constexpr const char* GRAV_LINE = "element set or blank, GRAV, magnitude, dx, dy, dz";

/// Face of a *DLOAD load type: 0..5 for P1..P6, -1 for P; nothing for other types.
std::optional<int> dload_face(const std::string& type) {
  if (type == "P") return -1;
  if (type.size() == 2 && type[0] == 'P' && type[1] >= '1' && type[1] <= '6') return type[1] - '1';
  return std::nullopt;
}

}  // namespace

void read_dload(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"AMPLITUDE"}, {"OP"}});
  Step& step = deck.model.steps.back();
  bool reset = false;  // OP=NEW on *DLOAD removes earlier pressures and gravity
  if (!read_load_op(deck, keyword, reset)) return;
  if (reset) step.pressures_reset = step.gravity_reset = true;
  const std::string amplitude = optional_name(keyword, "AMPLITUDE");
  for (const DeckDataLine& line : block.data) {
    if (line.fields.size() < 2 || line.fields[1].empty()) {
      error(deck, line.where(), keyword, "missing load type",
            "expected element or element set, load type, magnitude");
      continue;
    }
    const std::string type = normalize_name(line.fields[1]);
    if (type == "GRAV") {
      read_gravity(deck, line, keyword, amplitude);
      continue;
    }
    const std::optional<int> face = dload_face(type);
    if (!face) {  // before the field count: GRAV and BX have other data lines
      error(deck, line.where(), keyword, "load type " + type + " is not supported yet",
            DLOAD_TYPES);
      continue;
    }
    check_field_count(deck, line, keyword, 3, "element or element set, load type, magnitude");
    const std::optional<Real> magnitude = real_field(deck, line, keyword, 2, "magnitude");
    if (!magnitude) continue;
    PendingPressure pending;
    pending.step = static_cast<Index>(deck.model.steps.size() - 1);
    pending.target = reference(line, keyword, 0);
    pending.solid_face = *face;
    pending.load_type = type;
    pending.load.value = *magnitude;
    pending.load.where = line.where();
    pending.amplitude = amplitude;
    deck.pressures.push_back(std::move(pending));
  }
}

void read_dsload(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"AMPLITUDE"}, {"OP"}});
  if (!read_load_op(deck, keyword, deck.model.steps.back().pressures_reset)) return;
  const std::string amplitude = optional_name(keyword, "AMPLITUDE");
  for (const DeckDataLine& line : block.data) {
    if (line.fields.empty() || line.fields[0].empty()) {
      error(deck, line.where(), keyword, "missing surface name", "expected surface, P, magnitude");
      continue;
    }
    const std::string type = line.fields.size() > 1 ? normalize_name(line.fields[1]) : "";
    if (type.empty()) {
      error(deck, line.where(), keyword, "missing load type", "expected surface, P, magnitude");
      continue;
    }
    if (type != "P") {
      error(deck, line.where(), keyword, "load type " + type + " is not supported yet",
            "supported: P (pressure on an element-based surface)");
      continue;
    }
    check_field_count(deck, line, keyword, 3, "surface, P, magnitude");
    const std::optional<Real> magnitude = real_field(deck, line, keyword, 2, "magnitude");
    if (!magnitude) continue;
    PendingPressure pending;
    pending.step = static_cast<Index>(deck.model.steps.size() - 1);
    pending.target = {normalize_name(line.fields[0]), line.where(), keyword.label()};
    pending.on_surface = true;
    pending.load_type = type;
    pending.load.value = *magnitude;
    pending.load.where = line.where();
    pending.amplitude = amplitude;
    deck.pressures.push_back(std::move(pending));
  }
}

void resolve_pressures(DeckState& deck) {
  for (const PendingPressure& pending : deck.pressures) {
    Step& step = deck.model.steps[static_cast<std::size_t>(pending.step)];
    const DeckReference& target = pending.target;
    PressureLoad load = pending.load;
    load.amplitude = resolve_amplitude(deck, pending.amplitude, load.where, target.keyword);
    if (pending.on_surface) {
      const Index s = deck.model.find_surface(target.token);
      if (s == NO_INDEX) {
        deck.errors.add(target.where, target.keyword, "undefined surface " + target.token,
                        "expected *SURFACE, NAME=" + target.token);
        continue;
      }
      const Surface& surface = deck.model.surfaces[static_cast<std::size_t>(s)];
      if (surface.type != Surface::Type::Element) {
        deck.errors.add(
            target.where, target.keyword, "surface " + target.token + " is node-based",
            "expected an element-based surface (*SURFACE, TYPE=ELEMENT) under a pressure");
        continue;
      }
      for (const ElementFace& face : surface.faces) {
        load.face = face;
        step.pressures.push_back(load);
      }
      continue;
    }
    bool reported = false;  // one mismatch per data line, not one per element of a set
    for (Index e : resolve_elements(deck, target)) {
      const bool shell = is_shell(deck.model.element_types[static_cast<std::size_t>(e)]);
      if (shell == (pending.solid_face < 0)) {
        load.face = {e, shell ? SHELL_FACE_POS : static_cast<std::uint8_t>(pending.solid_face)};
        step.pressures.push_back(load);
      } else if (!reported) {
        reported = true;
        deck.errors.add(
            target.where, target.keyword,
            "load type " + pending.load_type + " does not fit " + element_text(deck, e, target),
            shell ? "expected P on S4R shell elements"
                  : "expected P1..P6 on C3D8R solid elements (faces S1..S6)");
      }
    }
  }
  // The model keeps these for the whole run: no growth capacity (a quarter of the array on a
  // plate with a pressure on every face, issue 38).
  for (Step& step : deck.model.steps) step.pressures.shrink_to_fit();
}

void read_gravity(DeckState& deck, const DeckDataLine& line, const DeckKeyword& keyword,
                  const std::string& amplitude) {
  check_field_count(deck, line, keyword, 6, GRAV_LINE);
  const std::string target = line.fields.empty() ? "" : std::string(line.fields[0]);
  if (looks_numeric(target)) {
    error(deck, line.where(), keyword, "GRAV on a single element (" + target + ") is not supported",
          std::string("expected an element set name, or the first field blank for the whole "
                      "model: ") +
              GRAV_LINE);
    return;
  }
  const std::optional<Real> magnitude = real_field(deck, line, keyword, 2, "gravity magnitude");
  Real direction[3] = {0.0, 0.0, 0.0};
  bool ok = magnitude.has_value();
  for (std::size_t c = 0; c < 3; ++c) {
    const std::optional<Real> value =
        real_field(deck, line, keyword, 3 + c, std::string("direction d") + "xyz"[c], 0.0);
    ok = ok && value.has_value();
    if (value) direction[c] = *value;
  }
  if (!ok) return;
  const Real length = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] +
                                direction[2] * direction[2]);
  if (!(length > 0.0) || !std::isfinite(length)) {
    error(deck, line.where(), keyword,
          "gravity direction " + number_text(direction[0]) + ", " + number_text(direction[1]) +
              ", " + number_text(direction[2]) + " has no length",
          "expected a nonzero direction dx, dy, dz (it is normalised)");
    return;
  }
  PendingGravity pending;
  pending.step = static_cast<Index>(deck.model.steps.size() - 1);
  pending.element_set = normalize_name(target);
  pending.load.magnitude = *magnitude;
  for (int c = 0; c < 3; ++c) pending.load.direction[c] = direction[c] / length;
  pending.load.where = line.where();
  pending.amplitude = amplitude;
  deck.gravity.push_back(std::move(pending));
}

void resolve_gravity(DeckState& deck) {
  for (const PendingGravity& pending : deck.gravity) {
    GravityLoad load = pending.load;
    load.amplitude = resolve_amplitude(deck, pending.amplitude, load.where, "*DLOAD");
    if (!pending.element_set.empty()) {
      load.element_set = deck.model.find_element_set(pending.element_set);
      if (load.element_set == NO_INDEX) {
        deck.errors.add(load.where, "*DLOAD", "undefined element set " + pending.element_set,
                        "expected *ELSET, ELSET=" + pending.element_set +
                            ", or the first field blank for the whole model");
        continue;
      }
    }
    deck.model.steps[static_cast<std::size_t>(pending.step)].gravity.push_back(load);
  }
}

}  // namespace xpl::io

/// \file Parts, assemblies and instances as Abaqus/CAE writes them: `*PART` … `*END PART` keeps
/// its part-level blocks; each `*INSTANCE` of the part reads them in its own scope (ids keyed
/// per instance, set and surface names qualified `INSTANCE.NAME`, nodes placed by the
/// instance's translation and rotation). Materials given in a part are read once; history data
/// cannot stand in a part. Also `*RESTART`, which CAE writes into every step.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "io/deck/deck_assembly.hpp"
#include "io/deck/deck_handlers.hpp"
#include "io/deck/deck_numbers.hpp"

namespace xpl::io {

namespace {

/// Keywords that open or close a structure: inside a part they mean the part was not closed.
bool is_structure(std::string_view name) {
  return name == "PART" || name == "ASSEMBLY" || name == "END ASSEMBLY" || name == "INSTANCE" ||
         name == "END INSTANCE" || name == "STEP";
}

void mark_assembly_model(DeckState& deck) {
  if (deck.assembly_model) return;
  deck.assembly_model = true;
  // Nodes and elements read before the first *PART are at the model level (scope 0).
  deck.node_scopes.assign(static_cast<std::size_t>(deck.model.node_count()), 0);
  deck.element_scopes.assign(static_cast<std::size_t>(deck.model.element_count()), 0);
}

/// Index of the part named `name`, or NO_INDEX.
Index find_part(const DeckState& deck, const std::string& name) {
  for (std::size_t p = 0; p < deck.parts.size(); ++p)
    if (deck.parts[p].name == name) return static_cast<Index>(p);
  return NO_INDEX;
}

/// R of a rotation by `degrees` about the unit vector u (right-handed), row major.
std::array<Real, 9> rotation_matrix(const std::array<Real, 3>& u, Real degrees) {
  const Real angle = degrees * std::numbers::pi / 180.0;
  const Real c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
  return {t * u[0] * u[0] + c,        t * u[0] * u[1] - s * u[2], t * u[0] * u[2] + s * u[1],
          t * u[0] * u[1] + s * u[2], t * u[1] * u[1] + c,        t * u[1] * u[2] - s * u[0],
          t * u[0] * u[2] - s * u[1], t * u[1] * u[2] + s * u[0], t * u[2] * u[2] + c};
}

/// The translation (first line) and rotation (second line) of an *INSTANCE; false if bad
/// (reported).
bool read_placement(DeckState& deck, const DeckBlock& block, DeckInstance& instance) {
  const DeckKeyword& keyword = block.keyword;
  if (block.data.size() > 2) {
    error(deck, block.data[2].where(), keyword, "more than two data lines",
          "expected a translation line (x, y, z) and a rotation line (a_x, a_y, a_z, b_x, b_y, "
          "b_z, angle in degrees)");
    return false;
  }
  bool ok = true;
  if (!block.data.empty()) {
    const DeckDataLine& line = block.data[0];
    ok = check_field_count(deck, line, keyword, 3, "the translation x, y, z") && ok;
    for (std::size_t c = 0; c < 3; ++c) {
      const std::optional<Real> value =
          real_field(deck, line, keyword, c, std::string("translation ") + "xyz"[c], 0.0);
      ok = ok && value.has_value();
      if (value) instance.translation[c] = *value;
    }
  }
  if (block.data.size() < 2) return ok;
  const DeckDataLine& line = block.data[1];
  ok = check_field_count(deck, line, keyword, 7,
                         "a_x, a_y, a_z, b_x, b_y, b_z, angle (rotation about the axis a-b, "
                         "degrees)") &&
       ok;
  Real values[7] = {};
  const char* names[7] = {"a_x", "a_y", "a_z", "b_x", "b_y", "b_z", "angle"};
  for (std::size_t k = 0; k < 7; ++k) {
    const std::optional<Real> value = real_field(deck, line, keyword, k, names[k], 0.0);
    ok = ok && value.has_value();
    if (value) values[k] = *value;
  }
  if (!ok) return false;
  for (std::size_t c = 0; c < 3; ++c) {
    instance.axis_a[c] = values[c];
    instance.axis_b[c] = values[c + 3];
  }
  instance.angle = values[6];
  if (instance.angle == 0.0) return true;  // a blank rotation line: no rotation
  std::array<Real, 3> axis{};
  Real length = 0.0;
  for (std::size_t c = 0; c < 3; ++c) {
    axis[c] = instance.axis_b[c] - instance.axis_a[c];
    length += axis[c] * axis[c];
  }
  length = std::sqrt(length);
  if (!(length > 0.0)) {
    error(deck, line.where(), keyword, "points a and b of the rotation axis coincide",
          "expected two different points a, b on the axis, then the angle in degrees");
    return false;
  }
  for (Real& c : axis) c /= length;
  instance.rotated = true;
  instance.rotation = rotation_matrix(axis, instance.angle);
  return true;
}

/// Reads the blocks of `part` for the instance just opened. The second and later instances of a
/// part repeat its errors and notes word for word: only new ones are kept (one per cause).
void read_part_blocks(DeckState& deck, PartDefinition& part) {
  const bool repeat = part.instances > 0;
  ++part.instances;
  const InputErrors before = repeat ? deck.errors : InputErrors();
  const std::size_t notes_before = deck.model.deck_messages.size();
  for (const DeckBlock* block : part.blocks) read_block(deck, *block);
  if (!repeat) return;
  InputErrors kept = before;
  for (std::size_t i = before.size(); i < deck.errors.size(); ++i) {
    const std::string& message = deck.errors.messages()[i];
    const std::vector<std::string>& old = before.messages();
    if (std::find(old.begin(), old.end(), message) == old.end()) kept.add_plain(message);
  }
  deck.errors = kept;
  std::vector<DeckMessage>& notes = deck.model.deck_messages;
  for (std::size_t i = notes.size(); i-- > notes_before;) {
    const auto same = [&](const DeckMessage& m) { return m.text == notes[i].text; };
    if (std::any_of(notes.begin(), notes.begin() + static_cast<std::ptrdiff_t>(notes_before), same))
      notes.erase(notes.begin() + static_cast<std::ptrdiff_t>(i));
  }
}

}  // namespace

std::string DeckState::id_text(ExternalId key) const {
  if (instances.empty()) return std::to_string(key);
  const auto in_scope = static_cast<std::size_t>(key >> SCOPE_SHIFT);
  std::string text = std::to_string(key & MAX_SCOPED_ID);
  if (in_scope > 0 && in_scope <= instances.size())
    text += " of instance " + instances[in_scope - 1].name;
  return text;
}

std::pair<Index, std::string> split_qualified(const DeckState& deck, const std::string& name) {
  const std::size_t dot = name.rfind('.');
  if (dot == std::string::npos || deck.instances.empty()) return {0, name};
  const std::string instance = name.substr(0, dot);
  for (std::size_t i = 0; i < deck.instances.size(); ++i)
    if (deck.instances[i].name == instance)
      return {static_cast<Index>(i + 1), name.substr(dot + 1)};
  return {0, name};
}

void read_part(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"NAME"}});
  expect_no_data(deck, block);
  mark_assembly_model(deck);
  if (deck.in_assembly) {
    error(deck, keyword.where, keyword, "*PART inside the *ASSEMBLY",
          "expected the parts before *ASSEMBLY, each closed by *END PART");
    return;
  }
  const std::optional<std::string> name = required_name(deck, keyword, "NAME");
  if (!name) return;
  if (find_part(deck, *name) != NO_INDEX) {
    error(deck, keyword.where, keyword, "part " + *name + " is defined twice",
          "expected each part name once");
    return;
  }
  deck.parts.push_back({*name, keyword.where, {}, 0});
  deck.open_part = static_cast<Index>(deck.parts.size() - 1);
}

void read_end_part(DeckState& deck, const DeckBlock& block) {
  check_parameters(deck, block.keyword, {});
  expect_no_data(deck, block);
  if (deck.open_part == NO_INDEX)
    error(deck, block.keyword.where, block.keyword, "*END PART without *PART",
          "expected *PART, NAME=... before it");
  deck.open_part = NO_INDEX;
}

void read_assembly(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"NAME"}});
  expect_no_data(deck, block);
  mark_assembly_model(deck);
  if (deck.in_assembly || !deck.instances.empty()) {
    error(deck, keyword.where, keyword, "second *ASSEMBLY",
          "expected one *ASSEMBLY … *END ASSEMBLY holding every instance");
    return;
  }
  deck.in_assembly = true;
  deck.assembly_where = keyword.where;
}

void read_end_assembly(DeckState& deck, const DeckBlock& block) {
  check_parameters(deck, block.keyword, {});
  expect_no_data(deck, block);
  if (!deck.in_assembly)
    error(deck, block.keyword.where, block.keyword, "*END ASSEMBLY without *ASSEMBLY",
          "expected *ASSEMBLY, NAME=... before it");
  deck.in_assembly = false;
}

void read_instance(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"NAME"}, {"PART"}, {"INSTANCE"}, {"LIBRARY"}});
  mark_assembly_model(deck);
  // A refused instance still opens its block, whose lines are then skipped (assembly_allows):
  // its *END INSTANCE and sets are no follow-up errors.
  deck.in_instance = true;
  deck.scope = 0;
  deck.instance_where = keyword.where;
  if (find_parameter(keyword, "INSTANCE") != nullptr ||
      find_parameter(keyword, "LIBRARY") != nullptr) {
    error(deck, keyword.where, keyword, "instances imported from a previous analysis",
          "expected NAME= and PART= (xpl continues a run with xpl run --import PREV.h5)");
    return;
  }
  if (!deck.in_assembly) {
    error(deck, keyword.where, keyword, "*INSTANCE outside an *ASSEMBLY",
          "expected it between *ASSEMBLY and *END ASSEMBLY");
    return;
  }
  const std::optional<std::string> name = required_name(deck, keyword, "NAME");
  const std::optional<std::string> part_name = required_name(deck, keyword, "PART");
  if (!name || !part_name) return;
  for (const DeckInstance& other : deck.instances) {
    if (other.name == *name) {
      error(deck, keyword.where, keyword, "instance " + *name + " is defined twice",
            "expected each instance name once");
      return;
    }
  }
  if (name->find('.') != std::string::npos) {
    error(deck, keyword.where, keyword, "instance name " + *name + " contains a '.'",
          "expected a name without '.', which separates the instance in INSTANCE.NAME");
    return;
  }
  const Index part = find_part(deck, *part_name);
  if (part == NO_INDEX) {
    error(deck, keyword.where, keyword, "undefined part " + *part_name,
          "expected *PART, NAME=" + *part_name + " before the *ASSEMBLY");
    return;
  }
  DeckInstance instance;
  instance.name = *name;
  instance.part = *part_name;
  instance.where = keyword.where;
  if (!read_placement(deck, block, instance)) return;
  deck.instances.push_back(std::move(instance));
  deck.scope = static_cast<Index>(deck.instances.size());
  read_part_blocks(deck, deck.parts[static_cast<std::size_t>(part)]);
}

void read_end_instance(DeckState& deck, const DeckBlock& block) {
  check_parameters(deck, block.keyword, {});
  expect_no_data(deck, block);
  if (!deck.in_instance)
    error(deck, block.keyword.where, block.keyword, "*END INSTANCE without *INSTANCE",
          "expected *INSTANCE, NAME=..., PART=... before it");
  deck.in_instance = false;
  deck.scope = 0;
}

void read_restart(DeckState& deck, const DeckBlock& block) {
  // WRITE/READ, FREQUENCY/NUMBER INTERVAL, OVERLAY, TIME MARKS: CAE writes them in every step.
  note(deck, block.keyword.where, block.keyword,
       "no restart file is written; xpl continues a run from its results: xpl run DECK.inp "
       "--import PREV.h5 (the last frame's positions, velocities, stresses)");
}

bool collect_part_block(DeckState& deck, const DeckBlock& block) {
  if (deck.open_part == NO_INDEX) return false;
  const DeckKeyword& keyword = block.keyword;
  if (keyword.name == "END PART") return false;
  PartDefinition& part = deck.parts[static_cast<std::size_t>(deck.open_part)];
  const KeywordSpec* spec = find_keyword(keyword.name);
  if (spec == nullptr) return false;  // read_block reports the unknown keyword, once
  if (spec->place == KeywordPlace::Part) {
    part.blocks.push_back(&block);
    return true;
  }
  if (is_structure(keyword.name)) {
    error(deck, keyword.where, keyword, "part " + part.name + " is not closed",
          "expected *END PART before " + keyword.label());
    deck.open_part = NO_INDEX;
    return false;
  }
  // Materials, amplitudes, interactions: model data, read once; *PREPRINT & co. anywhere.
  if (spec->place == KeywordPlace::Model || spec->place == KeywordPlace::Anywhere) return false;
  error(deck, keyword.where, keyword, keyword.label() + " inside part " + part.name,
        "expected it after *END ASSEMBLY (model data) or in a step; a part holds nodes, "
        "elements, sets, surfaces and sections");
  return true;
}

bool assembly_allows(DeckState& deck, const KeywordSpec& spec, const DeckKeyword& keyword) {
  if (deck.in_instance && deck.scope == 0 && keyword.name != "END INSTANCE") {
    // The block of a refused *INSTANCE (reported): its part-level lines are skipped; anything
    // else ends it without a second error.
    if (spec.place == KeywordPlace::Part) return false;
    deck.in_instance = false;
  }
  if (deck.in_instance && spec.place != KeywordPlace::Part && keyword.name != "END INSTANCE") {
    error(deck, keyword.where, keyword, "instance " + deck.instances.back().name + " is not closed",
          "expected *END INSTANCE before " + keyword.label() +
              " (an instance block holds only sets, surfaces and other part-level data)");
    deck.in_instance = false;
    deck.scope = 0;
  }
  if (deck.in_assembly && keyword.name == "STEP") {
    error(deck, keyword.where, keyword, "the *ASSEMBLY is not closed",
          "expected *END ASSEMBLY before the first *STEP");
    deck.in_assembly = false;
  }
  return true;
}

void close_assembly(DeckState& deck) {
  if (deck.open_part != NO_INDEX) {
    const PartDefinition& part = deck.parts[static_cast<std::size_t>(deck.open_part)];
    deck.errors.add(part.where, "*PART", "part " + part.name + " is not closed",
                    "expected *END PART");
  }
  if (deck.in_instance && deck.scope > 0)
    deck.errors.add(deck.instance_where, "*INSTANCE",
                    "instance " + deck.instances.back().name + " is not closed",
                    "expected *END INSTANCE");
  if (deck.in_assembly)
    deck.errors.add(deck.assembly_where, "*ASSEMBLY", "the *ASSEMBLY is not closed",
                    "expected *END ASSEMBLY");
  for (const PartDefinition& part : deck.parts)
    if (part.instances == 0)
      deck.model.deck_messages.push_back({true, location_text(part.where) + ": *PART: part " +
                                                    part.name +
                                                    " has no *INSTANCE: it is not in the model"});
}

}  // namespace xpl::io

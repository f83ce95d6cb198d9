/// \file Plasticity keywords of a material: *PLASTIC (tabular or Johnson–Cook isotropic
/// hardening) and *RATE DEPENDENT (power-law or Johnson–Cook rate factor), read into
/// Material::plastic (elements/plasticity.hpp). Every bad value is reported at its line; a
/// refused or bad *PLASTIC still counts as given (DeckState::plastic_lines), so its
/// *RATE DEPENDENT and the material draw no follow-up error.

#include <algorithm>
#include <cmath>
#include <string_view>

#include "io/deck/deck_handlers.hpp"

namespace xpl::io {

namespace {

using elements::Hardening;
using elements::Plasticity;
using elements::RateDependence;

constexpr const char* SUPPORTED_HARDENING =
    "supported: HARDENING=ISOTROPIC (default; yield stress, plastic strain table) or "
    "JOHNSON COOK, without other parameters";
constexpr const char* SUPPORTED_RATE =
    "supported: TYPE=POWER LAW (default; Cowper-Symonds D, n) or JOHNSON COOK (C, reference "
    "strain rate), without other parameters";

/// The plasticity lines of material `m`, the list grown to hold it.
PlasticLines& lines_of(DeckState& deck, Index m) {
  const auto i = static_cast<std::size_t>(m);
  if (deck.plastic_lines.size() <= i) deck.plastic_lines.resize(i + 1);
  return deck.plastic_lines[i];
}

/// Reports each parameter of `keyword` but `kept` as not supported (Abaqus' rate tables,
/// field-variable dependence, kinematic backstresses, ... and anything unknown), then checks
/// `kept` itself (given twice, no value); false if anything is wrong.
bool check_only_parameter(DeckState& deck, const DeckKeyword& keyword, std::string_view kept,
                          const char* supported) {
  bool ok = true;
  DeckKeyword only = keyword;
  only.parameters.clear();
  for (const DeckParameter& p : keyword.parameters) {
    if (p.name == kept) {
      only.parameters.push_back(p);
      continue;
    }
    error(deck, keyword.where, keyword, "parameter " + p.name + " is not supported", supported);
    ok = false;
  }
  return check_parameters(deck, only, {{kept}}) && ok;
}

/// A third value on a two-column line: the temperature column of Abaqus and CalculiX.
bool refuse_temperature(DeckState& deck, const DeckDataLine& line, const DeckKeyword& keyword,
                        const std::string& expected) {
  if (line.fields.size() <= 2) return true;
  error(deck, line.where(), keyword, "a third value (temperature-dependent data) is not supported",
        "expected " + expected + " only (no temperature or field-variable columns)");
  return false;
}

/// The (yield stress, plastic strain) lines of HARDENING=ISOTROPIC into `law`; false if any
/// is bad (all reported).
bool read_table(DeckState& deck, const DeckBlock& block, Plasticity& law) {
  const DeckKeyword& keyword = block.keyword;
  if (block.data.empty()) {
    error(deck, keyword.where, keyword, "no data lines",
          "expected lines of yield stress, plastic strain, the first at plastic strain 0");
    return false;
  }
  bool ok = true;
  bool first = true;
  Real previous = 0.0;  // the last plastic strain read
  for (const DeckDataLine& line : block.data) {
    const bool was_first = first;
    first = false;
    if (!refuse_temperature(deck, line, keyword, "yield stress, plastic strain")) {
      ok = false;
      continue;
    }
    const std::optional<Real> stress = real_field(deck, line, keyword, 0, "yield stress");
    // A blank plastic strain is 0, as in Abaqus ("250e6," starts a table).
    const std::optional<Real> strain = real_field(deck, line, keyword, 1, "plastic strain", 0.0);
    if (!stress || !strain) {
      ok = false;
      continue;
    }
    if (*stress <= 0.0) {
      error(deck, line.where(), keyword,
            "yield stress " + number_text(*stress) + " is not positive",
            "expected a yield stress > 0");
      ok = false;
    }
    if (was_first && *strain != 0.0) {
      error(deck, line.where(), keyword,
            "the first plastic strain is " + number_text(*strain) + ", not 0",
            "expected the table to start at plastic strain 0 (the initial yield stress)");
      ok = false;
    } else if (!was_first && !(*strain > previous)) {
      error(deck, line.where(), keyword,
            "plastic strain " + number_text(*strain) + " does not increase (previous " +
                number_text(previous) + ")",
            "expected strictly increasing plastic strains");
      ok = false;
    }
    previous = *strain;
    law.yield_stress.push_back(*stress);
    law.plastic_strain.push_back(*strain);
  }
  return ok;
}

/// The data line `A, B, n, m, θ_melt, θ_transition` of HARDENING=JOHNSON COOK into `law`;
/// false if bad (reported).
bool read_johnson_cook(DeckState& deck, const DeckBlock& block, Plasticity& law) {
  const DeckKeyword& keyword = block.keyword;
  const char* expected = "A, B, n, m, melting temperature, transition temperature";
  if (block.data.size() != 1) {
    error(deck, block.data.empty() ? keyword.where : block.data[1].where(), keyword,
          "found " + std::to_string(block.data.size()) + " data lines",
          std::string("expected one data line: ") + expected);
    return false;
  }
  const DeckDataLine& line = block.data.front();
  if (!check_field_count(deck, line, keyword, 6, expected)) return false;
  const std::optional<Real> a = real_field(deck, line, keyword, 0, "A");
  const std::optional<Real> b = real_field(deck, line, keyword, 1, "B");
  const std::optional<Real> n = real_field(deck, line, keyword, 2, "n");
  // The thermal values have no effect (no temperature field): blank is 0, as in Abaqus.
  const std::optional<Real> m = real_field(deck, line, keyword, 3, "m", 0.0);
  const std::optional<Real> melt = real_field(deck, line, keyword, 4, "melting temperature", 0.0);
  const std::optional<Real> transition =
      real_field(deck, line, keyword, 5, "transition temperature", 0.0);
  if (!a || !b || !n || !m || !melt || !transition) return false;
  bool ok = true;
  if (*a <= 0.0) {
    error(deck, line.where(), keyword, "A = " + number_text(*a) + " is not positive",
          "expected the initial yield stress A > 0");
    ok = false;
  }
  if (*b < 0.0) {
    error(deck, line.where(), keyword, "B = " + number_text(*b) + " is negative",
          "expected the hardening modulus B >= 0");
    ok = false;
  }
  if (*n <= 0.0) {
    error(deck, line.where(), keyword, "n = " + number_text(*n) + " is not positive",
          "expected the hardening exponent n > 0");
    ok = false;
  }
  law.jc_a = *a;
  law.jc_b = *b;
  law.jc_n = *n;
  law.jc_m = *m;
  law.jc_melt = *melt;
  law.jc_transition = *transition;
  if (ok && !std::isfinite(law.largest_flow_stress())) {
    error(deck, line.where(), keyword,
          "A = " + number_text(*a) + ", B = " + number_text(*b) + ", n = " + number_text(*n) +
              " give a flow stress of " +
              (std::isnan(law.largest_flow_stress()) ? std::string("NaN")
                                                     : number_text(law.largest_flow_stress())) +
              " at plastic strain " + number_text(elements::PLAUSIBLE_PLASTIC_STRAIN),
          "expected constants for which A + B (plastic strain)^n stays finite up to plastic "
          "strain " +
              number_text(elements::PLAUSIBLE_PLASTIC_STRAIN));
    ok = false;
  }
  return ok;
}

}  // namespace

void read_plastic(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  bool refused = !check_only_parameter(deck, keyword, "HARDENING", SUPPORTED_HARDENING);
  const std::string hardening = optional_name(keyword, "HARDENING");
  Plasticity law;
  if (hardening == "JOHNSON COOK") {
    law.hardening = Hardening::JohnsonCook;
  } else if (!hardening.empty() && hardening != "ISOTROPIC") {
    error(deck, keyword.where, keyword, "hardening " + hardening + " is not supported",
          SUPPORTED_HARDENING);
    refused = true;
  }
  if (deck.material == NO_INDEX) {
    error(deck, keyword.where, keyword, "no material to attach to",
          "expected *PLASTIC in a material: after *MATERIAL, NAME=... and its *ELASTIC");
    deck.plastic_without_material = true;
    return;
  }
  Material& material = deck.model.materials[static_cast<std::size_t>(deck.material)];
  PlasticLines& lines = lines_of(deck, deck.material);
  if (lines.plastic.line != 0) {
    error(deck, keyword.where, keyword,
          "material " + material.name + " already has *PLASTIC (" + location_text(lines.plastic) +
              ")",
          "expected one *PLASTIC per material");
    return;
  }
  lines.plastic = keyword.where;  // given, even if refused: no follow-up errors
  if (refused) return;
  const bool ok = law.hardening == Hardening::JohnsonCook ? read_johnson_cook(deck, block, law)
                                                          : read_table(deck, block, law);
  if (!ok) return;
  if (law.softens())
    note(deck, keyword.where, keyword,
         "the hardening of material " + material.name +
             " softens (the yield stress falls with plastic strain); accepted, but the "
             "response may localise in one element row");
  if (law.hardening == Hardening::JohnsonCook)
    note(deck, keyword.where, keyword,
         "material " + material.name +
             ": the Johnson-Cook thermal term is taken as 1 (m = " + number_text(law.jc_m) +
             ", melting temperature " + number_text(law.jc_melt) + ", transition temperature " +
             number_text(law.jc_transition) + " are read, but xpl has no temperature field)");
  material.plastic = std::move(law);
  material.plastic_where = keyword.where;
}

void read_rate_dependent(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  bool refused = !check_only_parameter(deck, keyword, "TYPE", SUPPORTED_RATE);
  const std::string type = optional_name(keyword, "TYPE");
  const bool johnson_cook = type == "JOHNSON COOK";
  if (!johnson_cook && !type.empty() && type != "POWER LAW") {
    error(deck, keyword.where, keyword, "rate dependence TYPE=" + type + " is not supported",
          SUPPORTED_RATE);
    refused = true;
  }
  if (deck.material == NO_INDEX) {
    if (!deck.plastic_without_material)  // else reported at the *PLASTIC already
      error(deck, keyword.where, keyword, "no material to attach to",
            "expected *RATE DEPENDENT right after the *PLASTIC of a material");
    return;
  }
  Material& material = deck.model.materials[static_cast<std::size_t>(deck.material)];
  PlasticLines& lines = lines_of(deck, deck.material);
  if (lines.plastic.line == 0) {
    error(deck, keyword.where, keyword, "material " + material.name + " has no *PLASTIC before it",
          "expected *RATE DEPENDENT after the *PLASTIC of the same material");
    return;
  }
  if (lines.rate_dependent.line != 0) {
    error(deck, keyword.where, keyword,
          "material " + material.name + " already has *RATE DEPENDENT (" +
              location_text(lines.rate_dependent) + ")",
          "expected one *RATE DEPENDENT per material");
    return;
  }
  lines.rate_dependent = keyword.where;
  if (refused) return;
  const char* expected = johnson_cook ? "C, reference strain rate" : "D, n";
  if (block.data.size() != 1) {
    error(deck, block.data.empty() ? keyword.where : block.data[1].where(), keyword,
          "found " + std::to_string(block.data.size()) + " data lines",
          std::string("expected one data line: ") + expected);
    return;
  }
  const DeckDataLine& line = block.data.front();
  if (!refuse_temperature(deck, line, keyword, expected)) return;
  const std::optional<Real> first = real_field(deck, line, keyword, 0, johnson_cook ? "C" : "D");
  const std::optional<Real> second =
      real_field(deck, line, keyword, 1, johnson_cook ? "reference strain rate" : "n");
  if (!first || !second) return;
  bool ok = true;
  if (johnson_cook) {
    if (*first < 0.0) {
      error(deck, line.where(), keyword, "C = " + number_text(*first) + " is negative",
            "expected the rate coefficient C >= 0");
      ok = false;
    }
    if (*second <= 0.0) {
      error(deck, line.where(), keyword,
            "reference strain rate " + number_text(*second) + " is not positive",
            "expected a reference strain rate > 0 (1/s)");
      ok = false;
    }
  } else {
    if (*first <= 0.0) {
      error(deck, line.where(), keyword, "D = " + number_text(*first) + " is not positive",
            "expected the Cowper-Symonds D > 0 (1/s)");
      ok = false;
    }
    if (*second <= 0.0) {
      error(deck, line.where(), keyword, "n = " + number_text(*second) + " is not positive",
            "expected the Cowper-Symonds exponent n > 0");
      ok = false;
    }
  }
  if (!ok || !material.plastic) return;  // a bad *PLASTIC is reported already
  Plasticity law = *material.plastic;
  if (johnson_cook) {
    law.rate = RateDependence::JohnsonCook;
    law.rate_c = *first;
    law.rate_reference = *second;
  } else {
    law.rate = RateDependence::PowerLaw;
    law.power_d = *first;
    law.power_n = *second;
  }
  // The returns solve every law whose flow stress is finite (elements/plasticity.hpp); one
  // that overflows at a plausible rate is a mistake in its constants.
  const Real largest = law.largest_flow_stress();
  if (!std::isfinite(largest)) {
    const std::string rate = number_text(elements::PLAUSIBLE_STRAIN_RATE);
    error(deck, line.where(), keyword,
          std::string(johnson_cook ? "C = " : "D = ") + number_text(*first) +
              (johnson_cook ? ", reference strain rate " : ", n = ") + number_text(*second) +
              " give material " + material.name + " a flow stress of " +
              (std::isnan(largest) ? std::string("NaN") : number_text(largest)) +
              " at a strain rate of " + rate + " /s",
          "expected rate constants for which the flow stress stays finite up to " + rate + " /s" +
              (johnson_cook ? "" : " (a larger D or n)"));
    return;
  }
  *material.plastic = std::move(law);
}

void check_plastic_materials(DeckState& deck) {
  for (std::size_t m = 0; m < deck.plastic_lines.size(); ++m) {
    const SourceLocation& where = deck.plastic_lines[m].plastic;
    Material& material = deck.model.materials[m];
    if (where.line == 0 || material.has_elastic) continue;
    deck.errors.add(where, "*PLASTIC", "material " + material.name + " has no *ELASTIC",
                    "expected *ELASTIC (E, nu) in the material: plasticity needs the elastic "
                    "moduli");
    material.has_elastic = true;  // reported here: no "has no elastic data" at *MATERIAL
  }
}

}  // namespace xpl::io

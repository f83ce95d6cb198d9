// *PLASTIC and *RATE DEPENDENT: good decks fill Material::plastic with the values written;
// every bad value is one `t.inp:LINE: *KEYWORD: ...` error at its line, all reported together.

#include <catch2/catch.hpp>

#include <string>

#include "deck/deck_test_support.hpp"

using namespace xpl;
using elements::Hardening;
using elements::RateDependence;
using test::at;
using test::simple_step;
using test::two_brick_model;

namespace {

/// The base deck with `lines` inserted right after STEEL's *ELASTIC data line.
std::string with_plastic(const std::string& lines) {
  std::string deck = two_brick_model() + simple_step();
  const std::string elastic = "2.1e11, 0.3\n";
  deck.insert(deck.find(elastic) + elastic.size(), lines);
  return deck;
}

/// STEEL of a deck that reads without errors (model checks skipped: the kernels may refuse).
Material steel(const std::string& deck) {
  const Model m = io::read_deck_text(deck, "t.inp", io::ModelChecks::Skip);
  REQUIRE(m.materials.size() == 1);
  return m.materials[0];
}

}  // namespace

TEST_CASE("*PLASTIC tabular hardening is read point by point", "[io][deck][plastic]") {
  const std::string deck = with_plastic(
      "*PLASTIC\n"
      "4.0e8, 0.0\n"
      "4.5e8, 0.1\n"
      "5.0e8, 0.5\n");
  const Material m = steel(deck);
  REQUIRE(m.plastic);
  const elements::Plasticity& p = *m.plastic;
  CHECK(p.hardening == Hardening::Tabular);
  CHECK(p.yield_stress == std::vector<Real>{4.0e8, 4.5e8, 5.0e8});
  CHECK(p.plastic_strain == std::vector<Real>{0.0, 0.1, 0.5});
  CHECK(p.rate == RateDependence::None);
  CHECK(p.initial_yield() == 4.0e8);
  CHECK(m.plastic_where.line == test::line_of(deck, "*PLASTIC"));
  CHECK(m.young == 2.1e11);  // *ELASTIC untouched
}

TEST_CASE("an elastic material stays without plasticity data", "[io][deck][plastic]") {
  CHECK_FALSE(steel(two_brick_model() + simple_step()).plastic);
}

TEST_CASE("*PLASTIC written in CalculiX style (lower case, blanks, before *ELASTIC)",
          "[io][deck][plastic]") {
  std::string deck = two_brick_model() + simple_step();
  deck.replace(deck.find("*ELASTIC\n"), 9,
               "*plastic ,  hardening = isotropic\n"
               " 250.E6 , 0.\n"
               " 300.E6 ,  0.2 ,\n"
               "*ELASTIC\n");
  const Material m = steel(deck);
  REQUIRE(m.plastic);
  CHECK(m.plastic->yield_stress == std::vector<Real>{250e6, 300e6});
  CHECK(m.plastic->plastic_strain == std::vector<Real>{0.0, 0.2});
}

TEST_CASE("one point is perfectly plastic; a blank plastic strain is 0", "[io][deck][plastic]") {
  const Material m = steel(with_plastic("*PLASTIC\n2.5e8,\n"));
  REQUIRE(m.plastic);
  CHECK(m.plastic->yield_stress == std::vector<Real>{2.5e8});
  CHECK(m.plastic->plastic_strain == std::vector<Real>{0.0});
}

TEST_CASE("*PLASTIC, HARDENING=JOHNSON COOK with *RATE DEPENDENT, TYPE=JOHNSON COOK",
          "[io][deck][plastic]") {
  const std::string deck = with_plastic(
      "*PLASTIC, HARDENING=JOHNSON COOK\n"
      "792e6, 510e6, 0.26, 1.03, 1793., 293.\n"
      "*RATE DEPENDENT, TYPE=JOHNSON COOK\n"
      "0.014, 1.0\n");
  const Model model = io::read_deck_text(deck, "t.inp", io::ModelChecks::Skip);
  const Material& m = model.materials[0];
  REQUIRE(m.plastic);
  const elements::Plasticity& p = *m.plastic;
  CHECK(p.hardening == Hardening::JohnsonCook);
  CHECK(p.jc_a == 792e6);
  CHECK(p.jc_b == 510e6);
  CHECK(p.jc_n == 0.26);
  CHECK(p.jc_m == 1.03);
  CHECK(p.jc_melt == 1793.0);
  CHECK(p.jc_transition == 293.0);
  CHECK(p.rate == RateDependence::JohnsonCook);
  CHECK(p.rate_c == 0.014);
  CHECK(p.rate_reference == 1.0);
  // The .msg says the thermal term is 1.
  REQUIRE(model.deck_messages.size() == 1);
  CHECK_FALSE(model.deck_messages[0].warning);
  CHECK(model.deck_messages[0].text.rfind(at(deck, "*PLASTIC", "*PLASTIC") +
                                              "material STEEL: the Johnson-Cook thermal term is "
                                              "taken as 1",
                                          0) == 0);
}

TEST_CASE("*RATE DEPENDENT power law (Cowper-Symonds), the default TYPE", "[io][deck][plastic]") {
  for (const char* keyword : {"*RATE DEPENDENT\n", "*Rate Dependent, type=power law\n"}) {
    const Material m =
        steel(with_plastic(std::string("*PLASTIC\n3e8, 0\n4e8, 0.3\n") + keyword + "40.4, 5\n"));
    REQUIRE(m.plastic);
    CHECK(m.plastic->rate == RateDependence::PowerLaw);
    CHECK(m.plastic->power_d == 40.4);
    CHECK(m.plastic->power_n == 5.0);
    CHECK(m.plastic->hardening == Hardening::Tabular);
  }
}

TEST_CASE("a softening table is accepted with a note", "[io][deck][plastic]") {
  const std::string deck = with_plastic("*PLASTIC\n4e8, 0\n3e8, 0.2\n");
  const Model m = io::read_deck_text(deck, "t.inp", io::ModelChecks::Skip);
  REQUIRE(m.materials[0].plastic);
  CHECK(m.materials[0].plastic->softens());
  REQUIRE(m.deck_messages.size() == 1);
  CHECK(m.deck_messages[0].text.rfind(
            at(deck, "*PLASTIC", "*PLASTIC") + "the hardening of material STEEL softens", 0) == 0);
}

// Nonsense values refused at their line (issue 33, item 5): a mass-scaling FACTOR below 1 or
// of 1e300, a DT of 1e±300, ELSET= a set of rigid-body elements, rate-law and Johnson–Cook
// constants that make the flow stress overflow. Before, each was accepted: FACTOR=0.5 removed
// half the mass ("mass added -7.1e-05 kg (-50 %)"), a rigid ELSET= scaled "0 of 0 elements"
// to an increment of inf s, and a Cowper–Symonds D of 1e-300 gave an infinite flow stress.

#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "deck/deck_test_support.hpp"

using namespace xpl;
using test::at;
using test::deck_errors;
using test::line_of;
using test::two_brick_model;

namespace {

/// Two bricks, an extra brick WALL made a rigid body, and one step of 1 ms with `lines`.
std::string scaling_deck(const std::string& lines) {
  return two_brick_model() +
         "*NODE\n20, 0, 0, 5\n21, 1, 0, 5\n22, 1, 1, 5\n23, 0, 1, 5\n24, 0, 0, 6\n25, 1, 0, 6\n"
         "26, 1, 1, 6\n27, 0, 1, 6\n30, 0, 0, 7\n"
         "*ELEMENT, TYPE=C3D8R, ELSET=WALL\n9, 20, 21, 22, 23, 24, 25, 26, 27\n"
         "*SOLID SECTION, ELSET=WALL, MATERIAL=STEEL\n"
         "*RIGID BODY, REF NODE=30, ELSET=WALL\n"
         "*ELSET, ELSET=BOTH\n5000001, 9\n"
         "*STEP\n*DYNAMIC, EXPLICIT\n, 1e-3\n" +
         lines + "*END STEP\n";
}

/// The base deck with `lines` right after STEEL's *ELASTIC data line.
std::string plastic_deck(const std::string& lines) {
  std::string deck = two_brick_model() + test::simple_step();
  const std::string elastic = "2.1e11, 0.3\n";
  deck.insert(deck.find(elastic) + elastic.size(), lines);
  return deck;
}

const std::string K = "*FIXED MASS SCALING";
const std::string RANGE = "expected a mass factor from 1 to 1e+06, e.g. FACTOR=4";

}  // namespace

TEST_CASE("mass scaling: factors below 1 and of 1e300 are refused",
          "[io][deck][mass-scaling][errors]") {
  const std::string deck = scaling_deck(
      "*FIXED MASS SCALING, FACTOR=0.5\n"
      "*FIXED MASS SCALING, FACTOR=1e-300\n"
      "*FIXED MASS SCALING, FACTOR=1e300, ELSET=BRICKS\n"
      "*FIXED MASS SCALING, FACTOR=1\n"  // no scaling: accepted
      "*FIXED MASS SCALING, FACTOR=1e6\n");
  const std::vector<std::string> expected = {
      at(deck, "FACTOR=0.5", K) +
          "FACTOR=0.5 is below 1: it would remove mass (the stable increment shrinks); " + RANGE,
      at(deck, "FACTOR=1e-300", K) +
          "FACTOR=1e-300 is below 1: it would remove mass (the stable increment shrinks); " + RANGE,
      at(deck, "FACTOR=1e300", K) +
          "FACTOR=1e+300 is above 1e+06: the scaled elements would be near-rigid lumps; " + RANGE,
  };
  CHECK(deck_errors(deck) == expected);
}

TEST_CASE("mass scaling: a DT of 1e300 or 1e-300 is refused", "[io][deck][mass-scaling][errors]") {
  const std::string deck = scaling_deck(
      "*FIXED MASS SCALING, DT=1e300\n"
      "*FIXED MASS SCALING, DT=1e-300, TYPE=UNIFORM\n"
      "*FIXED MASS SCALING, DT=1e-3\n"     // the step itself: accepted
      "*FIXED MASS SCALING, DT=1e-15\n");  // 1e-12 of the step: accepted
  const std::string range = "expected a target stable increment from 1e-15 to 0.001 s";
  const std::vector<std::string> expected = {
      at(deck, "DT=1e300", K) + "DT=1e+300 s is longer than the step time period 0.001 s; " + range,
      at(deck, "DT=1e-300", K) +
          "DT=1e-300 s is shorter than 1e-12 of the step time period 0.001 s; " + range,
  };
  CHECK(deck_errors(deck) == expected);

  // Before *DYNAMIC the step's time period is not known: bounds of 1e-30 and 1e30 s.
  const std::string early = two_brick_model() +
                            "*STEP\n*FIXED MASS SCALING, DT=1e300\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
                            "*END STEP\n";
  CHECK(deck_errors(early) ==
        std::vector<std::string>{at(early, "DT=1e300", K) +
                                 "DT=1e+300 s is longer than 1e+30 s; expected a target stable "
                                 "increment from 1e-30 to 1e+30 s"});
}

TEST_CASE("mass scaling: ELSET= a set of rigid-body elements only is refused",
          "[io][deck][mass-scaling][errors]") {
  const std::string deck = scaling_deck(
      "*FIXED MASS SCALING, FACTOR=4, ELSET=WALL\n"
      "*FIXED MASS SCALING, FACTOR=4, ELSET=BOTH\n");  // one deformable element: accepted
  CHECK(deck_errors(deck) ==
        std::vector<std::string>{at(deck, "FACTOR=4, ELSET=WALL", K) +
                                 "element set WALL holds only elements of rigid bodies (*RIGID "
                                 "BODY, ELSET=); expected a set with deformable elements: rigid "
                                 "bodies have no stable increment to raise"});
}

TEST_CASE("rate laws whose flow stress overflows are refused at their line",
          "[io][deck][plastic][errors]") {
  const std::string plastic = "*PLASTIC\n2.5e8, 0\n";
  const std::string finite =
      "expected rate constants for which the flow stress stays finite up "
      "to 1e+08 /s";
  SECTION("a Cowper-Symonds D of 1e-300") {
    const std::string deck = plastic_deck(plastic + "*RATE DEPENDENT\n1e-300, 1\n");
    CHECK(deck_errors(deck) ==
          std::vector<std::string>{at(deck, "1e-300, 1", "*RATE DEPENDENT") +
                                   "D = 1e-300, n = 1 give material STEEL a flow stress of inf "
                                   "at a strain rate of 1e+08 /s; " +
                                   finite + " (a larger D or n)"});
  }
  SECTION("a Cowper-Symonds n of 1e-3") {
    const std::string deck = plastic_deck(plastic + "*RATE DEPENDENT, TYPE=POWER LAW\n40, 1e-3\n");
    CHECK(deck_errors(deck) ==
          std::vector<std::string>{at(deck, "40, 1e-3", "*RATE DEPENDENT") +
                                   "D = 40, n = 0.001 give material STEEL a flow stress of inf "
                                   "at a strain rate of 1e+08 /s; " +
                                   finite + " (a larger D or n)"});
  }
  SECTION("a Johnson-Cook C of 1e308 and a reference rate of 1e-310") {
    const std::string deck =
        plastic_deck(plastic + "*RATE DEPENDENT, TYPE=JOHNSON COOK\n1e308, 1\n");
    CHECK(deck_errors(deck) ==
          std::vector<std::string>{at(deck, "1e308, 1", "*RATE DEPENDENT") +
                                   "C = 1e+308, reference strain rate 1 give material STEEL a "
                                   "flow stress of inf at a strain rate of 1e+08 /s; " +
                                   finite});
    const std::string tiny =
        plastic_deck(plastic + "*RATE DEPENDENT, TYPE=JOHNSON COOK\n0, 1e-310\n");
    CHECK(deck_errors(tiny) ==
          std::vector<std::string>{at(tiny, "0, 1e-310", "*RATE DEPENDENT") +
                                   "C = 0, reference strain rate 1e-310 give material "
                                   "STEEL a flow stress of NaN at a strain rate of 1e+08 /s; " +
                                   finite});
  }
  SECTION("Johnson-Cook hardening that overflows") {
    const std::string deck =
        plastic_deck("*PLASTIC, HARDENING=JOHNSON COOK\n3e8, 1e8, 400, 1, 1800, 293\n");
    CHECK(deck_errors(deck) ==
          std::vector<std::string>{at(deck, "3e8, 1e8, 400", "*PLASTIC") +
                                   "A = 3e+08, B = 1e+08, n = 400 give a flow stress of inf at "
                                   "plastic strain 10; expected constants for which A + B "
                                   "(plastic strain)^n stays finite up to plastic strain 10"});
  }
  SECTION("the steep laws of the issue are accepted: the return solves them") {
    CHECK(deck_errors(plastic_deck(plastic + "*RATE DEPENDENT\n40, 0.05\n")).empty());
    CHECK(deck_errors(plastic_deck("*PLASTIC, HARDENING=JOHNSON COOK\n3e8, 5e8, 0.01, 1, 1800, "
                                   "293\n*RATE DEPENDENT, TYPE=JOHNSON COOK\n0.5, 1\n"))
              .empty());
  }
}

#include <catch2/catch.hpp>

#include "common/error.hpp"

TEST_CASE("input errors are collected and formatted file:line: keyword", "[common][errors]") {
  xpl::InputErrors errors;
  CHECK(errors.empty());
  errors.add({"deck.inp", 12}, "*NODE", "bad number 'x1'", "expected a real number");
  errors.add({"deck.inp", 30}, "*ELEMENT", "node 99 is not defined", "");
  REQUIRE(errors.size() == 2);
  CHECK(errors.messages()[0] == "deck.inp:12: *NODE: bad number 'x1'; expected a real number");
  CHECK(errors.messages()[1] == "deck.inp:30: *ELEMENT: node 99 is not defined");
  try {
    errors.throw_if_any();
    FAIL("no exception");
  } catch (const xpl::InputError& e) {
    CHECK(e.messages().size() == 2);
    CHECK(std::string(e.what()).find('\n') != std::string::npos);
  }
}

TEST_CASE("deck text echoed in errors has its control characters escaped", "[common][errors]") {
  CHECK(xpl::escape_control("plain text, tab\tand\nnewline") == "plain text, tab\tand\nnewline");
  CHECK(xpl::escape_control("\x1b[31mred\x07\x7f") == "\\x1b[31mred\\x07\\x7f");
  xpl::InputErrors errors;
  errors.add({"deck.inp", 3}, "*\x1b[2JBOGUS", "unknown keyword", "");
  errors.add_plain("deck.inp: \r\x01");
  CHECK(errors.messages()[0] == "deck.inp:3: *\\x1b[2JBOGUS: unknown keyword");
  CHECK(errors.messages()[1] == "deck.inp: \\x0d\\x01");
}

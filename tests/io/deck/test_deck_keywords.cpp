// The keyword table of docs/user/keywords.md ("The keywords") and the reader's keyword table
// name the same keywords: a keyword added to one must be added to the other.

#include <catch2/catch.hpp>

#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "io/deck/deck_keywords.hpp"

using namespace xpl;

namespace {

/// Keywords in the first column of docs/user/keywords.md's table: every `*NAME`
/// in backticks (a row may name several, e.g. "`*STEP` … `*END STEP`").
std::set<std::string> documented_keywords() {
  std::ifstream file(XPL_SOURCE_DIR "/docs/user/keywords.md");
  REQUIRE(file);
  std::set<std::string> names;
  std::string line;
  bool in_section = false;
  while (std::getline(file, line)) {
    if (line.rfind("## ", 0) == 0) in_section = line == "## The keywords";
    if (!in_section || line.rfind("| `*", 0) != 0) continue;
    const std::string cell = line.substr(1, line.find('|', 1) - 1);
    for (std::size_t open = cell.find("`*"); open != std::string::npos;
         open = cell.find("`*", open + 1)) {
      const std::size_t close = cell.find('`', open + 1);
      REQUIRE(close != std::string::npos);
      names.insert(cell.substr(open + 2, close - open - 2));
      open = close;
    }
  }
  return names;
}

}  // namespace

TEST_CASE("docs/user/keywords.md lists exactly the keywords the reader supports", "[io][deck]") {
  const std::set<std::string> documented = documented_keywords();
  REQUIRE(!documented.empty());
  std::set<std::string> supported;
  for (const io::KeywordSpec& spec : io::keyword_table())
    if (spec.supported) supported.insert(std::string(spec.name));
  for (const std::string& name : supported) {
    INFO("*" << name << " is read but not in docs/user/keywords.md's table");
    CHECK(documented.count(name) == 1);
  }
  for (const std::string& name : documented) {
    INFO("*" << name << " is in docs/user/keywords.md's table but not read");
    CHECK(supported.count(name) == 1);
  }
}

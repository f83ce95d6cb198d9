// A generated block mesh read through every path of the lexer: long *NODE and *ELEMENT
// blocks, continuation lines across comments, CRLF line ends, quotes and files on disk.

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "deck_test_support.hpp"
#include "io/deck/deck_reader.hpp"

using namespace xpl;

namespace {

struct BlockDeck {
  std::string mesh;        ///< *NODE and *ELEMENT blocks
  int split_element = 0;   ///< id of the element written over two lines
  int split_line = 0;      ///< its first physical line
  std::string split_text;  ///< "id, n1, ..." of that element, for checking its nodes
};

/// An n x n x n block of unit hexes; ids 1.. in x-fastest order. Element `split` is written
/// over two lines with a comment between them.
BlockDeck block_deck(int n, int split, const std::string& eol) {
  BlockDeck deck;
  const int row = n + 1;
  auto node_id = [&](int i, int j, int k) { return 1 + i + row * (j + row * k); };
  int line = 0;
  auto add = [&](const std::string& text) {
    deck.mesh += text + eol;
    ++line;
  };
  add("** generated block");
  add("*NODE, NSET=\"All Nodes\"");
  for (int k = 0; k < row; ++k)
    for (int j = 0; j < row; ++j)
      for (int i = 0; i < row; ++i)
        add(std::to_string(node_id(i, j, k)) + ", " + std::to_string(i) + ".0, " +
            std::to_string(j) + ", " + std::to_string(k) + "e0");
  add("*ELEMENT, TYPE=C3D8R, ELSET=BLOCK");
  int id = 0;
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        ++id;
        const int c[8] = {node_id(i, j, k),
                          node_id(i + 1, j, k),
                          node_id(i + 1, j + 1, k),
                          node_id(i, j + 1, k),
                          node_id(i, j, k + 1),
                          node_id(i + 1, j, k + 1),
                          node_id(i + 1, j + 1, k + 1),
                          node_id(i, j + 1, k + 1)};
        std::string first = std::to_string(id), second;
        for (int a = 0; a < 8; ++a) (a < 4 ? first : second) += ", " + std::to_string(c[a]);
        if (id == split) {
          deck.split_element = id;
          deck.split_line = line + 1;
          deck.split_text = first + second;
          add(first + ",  ");
          add("** a comment between the two halves");
          add("   " + second.substr(2));
        } else {
          add(first + second);
        }
      }
    }
  }
  return deck;
}

std::string rest_of_deck(const std::string& eol) {
  std::string text = std::string("*ELSET, ELSET=HALF, GENERATE") + eol + "1, 1000, 2" + eol +
                     "*MATERIAL, NAME=STEEL" + eol + "*DENSITY" + eol + "7800." + eol + "*ELASTIC" +
                     eol + "2.1e11, 0.3" + eol + "*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL" +
                     eol;
  return text + test::simple_step();
}

}  // namespace

TEST_CASE("a generated block deck gives the expected counts and locations", "[io][deck]") {
  const int n = 12;
  for (const std::string eol : {"\n", "\r\n"}) {
    const BlockDeck deck = block_deck(n, 100, eol);
    const Model m = io::read_deck_text(deck.mesh + rest_of_deck(eol), "generated/block.inp");
    CHECK(m.node_count() == (n + 1) * (n + 1) * (n + 1));
    REQUIRE(m.element_count() == n * n * n);
    REQUIRE(m.element_line.size() == static_cast<std::size_t>(n * n * n));
    // Element 1 is on the line after *ELEMENT; the split element is found at its first line
    // and the one after it two lines later (continuation plus comment).
    const int first_element_line = 4 + (n + 1) * (n + 1) * (n + 1);
    CHECK(m.element_where(0).file == "generated/block.inp");
    CHECK(m.element_where(0).line == first_element_line);
    CHECK(m.element_where(deck.split_element - 1).line == deck.split_line);
    CHECK(m.element_where(deck.split_element).line == deck.split_line + 3);
    CHECK(m.element_where(m.element_count() - 1).line == first_element_line + n * n * n - 1 + 2);
    // The split element's nodes: ids follow the grid, internal index = id - 1.
    const Index* nodes = m.nodes_of(deck.split_element - 1);
    std::string text = std::to_string(deck.split_element);
    for (int a = 0; a < 8; ++a) text += ", " + std::to_string(m.node_ids[nodes[a]]);
    CHECK(text == deck.split_text);
    CHECK(m.coordinates(m.node_count() - 1, 0) == n);
    CHECK(m.coordinates(m.node_count() - 1, 2) == n);
    const Index all = m.find_node_set("ALL NODES");
    REQUIRE(all != NO_INDEX);
    CHECK(m.node_sets[all].members.size() == static_cast<std::size_t>(m.node_count()));
    const Index half = m.find_element_set("HALF");
    REQUIRE(half != NO_INDEX);
    CHECK(m.element_sets[half].members.size() == 500);
    CHECK(m.element_section.size() == static_cast<std::size_t>(n * n * n));
  }
}

TEST_CASE("a generated deck on disk, its mesh included from a long path", "[io][deck]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "xpl_deck_large_test_with_a_long_directory";
  fs::create_directories(dir / "mesh_parts_directory");
  const int n = 10;
  const BlockDeck deck = block_deck(n, 7, "\n");
  {
    std::ofstream(dir / "mesh_parts_directory" / "generated_block_mesh.inp") << deck.mesh;
    std::ofstream(dir / "main.inp") << "*HEADING\nblock on disk\n"
                                    << "*INCLUDE, INPUT=mesh_parts_directory/"
                                       "generated_block_mesh.inp\n"
                                    << rest_of_deck("\n");
  }
  const Model m = io::read_deck(dir / "main.inp");
  CHECK(m.heading == "block on disk");
  CHECK(m.job_name == "main");
  CHECK(m.node_count() == (n + 1) * (n + 1) * (n + 1));
  REQUIRE(m.element_count() == n * n * n);
  CHECK(m.element_where(6).file ==
        (dir / "mesh_parts_directory" / "generated_block_mesh.inp").lexically_normal().string());
  CHECK(m.element_where(6).line == deck.split_line);

  // An error in the included mesh names that file and line; errors of the lexer come first.
  std::string bad = deck.mesh;
  const std::string needle = "\n5, ";
  bad.replace(bad.find(needle), needle.size(), "\n5x, ");
  std::ofstream(dir / "mesh_parts_directory" / "generated_block_mesh.inp") << bad << "\"\n";
  try {
    io::read_deck(dir / "main.inp");
    FAIL("expected an InputError");
  } catch (const InputError& e) {
    const std::string part =
        (dir / "mesh_parts_directory" / "generated_block_mesh.inp").lexically_normal().string();
    REQUIRE(e.messages().size() >= 2);
    CHECK(e.messages()[0].rfind(part + ":", 0) == 0);
    CHECK(e.messages()[0].find("*ELEMENT: unterminated quote") != std::string::npos);
    CHECK(test::has_error(e.messages(), part + ":7: *NODE: bad integer '5x' for node id"));
  }
  fs::remove_all(dir);
}

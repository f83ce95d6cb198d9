/// \file Element geometry checks: the shape measures, and the reader's per-element checks run
/// once the whole mesh is known.

#include "io/deck/deck_geometry.hpp"

#include <algorithm>
#include <sstream>

#include <Eigen/Geometry>

#include "io/deck/deck_handlers.hpp"

namespace xpl::io {

namespace {

/// Relative tolerance of the shell checks: a length below this fraction of the longest edge
/// (an area below it times the longest edge squared) counts as zero. Far below any sane
/// element aspect ratio, far above round-off.
constexpr Real QUAD_TOLERANCE = 1e-8;

}  // namespace

CornerJacobian smallest_corner_jacobian(const std::array<Eigen::Vector3d, 8>& x) {
  CornerJacobian smallest;
  for (int c = 0; c < 8; ++c) {
    const int ring = c < 4 ? 0 : 4;  // bottom face 0-3, top face 4-7, both numbered alike
    const int local = c - ring;
    const int next = ring + (local + 1) % 4;
    const int previous = ring + (local + 3) % 4;
    const int across = c < 4 ? c + 4 : c - 4;
    const Eigen::Vector3d to_next = x[next] - x[c];
    const Eigen::Vector3d to_previous = x[previous] - x[c];
    const Eigen::Vector3d to_across = x[across] - x[c];
    // Bottom corners see (ξ, η, ζ) as (next, previous, up) up to a rotation; on the top face
    // the third edge points down, which flips the orientation, so next and previous swap.
    const Real det = c < 4 ? to_next.dot(to_previous.cross(to_across))
                           : to_previous.dot(to_next.cross(to_across));
    if (c == 0 || det < smallest.determinant) smallest = {det, c};
  }
  return smallest;
}

QuadShape quad_shape(const std::array<Eigen::Vector3d, 4>& x) {
  QuadShape shape;
  const Eigen::Vector3d normal = (x[2] - x[0]).cross(x[3] - x[1]);
  const Real twice_area = normal.norm();
  shape.area = 0.5 * twice_area;
  for (int k = 0; k < 4; ++k) {
    const Real edge = (x[(k + 1) % 4] - x[k]).norm();
    shape.longest_edge = std::max(shape.longest_edge, edge);
    if (k == 0 || edge < shape.shortest_edge) {
      shape.shortest_edge = edge;
      shape.shortest_edge_start = k;
    }
    if (twice_area > 0.0)
      shape.corner[k] =
          (x[(k + 1) % 4] - x[k]).cross(x[(k + 3) % 4] - x[k]).dot(normal) / twice_area;
  }
  return shape;
}

void check_element_geometry(DeckState& deck) {
  std::vector<char> bad(deck.bad_coordinate_nodes.empty() ? 0 : deck.model.node_count(), 0);
  for (Index n : deck.bad_coordinate_nodes) bad[n] = 1;
  for (Index e = 0; e < deck.model.element_count(); ++e) {
    const Index* nodes = deck.model.nodes_of(e);
    const Index* end = nodes + (deck.model.element_offsets[e + 1] - deck.model.element_offsets[e]);
    // Undefined nodes and bad coordinates are reported already; a shape error would repeat them.
    if (std::any_of(nodes, end, [](Index n) { return n == NO_INDEX; })) continue;
    if (!bad.empty() && std::any_of(nodes, end, [&](Index n) { return bad[n] != 0; })) continue;
    if (is_shell(deck.model.element_types[static_cast<std::size_t>(e)]))
      check_shell_geometry(deck, e);
    else
      check_hex_geometry(deck, e);
  }
}

void check_hex_geometry(DeckState& deck, Index e) {
  const Index* nodes = deck.model.nodes_of(e);
  std::array<Eigen::Vector3d, 8> x;
  for (int k = 0; k < 8; ++k) x[k] = deck.model.coordinates.row(nodes[k]).transpose();
  const CornerJacobian smallest = smallest_corner_jacobian(x);
  if (smallest.determinant > 0.0) return;
  std::ostringstream problem;
  problem << "inverted element " << deck.model.element_ids[e] << ": volume " << smallest.determinant
          << " at corner node " << deck.model.node_ids[nodes[smallest.corner]];
  capped_error(deck, deck.error_counts[INVERTED], deck.model.element_where(e), "*ELEMENT",
               problem.str(),
               "expected nodes in Abaqus C3D8R order (nodes 1-4 counter-clockwise on the "
               "bottom face seen from the top face 5-8), i.e. a positive Jacobian at every "
               "corner");
}

void check_shell_geometry(DeckState& deck, Index e) {
  const Index* nodes = deck.model.nodes_of(e);
  // Messages are built only for a bad element: this runs on every shell of a large mesh.
  auto report = [&](const std::string& what, const std::string& problem,
                    const std::string& expected) {
    capped_error(deck, deck.error_counts[DEGENERATE], deck.model.element_where(e), "*ELEMENT",
                 what + " element " + std::to_string(deck.model.element_ids[e]) + ": " + problem,
                 expected);
  };
  auto node_id = [&](int k) { return std::to_string(deck.model.node_ids[nodes[k]]); };
  const std::string distinct =
      "expected 4 distinct corner nodes (triangles and collapsed quadrilaterals are not "
      "supported)";
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j) {
      if (nodes[i] != nodes[j]) continue;
      report("degenerate", "node " + node_id(i) + " appears twice", distinct);
      return;
    }
  }
  std::array<Eigen::Vector3d, 4> x;
  for (int k = 0; k < 4; ++k) x[k] = deck.model.coordinates.row(nodes[k]).transpose();
  const QuadShape shape = quad_shape(x);
  const Real length = shape.longest_edge;
  const Real small_area = QUAD_TOLERANCE * length * length;
  if (shape.shortest_edge <= QUAD_TOLERANCE * length) {
    const int k = shape.shortest_edge_start;
    report("degenerate",
           "nodes " + node_id(k) + " and " + node_id((k + 1) % 4) + " are at the same place",
           distinct);
  } else if (shape.area <= small_area) {
    report("degenerate",
           "area " + number_text(shape.area) + " with edges up to " + number_text(length),
           "expected 4 corner nodes in order around a quadrilateral of non-zero area");
  } else if (std::count_if(shape.corner.begin(), shape.corner.end(),
                           [&](Real c) { return c < -small_area; }) >= 2) {
    // Two corners turning against the others: the nodes zigzag across the element. (A single
    // one is a concave element, poor but usable: the solver judges element quality.)
    report("crossed", "seen along its normal, edges 1-2 and 3-4 or 2-3 and 4-1 cross",
           "expected 4 corner nodes in order around the quadrilateral");
  }
}

}  // namespace xpl::io

#include "contact/adjustment_pass.hpp"

#include <algorithm>
#include <cmath>

namespace xpl::contact {

namespace {

/// Corner measures of element e: hex: the 8 corner Jacobians det[e1 e2 e3] and their scaled
/// values; shell: the 4 corner area vectors along the element normal `normal`. Returns the
/// number of corners (0 for other elements).
int corner_measures(const ElementTopology& topology, Index e, const NodalVectors& x,
                    const Vec3& normal, Real* measure, Real* scaled) {
  const Index* en = topology.nodes.data() + topology.offsets[e];
  if (topology.kinds[e] == ElementKind::Hex) {
    for (int a = 0; a < 8; ++a) {
      const int ring = a < 4 ? 0 : 4;
      const int local = a - ring;
      // Bottom corners: next, previous, up; top corners: previous, next, down (both right
      // handed for a valid element).
      const int first = ring + (a < 4 ? (local + 1) % 4 : (local + 3) % 4);
      const int second = ring + (a < 4 ? (local + 3) % 4 : (local + 1) % 4);
      const int third = a < 4 ? a + 4 : a - 4;
      const Vec3 p = node_point(x, en[a]);
      const Vec3 e1 = node_point(x, en[first]) - p, e2 = node_point(x, en[second]) - p,
                 e3 = node_point(x, en[third]) - p;
      measure[a] = e1.dot(e2.cross(e3));
      const Real lengths = std::sqrt(e1.dot(e1) * e2.dot(e2) * e3.dot(e3));
      scaled[a] = lengths > 0.0 ? measure[a] / lengths : -1.0;
    }
    return 8;
  }
  if (topology.kinds[e] == ElementKind::Shell) {
    for (int a = 0; a < 4; ++a) {
      const Vec3 p = node_point(x, en[a]);
      const Vec3 e1 = node_point(x, en[(a + 1) % 4]) - p, e2 = node_point(x, en[(a + 3) % 4]) - p;
      measure[a] = normal.dot(e1.cross(e2));
      const Real lengths = std::sqrt(e1.dot(e1) * e2.dot(e2));
      scaled[a] = lengths > 0.0 ? measure[a] / lengths : -1.0;
    }
    return 4;
  }
  return 0;
}

Vec3 shell_normal(const ElementTopology& topology, Index e, const NodalVectors& x) {
  const Index* en = topology.nodes.data() + topology.offsets[e];
  const Vec3 n = (node_point(x, en[2]) - node_point(x, en[0]))
                     .cross(node_point(x, en[3]) - node_point(x, en[1]));
  const Real length = std::sqrt(n.dot(n));
  return length > 0.0 ? Vec3(n / length) : Vec3::Zero();
}

}  // namespace

const char* offset_reason_name(OffsetReason reason) {
  switch (reason) {
    case OffsetReason::Boundary:
      return "BC";
    case OffsetReason::Rigid:
      return "rigid";
    case OffsetReason::Pinched:
      return "pinched";
    case OffsetReason::Distortion:
      return "distortion";
    case OffsetReason::Conflict:
      return "conflict";
    case OffsetReason::LaterStep:
      return "later step";
    case OffsetReason::Import:
      return "import";
    case OffsetReason::Tie:
      return "tie";
  }
  return "conflict";
}

std::optional<OffsetReason> lock_reason(std::uint8_t lock, const Vec3& normal) {
  if ((lock & LOCK_RIGID) != 0) return OffsetReason::Rigid;
  if ((lock & LOCK_TIE) != 0) return OffsetReason::Tie;
  for (int c = 0; c < 3; ++c)
    if (((lock >> c) & 1u) != 0 && std::abs(normal[c]) > LOCK_COMPONENT)
      return OffsetReason::Boundary;
  return std::nullopt;
}

std::vector<Index> distorted_elements(const ElementTopology& topology, const NodalVectors& original,
                                      const NodalVectors& position,
                                      std::span<const char> node_moved, Real& quality_before,
                                      Real& quality_after) {
  std::vector<Index> refused;
  quality_before = quality_after = 1.0;
  for (Index e = 0; e < topology.element_count(); ++e) {
    const Index* en = topology.nodes.data() + topology.offsets[e];
    const Index count = topology.offsets[e + 1] - topology.offsets[e];
    bool touched = false;
    for (Index k = 0; k < count && !touched; ++k) touched = node_moved[en[k]] != 0;
    if (!touched) continue;
    // A shell's corner areas are measured along its own mean normal in each configuration:
    // rotating a shell element is strain free (an adjustment may tilt it a lot), while a corner
    // folding over its mean plane turns negative.
    const bool shell = topology.kinds[e] == ElementKind::Shell;
    const Vec3 normal_before = shell ? shell_normal(topology, e, original) : Vec3::Zero();
    const Vec3 normal_after = shell ? shell_normal(topology, e, position) : Vec3::Zero();
    Real before[8], after[8], scaled_before[8], scaled_after[8];
    const int corners =
        corner_measures(topology, e, original, normal_before, before, scaled_before);
    corner_measures(topology, e, position, normal_after, after, scaled_after);
    bool refuse = false;
    for (int a = 0; a < corners; ++a) {
      quality_before = std::min(quality_before, scaled_before[a]);
      quality_after = std::min(quality_after, scaled_after[a]);
      refuse = refuse || after[a] < MIN_CORNER_RATIO * before[a];
    }
    if (refuse) refused.push_back(e);
  }
  return refused;
}

AdjustmentOutcome run_adjustment(const ElementTopology& topology, const NodalVectors& original,
                                 NodalVectors& position, std::span<const Index> movable,
                                 int max_passes, AdjustmentMoves& moves) {
  AdjustmentOutcome out;
  for (int round = 0; round < MAX_ADJUSTMENT_ROUNDS; ++round) {
    if (round > 0) position = original;
    moves.begin_round(round);
    out.passes = 0;
    for (int pass = 0; pass < max_passes; ++pass) {
      if (!moves.pass(pass)) break;
      ++out.passes;
    }

    // Safety: no element corner may lose more than its allowed share of volume (area), or
    // invert.
    std::vector<char> node_moved(static_cast<std::size_t>(position.rows()), 0);
    out.moved = false;
    for (Index node : movable)
      if ((position.row(node) - original.row(node)).squaredNorm() > 0.0) {
        node_moved[node] = 1;
        out.moved = true;
      }
    const std::vector<Index> refused = distorted_elements(topology, original, position, node_moved,
                                                          out.quality_before, out.quality_after);
    if (refused.empty() || round + 1 == MAX_ADJUSTMENT_ROUNDS) break;
    for (Index e : refused) {
      out.refused_elements.push_back(e);
      for (Index k = topology.offsets[e]; k < topology.offsets[e + 1]; ++k)
        if (node_moved[topology.nodes[k]]) moves.hold(topology.nodes[k]);
    }
  }
  return out;
}

}  // namespace xpl::contact

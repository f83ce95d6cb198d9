// Sleeping slots of ContactEngine (contact_engine.hpp, file comment "Sleeping slots"): the
// clearance an awake search records, the motion path that wears it down, and the decision.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "contact/contact_engine.hpp"

namespace xpl::contact {

namespace {

/// A lower bound (m) of the distance from `p` (m) to the bilinear patch with corners `mid`
/// (m): the patch lies in the corners' box and in their slab along the unit normal of their
/// diagonals (every point is a convex combination of the corners); less a relative rounding
/// slack of 1e-9 of the sizes involved.
Real patch_distance_below(const Vec3 (&mid)[4], const Vec3& p) {
  Real out_sq = 0.0, scale = 0.0;
  for (int d = 0; d < 3; ++d) {
    const Real lo = std::min({mid[0][d], mid[1][d], mid[2][d], mid[3][d]});
    const Real hi = std::max({mid[0][d], mid[1][d], mid[2][d], mid[3][d]});
    const Real out = std::max({lo - p[d], p[d] - hi, 0.0});
    out_sq += out * out;
    scale = std::max({scale, std::abs(lo), std::abs(hi), std::abs(p[d])});
  }
  Real bound = std::sqrt(out_sq);
  const Vec3 n = (mid[2] - mid[0]).cross(mid[3] - mid[1]);
  const Real n_len = std::sqrt(n.dot(n));
  if (n_len > 0.0) {
    const Vec3 unit = n / n_len;
    Real lo = std::numeric_limits<Real>::infinity(), hi = -lo;
    for (int a = 0; a < 4; ++a) {
      const Real h = mid[a].dot(unit);
      lo = std::min(lo, h);
      hi = std::max(hi, h);
    }
    const Real height = p.dot(unit);
    bound = std::max(bound, std::max({lo - height, height - hi, 0.0}));
  }
  return bound - 1e-9 * (bound + scale);
}

}  // namespace

ContactEngine::~ContactEngine() {
  if (m_sleep_mode != SleepMode::Count && m_sleep_mode != SleepMode::Check) return;
  const SleepCounts& n = m_sleep_counts;
  std::fprintf(stderr,
               "xpl contact sleep: %lld slot searches, %lld asleep (%lld of them searched by the "
               "check, none touching); %lld updates, mean largest step motion %.3e m\n",
               n.searched, n.asleep, n.checked, n.updates,
               n.updates > 0 ? n.path / static_cast<double>(n.updates) : 0.0);
}

void ContactEngine::init_sleep() {
  const char* value = std::getenv("XPL_CONTACT_SLEEP");
  m_sleep_mode = SleepMode::On;
  if (value != nullptr && std::strcmp(value, "off") == 0) m_sleep_mode = SleepMode::Off;
  if (value != nullptr && std::strcmp(value, "count") == 0) m_sleep_mode = SleepMode::Count;
  if (value != nullptr && std::strcmp(value, "check") == 0) m_sleep_mode = SleepMode::Check;
  forget_sleep();
}

void ContactEngine::forget_sleep() {
  const auto n = static_cast<std::size_t>(m_domain.slaves().size());
  m_sleep_clear.assign(n, -std::numeric_limits<Real>::infinity());
  m_sleep_path.assign(n, 0.0);
  m_asleep.assign(n, 0);
  m_path = 0.0;
}

void ContactEngine::advance_sleep_path(bool rebuilt, const NodalVectors& position) {
  const bool decided = m_step_decision >= 0.0 && m_shared_pass;
  const Real step_sq = rebuilt ? 0.0 : decided ? m_step_decision : m_broad.step_motion_sq(position);
  m_step_decision = -1.0;
  ++m_sleep_counts.updates;
  m_sleep_counts.path += std::sqrt(step_sq);
  if (rebuilt) {
    forget_sleep();
    return;
  }
  m_path += std::sqrt(step_sq);
}

bool ContactEngine::sleeps(Index s) const {
  const Real clear = m_sleep_clear[s];
  return clear > 0.0 && clear - 2.0 * (m_path - m_sleep_path[s]) * (1.0 + 1e-9) > 0.0;
}

void ContactEngine::record_sleep(const SlaveView& v, const SlaveTouch& best,
                                 const NodalVectors& position,
                                 std::span<const Real> node_thickness) {
  const Index s = v.slot;
  m_sleep_clear[s] = -std::numeric_limits<Real>::infinity();
  if (m_sleep_mode == SleepMode::Off || m_user_stiffness) return;
  const ContactConstraint& c = m_constraints[s];
  if (v.held != nullptr || v.continuing != NO_INDEX || c.offset_permanent ||
      c.status == ContactStatus::Closed || m_second[s].status == ContactStatus::Closed)
    return;
  if (!m_interference.empty() && m_interference[s].amount > 0.0) return;
  if ((best.face != NO_INDEX && !(best.gap > 0.0)) || m_second_touch[s].face != NO_INDEX ||
      m_lost_depth[s] != 0.0 || m_passed_depth[s] != 0.0 || m_behind_depth[s] != 0.0)
    return;
  const std::vector<ContactFace>& faces = m_domain.faces();
  const Real h_n = v.half_t;
  Real least = std::numeric_limits<Real>::infinity();
  Real reach_least = std::numeric_limits<Real>::infinity();
  const auto face_clearance = [&](Index f) {
    const ContactFace& face = faces[f];
    Vec3 mid[4];
    Real round = 0.0, t_sum = 0.0;
    for (int a = 0; a < 4; ++a) {
      mid[a] = node_point(position, face.nodes[a]);
      if (face.shell) {
        const Real t = node_thickness_of(node_thickness, face.nodes[a]);
        t_sum += t;
        round = std::max(round, 0.5 * t);
      }
    }
    const Real depth = face.shell ? DEPTH_LIMIT_FRACTION * 0.25 * t_sum : m_domain.face_depth(f);
    Real near;  // how near the offset surface's closest point a penetrating touch lies
    if (v.double_sided && face.shell) {
      near = std::max(h_n, depth);  // interior; beside the edges the round edge (h_n + round)
    } else {
      const Real l = depth + h_n;
      near = std::max(h_n, std::sqrt(l * l + (l - h_n) * (l - h_n)));
    }
    const Real reach = near + round;
    reach_least = std::min(reach_least, reach);
    least = std::min(least, patch_distance_below(mid, v.point) - reach);
  };
  // The nearest touch first: a slot near its faces stops at once.
  if (best.face != NO_INDEX) face_clearance(best.face);
  for (Index f : listed_faces(s)) {
    if (!(least > 0.0)) return;
    if (f != best.face) face_clearance(f);
  }
  const Real clear = least - SLEEP_GUARD * reach_least;
  if (!(clear > 0.0)) return;
  m_sleep_clear[s] = clear;
  m_sleep_path[s] = m_path;
}

void ContactEngine::put_to_sleep(Index s, bool searched) {
  if (searched) {
    const SlaveTouch& t = m_touch[s];
    const bool touched = (t.face != NO_INDEX && !(t.gap > 0.0)) ||
                         m_second_touch[s].face != NO_INDEX || m_lost_depth[s] != 0.0 ||
                         m_passed_depth[s] != 0.0 || m_behind_depth[s] != 0.0;
    if (touched) {
      throw std::logic_error("contact: sleeping slot " + std::to_string(s) + " (node " +
                             std::to_string(m_domain.slaves().nodes()[s]) +
                             ") would have touched face " + std::to_string(t.face) + " (gap " +
                             std::to_string(t.gap) + " m)");
    }
  }
  m_touch[s] = SlaveTouch{};
  m_second_touch[s] = SlaveTouch{};
  m_lost_depth[s] = 0.0;
  m_passed_depth[s] = 0.0;
  m_behind_depth[s] = 0.0;
  if (m_warm[s].count > 0) m_warm[s] = WarmStarts{};
}

}  // namespace xpl::contact

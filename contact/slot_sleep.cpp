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

#include "contact/slot_sleep.hpp"

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

SleepMode sleep_mode_from_environment() {
  const char* value = std::getenv("XPL_CONTACT_SLEEP");
  if (value == nullptr || *value == '\0') return SleepMode::On;  // unset or empty: on
  const std::string v = value;
  if (v == "on") return SleepMode::On;
  if (v == "off") return SleepMode::Off;
  if (v == "count") return SleepMode::Count;
  if (v == "check") return SleepMode::Check;
  throw std::invalid_argument("XPL_CONTACT_SLEEP=" + v +
                              ": unknown value; expected on, off, count or check (or unset)");
}

SlotSleep::SlotSleep(Index n_slave) {
  mode = sleep_mode_from_environment();
  clear.assign(static_cast<std::size_t>(n_slave), 0.0);
  path_then.assign(static_cast<std::size_t>(n_slave), 0.0);
  asleep.assign(static_cast<std::size_t>(n_slave), 0);
  forget();
}

SlotSleep::~SlotSleep() {
  if (mode != SleepMode::Count && mode != SleepMode::Check) return;
  std::fprintf(stderr,
               "xpl contact sleep: %lld slot searches, %lld asleep (%lld of them searched by the "
               "check, none touching); %lld updates, mean largest step motion %.3e m\n",
               counts.searched, counts.asleep, counts.checked, counts.updates,
               counts.updates > 0 ? counts.path / static_cast<double>(counts.updates) : 0.0);
}

void SlotSleep::forget() {
  std::fill(clear.begin(), clear.end(), -std::numeric_limits<Real>::infinity());
  std::fill(asleep.begin(), asleep.end(), 0);
  path = 0.0;
}

void SlotSleep::advance(bool rebuilt, Real step_sq) {
  ++counts.updates;
  counts.path += std::sqrt(step_sq);
  if (rebuilt)
    forget();
  else
    path += std::sqrt(step_sq);
}

Real ContactEngine::measure_motions(const NodalVectors& position, std::span<const char> node_mask,
                                    Real& step_sq) {
  return m_broad.motions_sq(position, node_mask, step_sq);
}

void ContactEngine::record_sleep(const SlaveView& v, const SlaveTouch& best,
                                 const SlaveTouch& second, const NodalVectors& position,
                                 std::span<const Real> node_thickness) {
  const Index s = v.slot;
  m_sleep.clear[s] = -std::numeric_limits<Real>::infinity();
  if (m_sleep.mode == SleepMode::Off || m_user_stiffness) return;
  const ContactConstraint& c = m_constraints[s];
  if (v.held != nullptr || v.continuing != NO_INDEX || c.offset_permanent ||
      c.status == ContactStatus::Closed || m_second[s].status == ContactStatus::Closed)
    return;
  if (!m_interference.empty() && m_interference[s].amount > 0.0) return;
  if ((best.face != NO_INDEX && !(best.gap > 0.0)) || second.face != NO_INDEX ||
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
  m_sleep.clear[s] = clear;
  m_sleep.path_then[s] = m_sleep.path;
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

// Stages 2 and 3 of the clearance pass: the adjustment passes that move the nodes to their
// targets, and the permanent offsets (or interference ramps) for what remains.
#include <algorithm>
#include <cmath>
#include <utility>

#include "common/parallel_error.hpp"
#include "contact/clearance_pass.hpp"

namespace xpl::contact::clearance {

namespace {

/// The clearance pass's moves: every free record off its target moves along the normal of
/// its face by w·(h* − h), until the largest residual stops halving.
class ClearanceMoves final : public AdjustmentMoves {
 public:
  explicit ClearanceMoves(Clearance& pass)
      : m(pass), m_moving(pass.records.size(), 0), m_move(3 * pass.records.size(), 0.0) {}

  void begin_round(int /*round*/) override { m_worst_of_pass.clear(); }

  bool pass(int pass) override {
    const auto n_records = static_cast<Index>(m.records.size());
    bool any = false;
    Real worst = 0.0;
    ParallelErrors errors;
#pragma omp parallel for schedule(static) reduction(|| : any) reduction(max : worst)
    for (Index k = 0; k < n_records; ++k)
      errors.guard(ParallelSite::Clearance, k, [&] {
        const Record& r = m.records[k];
        m_moving[k] = 0;
        if (!r.adjust || r.held) return;
        Vec3 normal;
        const Real delta = m.residual(r, normal);
        if (std::abs(delta) <= r.tolerance) return;
        m_moving[k] = 1;
        any = true;
        worst = std::max(worst, std::abs(delta));
        for (int d = 0; d < 3; ++d) m_move[3 * k + d] = delta * normal[d];
      });
    errors.rethrow_if_any();
    if (!any) return false;
    m_worst_of_pass.push_back(worst);
    if (pass >= 1 && worst > CLEARANCE_CONVERGENCE_RATIO * m_worst_of_pass[pass - 1]) return false;
    for (Index k = 0; k < n_records; ++k) {
      if (!m_moving[k]) continue;
      const Record& r = m.records[k];
      Real w = 1.0;
      for (Index c : m.faces[r.face].nodes) {
        const Index cs = m.slaves.slot(c);
        if (cs != NO_INDEX && m.record_of[cs] != NO_INDEX && m_moving[m.record_of[cs]]) w = 0.5;
      }
      const std::uint8_t lock = m.node_lock.empty() ? 0 : m.node_lock[r.node];
      for (int d = 0; d < 3; ++d)
        if (((lock >> d) & 1u) == 0) m.position(r.node, d) += w * m_move[3 * k + d];
    }
    return true;
  }

  void hold(Index node) override {
    const Index s = m.slaves.slot(node);
    if (s == NO_INDEX || m.record_of[s] == NO_INDEX) return;
    Record& r = m.records[m.record_of[s]];
    if (r.held) return;
    r.held = true;
    r.reason = OffsetReason::Distortion;
  }

 private:
  Clearance& m;
  std::vector<char> m_moving;
  std::vector<Real> m_move;
  std::vector<Real> m_worst_of_pass;
};

}  // namespace

/// 2. Adjustment passes (Jacobi) with the distortion check, then the report of every record.
void Clearance::adjust(const ElementTopology& topology, ClearanceReport& report) {
  const bool any_adjust = std::any_of(records.begin(), records.end(),
                                      [](const Record& r) { return r.adjust && !r.held; });
  if (!any_adjust) {
    for (const Record& r : records)
      report.nodes.push_back(
          {r.node, r.view, r.face, r.clearance, r.gap_before, 0.0, Vec3::Zero(), 0.0, r.reason});
    return;
  }
  const NodalVectors original = position;
  std::vector<Index> movable;
  for (const Record& r : records) movable.push_back(r.node);
  ClearanceMoves moves(*this);
  AdjustmentOutcome outcome =
      run_adjustment(topology, original, position, movable, MAX_ADJUSTMENT_PASSES, moves);
  report.passes = outcome.passes;
  report.refused_elements = std::move(outcome.refused_elements);
  report.quality_before = outcome.quality_before;
  report.quality_after = outcome.quality_after;
  for (const Record& r : records) {
    const Vec3 delta = node_point(position, r.node) - node_point(original, r.node);
    const Real distance = delta.norm();
    const Vec3 direction = distance > 0.0 ? Vec3(delta / distance) : Vec3::Zero();
    report.nodes.push_back(
        {r.node, r.view, r.face, r.clearance, r.gap_before, distance, direction, 0.0, r.reason});
  }
}

/// 3. Permanent offsets: the violation that remains, along the node's side; the search is
/// widened for offsets that move a contact surface out.
void Clearance::store_offsets(ClearanceReport& report, std::span<const ClearanceView> views) {
  Real widest = 0.0;
  for (Index k = 0; k < static_cast<Index>(records.size()); ++k) {
    const Record& r = records[k];
    Vec3 normal;
    const Real delta = residual(r, normal);
    ContactConstraint& constraint = engine.constraints()[r.slot];
    if (r.interference) {
      // The overclosure reached, d = σ·δ − target gap (δ = h* − h); what the ramp removes and
      // what stays (file comment).
      const Real reached = r.sigma * delta - r.target_gap;
      const bool at_target = std::abs(delta) <= r.tolerance;
      const Real amount =
          at_target || std::isnan(views[r.view].interference_distance) ? reached : -r.target_gap;
      const Real base = reached - amount;
      engine.set_interference(r.slot, std::max(amount, 0.0), base, views[r.view].ramp_time);
      report.nodes[k].interference = std::max(amount, 0.0);
      report.nodes[k].offset = base;
      if (base != 0.0 && r.adjust && !r.held) report.nodes[k].reason = OffsetReason::Conflict;
      widest = std::max(widest, -base);
      continue;
    }
    if (std::abs(delta) <= r.tolerance) {
      constraint.offset = 0.0;
      constraint.offset_permanent = false;
      continue;
    }
    const Real d0 = r.sigma * delta;
    constraint.offset = d0;
    constraint.offset_permanent = true;
    report.nodes[k].offset = d0;
    if (r.adjust && !r.held) report.nodes[k].reason = OffsetReason::Conflict;
    widest = std::max(widest, -d0);
  }
  engine.widen_search(widest);
  engine.probe(position, node_thickness);
}

}  // namespace xpl::contact::clearance

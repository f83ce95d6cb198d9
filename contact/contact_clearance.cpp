#include "contact/contact_clearance.hpp"

#include <chrono>

#include "contact/clearance_pass.hpp"

namespace xpl::contact {

namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

const char* clearance_skip_name(ClearanceSkip why) {
  switch (why) {
    case ClearanceSkip::NoValue:
      return "no clearance value at the node or at every corner of its master face";
    case ClearanceSkip::PerimeterEdge:
      return "closest point on a perimeter edge of the master surface";
    case ClearanceSkip::WrongSide:
      return "ADJUST=NO and the node lies on the other side of the shell";
    case ClearanceSkip::NotInDomain:
      return "the contact domain does not let it touch the master surface";
    case ClearanceSkip::Repeated:
      return "an earlier assignment already gave it a clearance";
  }
  return "?";
}

ClearanceReport apply_clearances(ContactEngine& engine, const ElementTopology& topology,
                                 NodalVectors& position, std::span<const Real> node_thickness,
                                 std::span<const std::uint8_t> node_lock,
                                 std::span<const ClearanceView> views, bool adjust_allowed) {
  const auto start = Clock::now();
  ClearanceReport report;
  const Index n_slave = engine.domain().slaves().size();
  report.handled.assign(static_cast<std::size_t>(n_slave), 0);
  if (views.empty() || n_slave == 0) return report;
  clearance::Clearance pass(engine, position, node_thickness, node_lock, adjust_allowed);
  for (Index v = 0; v < static_cast<Index>(views.size()); ++v)
    pass.collect_view(views[v], v, report);
  pass.adjust(topology, report);
  pass.store_offsets(report, views);
  report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return report;
}

}  // namespace xpl::contact

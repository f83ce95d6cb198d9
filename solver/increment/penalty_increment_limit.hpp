#pragma once
/// \file The stable increment with a deck's own penalty stiffness: where the springs of a
/// LINEAR pressure–overclosure slope are stiffer than the default penalty would be at the
/// element increment, the increment is shortened for the increments where they act, and the
/// spans where contact governs are reported (.msg: which interaction, by how much; .sta: the
/// critical contact node).
///
/// Rule. The elements allow Δt_e = s·φ·Δt_raw (scale factor s, safety φ, element estimate
/// Δt_raw, so their highest frequency is ω_e = 2/Δt_raw and ω_eΔt_e = 2sφ). The default penalty
/// adds ω_c²Δt_e² = B = PENALTY_INCREMENT_BUDGET on top (contact/penalty_increment.hpp). A
/// user's spring of frequency bound ω_c (the stiffest node, both views and the corner shares
/// summed) gets the same total: frequencies add in squares, so
///   Δt_c = s·√((2φ)² + B) / √(ω_e² + ω_c²),
/// which equals Δt_e exactly when ω_c²Δt_e² = B·s² and is below it only for stiffer springs.
/// Where the springs dominate (ω_c² > 1.1 ω_e²) the spring alone is held to
/// ω_cΔt ≤ s·√PENALTY_ALONE_BUDGET instead: Δt_c = s·min(√((2φ)² + B)/√(ω_e² + ω_c²), √2/ω_c).
/// Δt = min(Δt_e, Δt_c); a step with a fixed increment keeps it. The stiffest node of a span
/// is held for HOLD_INCREMENTS after its springs stop acting: a node that rebounds off a stiff
/// spring and touches again within an element increment (chatter at a bar end) would
/// otherwise meet it at the long increment.

#include <string>

#include "contact/penalty_increment.hpp"
#include "solver/increment/increment_control.hpp"
#include "solver/model/model.hpp"
#include "solver/output/output_sink.hpp"

namespace xpl {

/// Holds and reports the penalty limit of one run; the rule itself is the increment control's
/// (contact_increment, increment_control.hpp).
class PenaltyIncrementLimit {
 public:
  /// Increments a span's stiffest node keeps governing after its springs opened.
  static constexpr int HOLD_INCREMENTS = 50;

  /// `model`, `sink` and `control` must outlive the limit.
  PenaltyIncrementLimit(const Model& model, OutputSink& sink, const IncrementControl& control)
      : m_model(model), m_sink(sink), m_control(control) {}

  /// The increment the user's springs allow against the elements' increment `elements` in
  /// `step`, for the stiffest node `limit` (or the one held); +inf when they do not govern.
  /// `time` (s) and `increment` say where, for the reports.
  ContactIncrement apply(const contact::PenaltyLimit& limit, const ElementIncrement& elements,
                         int step, Real time, long increment);
  /// Deck id of the contact node that governs the increment last returned, 0 when none.
  ExternalId critical_node() const { return m_governing ? m_critical_node : 0; }
  /// Ends a span in which contact governs (end of a step or of the run): its .msg summary.
  void end_span();

 private:
  /// The interaction's name and law for the messages.
  std::string interaction_text(Index interaction) const;

  const Model& m_model;
  OutputSink& m_sink;
  const IncrementControl& m_control;
  bool m_governing = false;
  contact::PenaltyLimit m_held;  ///< the stiffest node since the span began
  int m_hold = 0;                ///< increments the held node still governs
  ExternalId m_critical_node = 0;
  // The span in which contact governs: where it began, its shortest increment and where.
  int m_step = 0;
  long m_increments = 0;
  Real m_end_time = 0.0;
  Real m_smallest_ratio = 1.0;
  Real m_smallest_dt = 0.0;
  ExternalId m_smallest_node = 0;
  Index m_smallest_interaction = NO_INDEX;
};

}  // namespace xpl

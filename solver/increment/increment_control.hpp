#pragma once
/// \file The one owner of the stable increment: it takes what limits the increment (the
/// element-by-element estimate with its critical element, the global estimate's bound on it,
/// the contact springs' limit) and the step's IncrementControls, and returns the increment with
/// the cause that governs it and the critical element or node. The .sta file shows the cause
/// on every line, the .msg file at the start of each step and, counted, at its end.
///
/// The sequence, each step of it strict (a tie keeps the earlier cause):
///   raw   = Δt_e · r              r < 1: the global estimate governs (global_increment.hpp)
///   Δt_s  = raw · s · φ           scale factor s (`*DYNAMIC, EXPLICIT`), safety φ
///   Δt_s  = min(Δt_s, Δt_max)     a step's maximum increment
///   Δt_s  = Δt_fixed              DIRECT USER CONTROL replaces all of the above
///   Δt    = min(Δt_s, Δt_c)       a deck's own penalty stiffness (contact_increment)
///   Δt    = what is left of the step, when Δt reaches past it or stops a sliver short
/// The contact springs are tied to Δt_s (not to Δt: a short last increment must not stiffen
/// them). A run whose increment falls below the floor (increment_floor) stops.

#include <limits>
#include <string>

#include "common/types.hpp"
#include "solver/model/model.hpp"
#include "solver/model/state.hpp"
#include "solver/output/output_sink.hpp"

namespace xpl {

/// What governs an increment.
enum class IncrementCause {
  Element,  ///< the element-by-element estimate
  Global,   ///< the global estimate (ω_max of the hexes) bounds the element estimate
  Maximum,  ///< the step's maximum increment
  Fixed,    ///< the step's fixed increment (DIRECT USER CONTROL)
  Contact,  ///< the springs of a deck's own penalty stiffness
  StepEnd,  ///< shortened or stretched to land on the end of the step
};

/// One word for the .sta column: "element", "global", "maximum", "fixed", "contact", "step-end".
const char* cause_name(IncrementCause cause);
/// A phrase for the .msg file: "the element-by-element estimate", ...
const char* cause_text(IncrementCause cause);

/// The elements' part of one force evaluation.
struct ElementEstimate {
  Real stable_dt = std::numeric_limits<Real>::infinity();  ///< Δt_e, s; +inf without elements
  Index critical_element = NO_INDEX;  ///< model index of the element that sets Δt_e
  Real global_ratio = 1.0;            ///< r ≤ 1 the global estimate puts on Δt_e
};

/// The increment the elements allow in a step, before contact and the end of the step.
struct ElementIncrement {
  Real raw_dt = std::numeric_limits<Real>::infinity();  ///< Δt_e · r, s
  Real dt = std::numeric_limits<Real>::infinity();      ///< Δt_s, s
  IncrementCause cause = IncrementCause::Element;       ///< element, global, maximum or fixed
  Index critical_element = NO_INDEX;
  /// The increment the contact penalty is tied to: Δt_s, or `fallback` (s) when it is not
  /// finite (a model without elements).
  Real penalty_dt(Real fallback) const;
};

/// The contact springs' part: the increment a deck's own penalty allows (+inf: none) and the
/// node where it is reached.
struct ContactIncrement {
  Real dt = std::numeric_limits<Real>::infinity();  ///< Δt_c, s
  Index node = NO_INDEX;                            ///< model index, NO_INDEX: none
};

/// The increment chosen and why.
struct IncrementDecision {
  Real dt = 0.0;  ///< s
  IncrementCause cause = IncrementCause::Element;
  Index critical_element = NO_INDEX;  ///< the elements' critical element (always kept)
  Index critical_node = NO_INDEX;     ///< the contact node when contact governs
};

/// Δt_s of `controls` for `estimate` with the safety factor `safety`.
ElementIncrement element_increment(const IncrementControls& controls, Real safety,
                                   const ElementEstimate& estimate);
/// The increment from the elements' and the contact springs' and `remaining` (s) of the step:
/// the shorter of the two, or `remaining` when it lies within reach or a sliver beyond.
IncrementDecision choose_increment(const ElementIncrement& elements,
                                   const ContactIncrement& contact, Real remaining);
/// The increment at the start of a later step: `carried` (the last increment of the step
/// before), shortened to the step's `period` (s) when that is shorter.
IncrementDecision carry_increment(const IncrementDecision& carried, Real period);
/// Δt_c of a spring frequency bound `omega_sq` (1/s²) with the element estimate `raw_dt` and
/// the elements' increment `dt_elements` (s) at scale factor `scale`
/// (penalty_increment_limit.hpp gives the rule); +inf when omega_sq ≤ 0.
Real contact_increment(Real raw_dt, Real dt_elements, Real scale, Real omega_sq);
/// The smallest increment a run may take: `floor_ratio` times the first increment `dt_first`,
/// at least DT_TRANSIT_FLOOR times the model's wave transit time `transit_time` (s).
Real increment_floor(Real floor_ratio, Real dt_first, Real transit_time);

/// Increments below this fraction of the model's wave transit time stop the run, whatever
/// the first increment was (an initial velocity of 1e12 m/s makes even that one zero).
inline constexpr Real DT_TRANSIT_FLOOR = 1e-9;

/// The increment control of one run: the policy above with the run's safety factor, its floor,
/// and the reports of which cause governs.
class IncrementControl {
 public:
  /// `model` and `sink` must outlive the control; `safety` is SolverOptions::dt_safety,
  /// `floor_ratio` SolverOptions::dt_floor_ratio, `transit_time` the model's wave transit
  /// time (EnergyCheck::transit_time), s.
  IncrementControl(const Model& model, OutputSink& sink, Real safety, Real floor_ratio,
                   Real transit_time);

  /// Δt_s of `step` for `estimate`.
  ElementIncrement elements(int step, const ElementEstimate& estimate) const {
    return element_increment(m_model.steps[step].increment, m_safety, estimate);
  }
  /// Δt_c of `step` for the spring bound `omega_sq` (1/s²) at `node`, against `elements`; +inf
  /// in a step with a fixed increment.
  ContactIncrement contact(int step, const ElementIncrement& elements, Real omega_sq,
                           Index node) const;

  /// The first increment of the run (s): the floor is measured against it.
  void start(Real dt_first) { m_dt_first = dt_first; }
  /// Throws SolverError when the increment `dt_next` (s) about to be taken in `state`'s step
  /// has fallen below the floor (a fixed increment is never checked); `critical_id` is the
  /// deck id of the critical element, for the message.
  void check_floor(const State& state, Real dt_next, ExternalId critical_id) const;

  /// The .msg note of the increment that starts `step`.
  void report_start(int step, const IncrementDecision& first);
  /// Counts one increment taken under `decision`.
  void count(const IncrementDecision& decision) { ++m_counts[static_cast<int>(decision.cause)]; }
  /// The .msg note of the increments of `step` by cause; the counts start again.
  void report_step(int step);

 private:
  /// "element 17", "contact node 5" or "" for the .msg notes.
  std::string critical_text(const IncrementDecision& decision) const;

  static constexpr int CAUSES = 6;
  const Model& m_model;
  OutputSink& m_sink;
  Real m_safety;
  Real m_floor_ratio;
  Real m_transit_time;
  Real m_dt_first = 0.0;       ///< s
  long m_counts[CAUSES] = {};  ///< increments of the step by cause
};

}  // namespace xpl

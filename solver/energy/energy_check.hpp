#pragma once
/// \file The health check of the time loop, from the first increment of every step on:
/// collapsed elements, non-finite energies, a node moving farther than the whole model in one
/// increment and a drifting energy balance (a collapsing stable increment is the increment
/// control's floor, solver/increment/increment_control.hpp). A drift of ETOTAL
/// above 1 % of the energy scale is warned of once; above the run's limit
/// (SolverOptions::energy_limit, `xpl run --energy-limit`) and on every other failure the run
/// stops with a SolverError. "Completed" therefore means: a finite state, the balance checked
/// at every increment, the drift within the limit (R3).

#include <vector>

#include "common/types.hpp"
#include "solver/forces/element_set.hpp"
#include "solver/model/model.hpp"
#include "solver/model/state.hpp"
#include "solver/output/output_sink.hpp"

namespace xpl {

/// ETOTAL drift (as a fraction of the largest energy) above which .msg and .sta warn, once.
inline constexpr Real ENERGY_WARNING_FRACTION = 0.01;
/// The smallest energy scale of the balance is that of the whole model moving at this
/// fraction of its fastest wave speed, ½ M (ROUND_OFF_MOTION c_d)²: a model at rest, or moved
/// by round-off alone (energies of 1e-44 J at the start of a step in examples/overclosure's
/// pinched), is not measured against nothing.
inline constexpr Real ROUND_OFF_MOTION = 1e-10;

/// |ALLKD| above this multiple of the energy put in (EnergyCheck::input), in two checks in a row
/// and growing, fails the run. A stable mode of frequency ω keeps the energy central
/// differences conserve, E = (1 − r) × its largest strain energy with r = (ωΔt/2)², and holds
/// |ALLKD| = r × its strain energy, so |ALLKD| ≤ r/(1 − r) × E ≤ r/(1 − r) × the input: 4.3 for
/// an element at the safety factor 0.9 (ωΔt = 1.8; 5.3 measured on a one-element C3D8R
/// benchmark), 14 with a default contact spring on top (ω²Δt² = 3.74). 20 is ωΔt = 1.95.
inline constexpr Real DEFECT_INPUT_FACTOR = 20.0;

/// The largest ETOTAL drift of a run: where it was and the energy that moved most then.
struct EnergyDrift {
  Real fraction = 0.0;      ///< |ETOTAL − ETOTAL_0| / energy scale
  Real drift = 0.0;         ///< ETOTAL − ETOTAL_0, J
  Real largest = 0.0;       ///< the energy scale then (EnergyCheck::scale), J
  Real time = 0.0;          ///< total time, s
  long increment = 0;       ///< increment number
  const char* mover = "";   ///< the term of the balance that changed most ("ALLKE")
  Real mover_change = 0.0;  ///< its change since the reference, J
};

/// Watches the energy balance ETOTAL of a run.
class EnergyCheck {
 public:
  /// `model` must outlive the check; an ETOTAL drift above `energy_limit` (a fraction of the
  /// energy scale; SolverOptions::energy_limit) stops the run.
  EnergyCheck(const Model& model, Real energy_limit);

  /// The reference of the balance: ETOTAL of the state after the first update (J) and its
  /// energies as the first energy scale.
  void start(const State& state);
  /// Throws SolverError if the increment just taken went wrong: an element failed in
  /// `totals`, an energy is not finite, a free node moved at `largest_speed` (m/s, the
  /// largest |v(n+½)| component) farther than the model's extent in the increment `dt_next`
  /// (s) about to be taken, or ETOTAL drifted beyond the limit. Warns
  /// `sink` (.msg and .sta) once when the drift first passes ENERGY_WARNING_FRACTION.
  /// `critical_id` is the deck id of the element that limits the increment (for the
  /// message).
  void check(const State& state, const ElementTotals& totals, Real dt_next, Real largest_speed,
             ExternalId critical_id, OutputSink& sink);

  /// The largest drift seen so far (fraction 0 before the first check).
  const EnergyDrift& largest_drift() const { return m_largest; }
  /// The energy scale of the balance so far: the largest magnitude any energy of the model
  /// (ALLKE, ALLSE, ALLPD, ALLAE, ALLIE, ALLVD, ALLWK, ALLFD, ALLPW) has had since t = 0, the
  /// initial energies included, and at least ½ M (ROUND_OFF_MOTION c_d)², J.
  Real scale() const { return m_max_energy; }
  /// The model's wave transit time: its largest extent over the fastest dilatational wave
  /// speed of its materials, s (0 when it has no elastic material).
  Real transit_time() const { return m_transit_time; }
  /// The energy put into the model so far: the magnitudes of the initial energies (ALLKD
  /// left out), plus the largest change of ALLWK and the largest energy the contact penalties
  /// have given to the nodes (a fall of ALLPW) since t = 0, or the largest ALLKE so far when
  /// that is more (the work of prescribed motion is booked an increment late), and at least
  /// the round-off floor of scale(), J. Unlike scale() it does not grow with an instability:
  /// central differences go unstable through ωΔt = 2, where a mode changes sign every
  /// increment, so it builds strain energy (ALLSE) and ALLKD while the whole-step velocities
  /// v(n) = ½ (v(n−½) + v(n+½)) of ALLKE nearly cancel; the work done on the model does not grow.
  Real input() const { return m_input; }

 private:
  /// The drift of `state` against the reference, with the term that moved most.
  EnergyDrift drift_of(const State& state) const;
  /// Raises the energy scale to the magnitudes of the terms of `e`.
  void widen_scale(const Energies& e);
  /// Raises input() to the work, the contact release and the ALLKE of `e`.
  void widen_input(const Energies& e);
  /// Throws SolverError naming the fastest node of `state` when a node moved farther than the
  /// model's extent in one increment `dt` (s).
  void check_speed(const State& state, Real dt, Real largest_speed, ExternalId critical_id) const;

  const Model& m_model;
  Real m_energy_limit;
  Real m_transit_time = 0.0;      ///< s
  Real m_extent = 0.0;            ///< diagonal of the model's bounding box at t = 0, m
  Real m_wave_speed = 0.0;        ///< fastest dilatational wave speed, m/s
  Real m_max_energy = 0.0;        ///< the energy scale (scale()), J
  bool m_defect_beyond = false;   ///< |ALLKD| was beyond the scale at the last check
  Real m_last_defect = 0.0;       ///< |ALLKD| at the last check, J
  bool m_defect_created = false;  ///< |ALLKD| was beyond DEFECT_INPUT_FACTOR × input() then
  Real m_input_initial = 0.0;     ///< the initial part of input() and its floor, J
  Real m_input = 0.0;             ///< input(), J
  Real m_largest_work = 0.0;      ///< largest |ALLWK − ALLWK(0)| so far, J
  Real m_largest_release = 0.0;   ///< largest ALLPW(0) − ALLPW so far, J
  Real m_largest_kinetic = 0.0;   ///< largest ALLKE so far, J
  Real m_initial_work = 0.0;      ///< ALLWK after the first update, J
  Real m_initial_contact = 0.0;   ///< ALLPW after the first update, J
  Real m_initial_total = 0.0;     ///< ETOTAL after the first update, J
  std::vector<Real> m_initial;    ///< each term of the balance then (ENERGIES order), J
  bool m_warned = false;          ///< the 1 % warning has been given
  EnergyDrift m_largest;
};

/// "2.3 % of the largest energy 1.5 J at t = 3e-05 s (increment 120); ALLKE moved most
/// (-0.8 J)": the text of a drift for messages.
std::string describe(const EnergyDrift& drift);

}  // namespace xpl

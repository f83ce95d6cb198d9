#pragma once
/// \file The contact part of the run's health check (issue 20, item 4): energy that the
/// penalty springs put into the model.
///
/// ETOTAL does not see it. ALLPW is the work the contact forces have taken from the nodes,
/// and it sits inside ETOTAL, so when a spring gives back more than it took (a stiffness too
/// high for the increment, chatter) the kinetic energy grows and ALLPW falls by the same
/// amount: ETOTAL stays balanced while the model gains energy. What exposes it is the energy
/// the closed springs actually hold, S = Σ ½ k (d − d0)² (plus the friction stick springs):
/// a healthy run has ALLPW ≈ S (≈ 0 after a rebound), and the energy created by contact is
/// C = S − ALLPW.

#include <string>

#include "common/types.hpp"
#include "solver/model/state.hpp"

namespace xpl {

/// C above this share of the energy scale gives one warning in the .msg: clear of the ±4 %
/// of ALLKE(0) that the default penalty's onset and release stepping leaves in ALLPW after
/// a rebound on the coarsest two-body decks (benchmarks/RESULTS.md, stress test).
inline constexpr Real CONTACT_CREATION_WARNING = 0.05;
/// C above this share of the energy scale stops the run, as a lost energy balance does
/// (the watchdog's 10 % limit on ETOTAL drift).
inline constexpr Real CONTACT_CREATION_LIMIT = 0.10;

/// Increments at the start of each step before C is watched; C is measured from its value
/// then. Deep overclosures left to the penalty ("ignored", C4) are pushed out in the first
/// increments with the release error of a spring that opens within one increment (energy
/// the model gains, a known input of such a deck, reported by the overclosure pass); a
/// stepping instability keeps creating energy and is caught after it.
inline constexpr long CONTACT_CHECK_WARMUP = 10;

/// Watches the energy created by contact, C = stored spring energy − ALLPW, from the end of
/// each step's warm-up.
class ContactEnergyCheck {
 public:
  /// A step starts at increment `increment`: C is measured again from the end of its warm-up.
  void begin_step(long increment) {
    m_step_first_increment = increment;
    m_baseline_pending = true;
  }
  /// After an increment with the state's energies and the springs' stored energy `stored`
  /// (J, ContactStage::stored_energy): throws SolverError when C exceeds
  /// CONTACT_CREATION_LIMIT × the energy scale (the running maximum of ALLKE, ALLIE, |ALLWK|
  /// and the stored energy), naming `critical_id` (deck id of the element that limits the
  /// increment) as EnergyCheck does. Returns the text of a warning the first time C exceeds
  /// CONTACT_CREATION_WARNING × the scale, else an empty string.
  std::string check(const State& state, Real stored, ExternalId critical_id);

  /// Energy created by contact at the last check, J (≤ 0: none).
  Real created() const { return m_created; }

 private:
  Real m_scale = 0.0;     ///< running maximum of the energy scales, J
  Real m_created = 0.0;   ///< C of the last check, J
  Real m_baseline = 0.0;  ///< stored − ALLPW at the end of the step's warm-up, J
  long m_step_first_increment = 0;
  bool m_baseline_pending = true;
  bool m_warned = false;
};

}  // namespace xpl

#pragma once
/// \file Sleeping slots of ContactEngine (contact_engine.hpp; slot_sleep.cpp): a listed slot far
/// from every face it lists is not searched and holds no touch while a lower bound on its distance,
/// reduced by the motion since, keeps it beyond any penetration. An awake search of slot s records,
/// when the slot is free (no closed constraint, so no side memory and no continuing face; no
/// permanent offset, ramp or user-stiffness law; nothing penetrated, released or passed), its
/// clearance
///   c = min over its listed faces f of (L_f − R_f) − G,
/// and the motion path P then. L_f bounds from below the distance from the node to the
/// mid-surface of f (the bilinear patch of f's nodes; a solid face is its own mid-surface): the
/// patch is a convex combination of its corners, so it lies in their box and in their slab along
/// any unit vector (the normal of their diagonals), and the larger of the two distances is a
/// bound, less a relative rounding slack. Every face the search could evaluate gets it, those
/// admissible() rejects by orientation or reach too, since both tests change with the motion.
/// R_f is how near that mid-surface a node must come for admissible() to keep a penetrating
/// touch on f (gap < 0) with the rules of an updated engine: the closest point q of f's offset
/// surface (a shell face's corners moved out along its normal by their half thicknesses h_a on
/// its side; each offset point is within r_f = max h_a of the mid-surface point of the same
/// bilinear coordinates, so the node is within |p − q| + r_f of the mid-surface) lies within
/// max(h_n, depth_f) of a node h_n (the node's half thickness) in front of it over the face's
/// interior, and beside its edges a double-sided node touches the round edge, within h_n + r_f
/// of the mid-surface: R_f = max(h_n, depth_f) + r_f; a single-sided node beside a square edge
/// lies within √(l² + (l − h_n)²), l = depth_f + h_n, of q (penetration_reach_sq()), so
/// R_f = max(h_n, that) + r_f. Both sides of a double-sided shell are listed faces of their own
/// and bounded alike; the node's own side does not enter (L_f and R_f hold for either).
/// Thicknesses and face depths are fixed for the step. G = SLEEP_GUARD × min_f R_f wakes the
/// slot while it is still that far from any touch, so that it is searched (and keeps an open
/// touch's memory: master face, gap, normal, onset offset) for several increments before it can
/// touch. Motion: every tracked node (each face corner, a rigid body's included, and each slave
/// node) moves by at most the per-update largest motion m_k (BroadPhase::step_motion_sq()) in
/// an update, so between two updates by at most the path P = Σ m_k between them, and so does
/// each mid-surface point (a convex combination of corners); the distance from a node to a
/// mid-surface shrinks by at most 2 ΔP. The slot sleeps while c − 2 (P − P_s)(1 + 1e-9) > 0:
/// then no listed face is within R_f, admissible() keeps no penetrating touch, so no spring
/// acts, nothing is pinched, and a free slot releases and passes nothing: all it loses is the
/// open touch (its memory) and the warm starts. A slot with no listed face changes is assumed
/// (the lists change at broad-phase builds only, which forget every record and the path).
/// A sleeping slot is left out of the visits once its last visit made it quiet. probe(), a
/// mutable constraints() and the other full visits forget the records. In a shared pass the
/// owner records and decides with its own listed faces and the path every process has (the
/// max of the processes' step motions is exact): the one-process decision. XPL_CONTACT_SLEEP:
/// `off` never sleeps, `check` searches the sleeping slots anyway and throws if one would have
/// touched, `count` (or `check`) prints the counts to stderr when the engine goes.

#include <cstdint>
#include <vector>

#include "common/types.hpp"

namespace xpl::contact {

/// Slot searches made and left asleep, asleep ones searched by the check, updates, and the
/// sum over the updates of the largest step motion (m), since construction.
struct SleepCounts {
  long long searched = 0, asleep = 0, checked = 0, updates = 0;
  double path = 0.0;
};

/// XPL_CONTACT_SLEEP: off, on (unset), count, check (file comment).
enum class SleepMode : std::uint8_t { Off, On, Count, Check };

/// The mode XPL_CONTACT_SLEEP asks for; std::invalid_argument naming the value and the
/// accepted ones when it is set to anything else (never a silent default); unset or empty: on.
SleepMode sleep_mode_from_environment();

/// The engine's sleeping-slot state.
struct SlotSleep {
  /// Per slave slot: the clearance c its last awake search recorded (m; −inf: none), the path
  /// then (m), and whether it sleeps in the current update.
  std::vector<Real> clear, path_then;
  std::vector<char> asleep;
  std::vector<Index> awake_listed;  ///< the listed slots awake in the current update
  std::vector<Index> searched;      ///< the slots search() looks at in the current update
  Real path = 0.0;                  ///< P since the last build, m
  Real step_decision = -1.0;        ///< decided step motion for the next update, m² (< 0: none)
  SleepMode mode = SleepMode::On;
  SleepCounts counts;

  /// The mode from the environment (sleep_mode_from_environment()); `n_slave` records, none set.
  explicit SlotSleep(Index n_slave = 0);
  SlotSleep(const SlotSleep&) = default;
  SlotSleep(SlotSleep&&) = default;
  SlotSleep& operator=(const SlotSleep&) = default;
  SlotSleep& operator=(SlotSleep&&) = default;
  /// Prints the counts to stderr in the modes count and check.
  ~SlotSleep();
  /// Forgets every record and the path (builds, full visits).
  void forget();
  /// The path after an update whose largest squared step motion is `step_sq` (m²), or a build.
  void advance(bool rebuilt, Real step_sq);
  /// Whether slot s's record keeps it asleep at the current path.
  bool sleeps(Index s) const {
    return clear[s] > 0.0 && clear[s] - 2.0 * (path - path_then[s]) * (1.0 + 1e-9) > 0.0;
  }
};

}  // namespace xpl::contact

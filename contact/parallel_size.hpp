#pragma once
/// \file How large a loop of the contact pass must be to run on the team; below these sizes it
/// runs on the calling thread. With OpenMP's passive wait (xpl's default) every parallel
/// region wakes the sleeping threads and puts them to sleep again: ~100 µs on an idle 2-vCPU
/// VM, far more on a loaded one (benchmarks/RESULTS.md, "Small models on one thread" and
/// "One parallel region for the contact pass"). Every loop gated here writes only its own
/// slot or face, or takes an exact max, so the choice changes no bit of the results.

#include "common/types.hpp"

namespace xpl::contact {

/// The light per-item loops of the contact pass (the rebuild check over the tracked nodes,
/// face and node areas, preparing the springs and their forces): a few tens of ns per item,
/// so a region pays back its wake-ups only over tens of thousands of items. The block impact
/// of `xpl bench` (10 244 slots) runs them serially.
inline constexpr Index PARALLEL_MIN_SLOTS = 32768;

/// The search, by its listed candidate faces over all slots (~0.3 µs each): the crash tube's
/// (up to ~1 900) run serially, the block impact's (8 704) on the team.
inline constexpr Index PARALLEL_MIN_CANDIDATES = 4096;

}  // namespace xpl::contact

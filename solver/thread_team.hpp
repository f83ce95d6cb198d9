#pragma once
/// \file How many OpenMP threads a run uses: the user's `--threads`, or, by default, one for
/// small models (benchmarks/RESULTS.md, "Small models on one thread") and the OpenMP default
/// otherwise. Results do not depend on the choice (the element pass sums every node in
/// colour order, the nodal and contact loops in fixed chunks), only the wall time does.

#include "solver/model/model.hpp"

namespace xpl {

/// Models with fewer elements than this run on one thread unless the user asks for more:
/// below it a second thread gains less than its forks and barriers cost per increment, and
/// on a busy machine a descheduled thread makes every barrier wait. Measured crossing
/// (benchmarks/RESULTS.md, "Small models on one thread"): ~10,600 hexes on an idle 2-vCPU
/// VM, where waking a sleeping (passive) thread costs ~100 µs per barrier; ~2,000 on a
/// heavily loaded one. Below 10,000, one thread was at least as fast as two in every
/// median measured on that VM, idle and with a competing job.
inline constexpr Index SMALL_MODEL_ELEMENTS = 10000;

/// The team size of a run of `model`: `requested` when it is positive (`--threads`
/// insists), else 1 for a model of fewer than SMALL_MODEL_ELEMENTS elements and
/// `default_threads` (the OpenMP default, omp_get_max_threads()) otherwise.
int team_size(const Model& model, int requested, int default_threads);

}  // namespace xpl

#pragma once
/// \file Contact slots shared out among processes (distributed runs, docs/dev/mpi.md "Contact
/// under N ranks"): each process searches and computes the springs of the slave slots it owns
/// only, and the engine then gives every process every slot's results (contact_slot_rows.cpp)
/// through this interface, so that the assembly and every sum run over all slots in the
/// one-process order. The contact library knows nothing of how the processes talk.

#include <vector>

#include "common/types.hpp"

namespace xpl::contact {

/// How the processes of a run exchange rows of slot results.
class SlotSharing {
 public:
  virtual ~SlotSharing() = default;
  /// Every process's `mine` concatenated in process order (collective: every process calls
  /// it the same number of times, in the same order). `counts` (one per process): the number
  /// of values each sends, found (out), or given with `counts_known` (in; one collective less).
  virtual std::vector<Real> gather(const std::vector<Real>& mine, std::vector<int>& counts,
                                   bool counts_known) = 0;
};

}  // namespace xpl::contact

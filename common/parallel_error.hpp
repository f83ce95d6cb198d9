#pragma once
/// \file Exceptions inside OpenMP regions. An exception may not leave a parallel region (the
/// runtime calls std::terminate), so a region whose body can throw (std::bad_alloc, an error
/// of the element or contact code) runs each iteration through ParallelErrors::guard, which
/// keeps the exception, and rethrows it after the region:
///
///     ParallelErrors errors;
///     #pragma omp parallel for
///     for (Index i = 0; i < n; ++i) errors.guard(ParallelSite::ContactSearch, i, [&] { ... });
///     errors.rethrow_if_any();
///
/// The guard costs nothing while nothing throws (a try block and one compare with the fault
/// site of the tests), so the loops keep their speed and their results bitwise.

#include <exception>
#include <mutex>
#include <string_view>

#include "common/types.hpp"

namespace xpl {

/// The guarded OpenMP regions, named for fault injection in tests.
enum class ParallelSite : int {
  None = 0,
  ElementForces,    ///< element forces of a thread's part (elements/parallel/thread_partition.hpp)
  ElementBoundary,  ///< sums at nodes two parts share (elements/parallel/thread_partition.hpp)
  HexStiffness,     ///< C3D8R stiffness product (elements/hex/hex8r_stiffness.cpp)
  ContactSearch,    ///< closest master face per slave node (contact/contact_engine.cpp)
  ContactForces,    ///< penalty and friction forces (contact/contact_engine.cpp)
  BroadPhase,       ///< candidate faces per slave node (contact/broad_phase.cpp)
  Overclosure,      ///< initial overclosure moves and crossed edges (initial_overclosure.cpp)
  Clearance,        ///< contact clearance moves (contact/clearance_moves.cpp)
  /// Not a region: the time loop's checks at increment INDEX stop the run with a SolverError
  /// (solver/explicit_solver.cpp), on the ranks whose environment sets it.
  SolverStop,
  COUNT
};

/// The name of a site as XPL_TEST_FAULT takes it ("element-forces", "contact-search", ...).
std::string_view parallel_site_name(ParallelSite site);

/// Fault injection for tests: the environment variable XPL_TEST_FAULT=SITE:INDEX (read once,
/// at start-up) makes iteration INDEX of the guarded region SITE throw std::runtime_error
/// ("injected fault at SITE:INDEX"), so a test can show that the run ends with that message
/// and a failed status instead of std::terminate. Unset, nothing is injected.
namespace fault_injection {
/// The site of XPL_TEST_FAULT, ParallelSite::None when unset or not understood.
extern const ParallelSite SITE;
/// Throws the injected fault when `index` is the INDEX of XPL_TEST_FAULT.
void throw_at(ParallelSite site, Index index);
/// Throws a SolverError when `increment` is the INDEX of XPL_TEST_FAULT=solver-stop:INDEX.
void stop_at(long increment, Real time);
}  // namespace fault_injection

/// The first exception (lowest iteration index, so the message does not depend on the number
/// of threads) thrown in the guarded iterations of one parallel region.
class ParallelErrors {
 public:
  /// Runs body() for iteration `index` of a region at `site`; an exception it throws is kept
  /// instead of leaving the region. The other iterations still run.
  template <typename Body>
  void guard(ParallelSite site, Index index, Body&& body) noexcept {
    try {
      if (site == fault_injection::SITE) [[unlikely]]
        fault_injection::throw_at(site, index);
      body();
    } catch (...) {
      keep(index, std::current_exception());
    }
  }

  /// After the region: rethrows the kept exception, if there is one.
  void rethrow_if_any() const {
    if (m_error) std::rethrow_exception(m_error);
  }

 private:
  void keep(Index index, std::exception_ptr error) noexcept;

  std::mutex m_mutex;
  Index m_index = 0;
  std::exception_ptr m_error;
};

}  // namespace xpl

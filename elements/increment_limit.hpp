#pragma once
/// \file The stable-increment minimum of a set of elements, merged in a fixed order so that
/// the result (and the critical element reported in the .sta file) does not depend on the
/// thread count.

#include <limits>

#include "common/types.hpp"

namespace xpl::elements {

/// Smallest stable increment, the element that sets it, and the first failed element.
struct IncrementLimit {
  Real stable_dt = std::numeric_limits<Real>::infinity();  ///< s
  Index critical_element = NO_INDEX;  ///< model index with the smallest stable dt
  Index failed_element = NO_INDEX;    ///< lowest model index with a collapsed element

  /// Takes in one more candidate; ties go to the lower element index.
  void merge(Real dt, Index critical, Index failed) {
    if (dt < stable_dt || (dt == stable_dt && critical != NO_INDEX &&
                           (critical_element == NO_INDEX || critical < critical_element))) {
      stable_dt = dt;
      critical_element = critical;
    }
    if (failed != NO_INDEX && (failed_element == NO_INDEX || failed < failed_element))
      failed_element = failed;
  }
  void merge(const IncrementLimit& other) {
    merge(other.stable_dt, other.critical_element, other.failed_element);
  }
};

}  // namespace xpl::elements

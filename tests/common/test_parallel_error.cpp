#include <catch2/catch.hpp>

#include <atomic>
#include <new>
#include <stdexcept>
#include <string>

#include "common/parallel_error.hpp"

using xpl::Index;
using xpl::ParallelErrors;
using xpl::ParallelSite;

TEST_CASE("an exception in an OpenMP region is carried out of it", "[common][parallel]") {
  // Two threads, exceptions in both halves of the iteration space: the region ends, every
  // other iteration ran, and the exception of the lowest index comes out after it, whichever
  // thread threw first.
  constexpr Index N = 1000;
  std::atomic<int> ran{0};
  ParallelErrors errors;
#pragma omp parallel for schedule(static) num_threads(2)
  for (Index i = 0; i < N; ++i)
    errors.guard(ParallelSite::ContactSearch, i, [&] {
      if (i == 700) throw std::runtime_error("failed at 700");
      if (i == 3) throw std::runtime_error("failed at 3");
      ++ran;
    });
  CHECK(ran == N - 2);
  try {
    errors.rethrow_if_any();
    FAIL("no exception after the region");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()) == "failed at 3");
  }
}

TEST_CASE("std::bad_alloc keeps its type through a parallel region", "[common][parallel]") {
  ParallelErrors errors;
#pragma omp parallel for num_threads(2)
  for (Index i = 0; i < 64; ++i)
    errors.guard(ParallelSite::BroadPhase, i, [&] {
      if (i == 40) throw std::bad_alloc();
    });
  CHECK_THROWS_AS(errors.rethrow_if_any(), std::bad_alloc);
}

TEST_CASE("a region without exceptions rethrows nothing", "[common][parallel]") {
  ParallelErrors errors;
  double sum = 0.0;
#pragma omp parallel for reduction(+ : sum) num_threads(2)
  for (Index i = 0; i < 100; ++i) errors.guard(ParallelSite::ElementForces, i, [&] { sum += i; });
  CHECK_NOTHROW(errors.rethrow_if_any());
  CHECK(sum == 4950.0);
  CHECK(xpl::parallel_site_name(ParallelSite::ElementForces) == "element-forces");
  CHECK(xpl::parallel_site_name(ParallelSite::Clearance) == "clearance");
}

/* Counts OpenMP synchronisation points of a run (benchmarks/count_sync_points.sh):
 * LD_PRELOAD'ed, it wraps libgomp's entry points for parallel regions and explicit barriers
 * and loop ends that wait (GOMP_barrier, GOMP_loop_end: one call per thread of the team)
 * and prints the counts at exit. A region started with one thread (an `if` clause that is
 * false, or a team of one) forks nothing and is counted apart. GCC/libgomp only. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>

static unsigned long g_regions, g_serial_regions, g_barriers;

typedef void (*parallel_fn)(void (*)(void*), void*, unsigned, unsigned);
void GOMP_parallel(void (*fn)(void*), void* data, unsigned num_threads, unsigned flags) {
  static parallel_fn real;
  if (!real) real = (parallel_fn)dlsym(RTLD_NEXT, "GOMP_parallel");
  if (num_threads == 1)
    __atomic_add_fetch(&g_serial_regions, 1, __ATOMIC_RELAXED);
  else
    __atomic_add_fetch(&g_regions, 1, __ATOMIC_RELAXED);
  real(fn, data, num_threads, flags);
}

typedef void (*barrier_fn)(void);
void GOMP_barrier(void) {
  static barrier_fn real;
  if (!real) real = (barrier_fn)dlsym(RTLD_NEXT, "GOMP_barrier");
  __atomic_add_fetch(&g_barriers, 1, __ATOMIC_RELAXED);
  real();
}

void GOMP_loop_end(void) {
  static barrier_fn real;
  if (!real) real = (barrier_fn)dlsym(RTLD_NEXT, "GOMP_loop_end");
  __atomic_add_fetch(&g_barriers, 1, __ATOMIC_RELAXED);
  real();
}

__attribute__((destructor)) static void report(void) {
  const char* path = getenv("OMP_COUNT_FILE");
  FILE* f = path ? fopen(path, "w") : stderr;
  if (!f) return;
  fprintf(f, "parallel_regions %lu\nserial_regions %lu\nbarrier_calls_all_threads %lu\n", g_regions,
          g_serial_regions, g_barriers);
  if (path) fclose(f);
}

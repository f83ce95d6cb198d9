#!/usr/bin/env bash
# Install missing dependencies, build xpl with a preset and run its test suite, then fuzz the
# deck reader (and run the generated decks it accepts) under address+undefined sanitizers.
# Usage: scripts/run_tests.sh [preset]    (release by default)
#   XPL_FUZZ_DECKS=N  mutated decks checked in process (tests/fuzz/xpl_fuzz_check: batches of
#                     decks through the code of `xpl check`, each isolated) under address+
#                     undefined sanitizers (default 3000, 0 skips them)
#   XPL_FUZZ_PROCESS_DECKS=N  mutated decks checked by `xpl check` as a process each under the
#                     sanitizers, the whole command line (default 300, 0 skips them; about
#                     0.25 s of CPU per deck, most of it starting the process)
#   XPL_FUZZ_GENERATED_DECKS=N  generated decks of plasticity, rate laws, ties, mass scaling
#                     and contact inclusions/exclusions (tests/fuzz/generate_decks.py), each
#                     checked and, when accepted, run (`xpl run`, a few hundred increments at
#                     most) as a process under the sanitizers (default 80, 0 skips them;
#                     about 0.5 s of CPU per deck)
#                     The fuzz stage builds only xpl and xpl_fuzz_check with the sanitize preset.
#   XPL_MPI_TESTS=1|0  the MPI stage after the default tests (scripts/run_mpi_tests.sh: installs
#                     OpenMPI, METIS and the parallel HDF5, builds xpl with XPL_MPI=ON into
#                     build/mpi, runs ctest -L mpi on 1, 2 and 3 ranks); on when CI=true, off
#                     otherwise
#   XPL_WERROR=ON|OFF  compiler warnings as errors in both builds (scripts/build.sh); the
#                     build directory's setting when unset, except that CI (CI=true) turns it
#                     on for the test build (below)
# Exit code: ctest's, else the MPI stage's, else the fuzzer's (1 when it found a crash, hang or
# sanitizer report).
set -euo pipefail

preset="${1:-release}"
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

# The whole run needs about 6 GB of disk (the test build 3.2 GB with its results, the MPI
# build 1.2 GB, the sanitizer build 1.8 GB). CI hosts share their disk, and one once had less
# than that free (the tests then failed on "No space left on device"): say what there is.
free_kb=$(df -Pk . | awk 'NR == 2 { print $4 }')
echo "run_tests.sh: $((free_kb / 1024)) MB free on $(df -P . | awk 'NR == 2 { print $6 }')"
if [[ $free_kb -lt $((6 * 1024 * 1024)) ]]; then
  echo "run_tests.sh: warning: less than the ~6 GB a full run needs; tests may fail on a full disk"
fi

# In CI (CI=true) the test build treats warnings as errors, unless XPL_WERROR says otherwise.
# The build uses -march=native, and a fresh build precompiles headers (a ccache build does
# not), so the CI machine decides what GCC sees: before this was turned on the tree built
# warning-free with -Werror fresh (precompiled headers) natively on AVX-512 and at
# -march=x86-64-v3, and through ccache at x86-64-v2 and v3 (docs/dev/testing.md, which also
# names the two GCC 12 false positives the code avoids). The sanitizer build of the fuzz stage
# below keeps the build directory's setting.
if [[ ${CI:-} == true && -z ${XPL_WERROR:-} ]]; then
  XPL_WERROR=ON bash scripts/build.sh "$preset"
else
  bash scripts/build.sh "$preset"
fi

# CMakePresets.json has test presets for release and sanitize only; other presets are
# tested straight from their build directory.
case "$preset" in
  release | sanitize) ctest_target=(--preset "$preset") ;;
  *) ctest_target=(--test-dir "build/$preset") ;;
esac

set +e
ctest "${ctest_target[@]}" --output-on-failure -j2
status=$?
set -e
if [[ $status -ne 0 ]]; then exit "$status"; fi
# In CI nothing builds in the test build after this; its precompiled headers (about 120 MB a
# target, 2.4 GB in all) would only keep disk from the builds that follow.
if [[ ${CI:-} == true ]]; then find "build/$preset" -name 'cmake_pch.hxx.gch' -delete; fi

# The MPI build is a configuration of its own (build/mpi); the default build above keeps the
# serial HDF5 even once the MPI packages are installed (CMakeLists.txt names its wrapper).
mpi_tests_default=0
if [[ ${CI:-} == true ]]; then mpi_tests_default=1; fi
if [[ ${XPL_MPI_TESTS:-$mpi_tests_default} == 1 ]]; then bash scripts/run_mpi_tests.sh; fi

fuzz_decks="${XPL_FUZZ_DECKS:-3000}"
fuzz_process_decks="${XPL_FUZZ_PROCESS_DECKS:-300}"
fuzz_generated_decks="${XPL_FUZZ_GENERATED_DECKS:-80}"
if [[ $fuzz_decks -gt 0 || $fuzz_process_decks -gt 0 || $fuzz_generated_decks -gt 0 ]]; then
  [[ $preset == sanitize ]] || bash scripts/build.sh sanitize xpl xpl_fuzz_check
  fuzz_status=0
  if [[ $fuzz_decks -gt 0 ]]; then
    python3 tests/fuzz/fuzz_decks.py --in-process build/sanitize/tests/fuzz/xpl_fuzz_check \
      --count "$fuzz_decks" --seed 1 --timeout 10 --generated-fraction 0.2 \
      --keep build/sanitize/fuzz-findings || fuzz_status=1
  fi
  if [[ $fuzz_process_decks -gt 0 ]]; then
    python3 tests/fuzz/fuzz_decks.py --xpl build/sanitize/apps/xpl --count "$fuzz_process_decks" \
      --seed 2 --timeout 10 --keep build/sanitize/fuzz-findings-process || fuzz_status=1
  fi
  if [[ $fuzz_generated_decks -gt 0 ]]; then
    python3 tests/fuzz/fuzz_decks.py --xpl build/sanitize/apps/xpl --generate --run \
      --count "$fuzz_generated_decks" --seed 3 --timeout 30 \
      --keep build/sanitize/fuzz-findings-generated || fuzz_status=1
  fi
  exit "$fuzz_status"
fi

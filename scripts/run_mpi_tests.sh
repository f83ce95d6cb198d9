#!/usr/bin/env bash
# The MPI stage of the tests (issue 37, docs/dev/mpi.md): installs what is missing of OpenMPI,
# METIS and the OpenMPI build of HDF5 (scripts/install_deps.sh with XPL_WITH_MPI=1), builds
# only the program xpl with XPL_MPI=ON into build/mpi (the `mpi` preset) and runs the
# distributed runs' tests (ctest label `mpi`, tests/mpi/: decks on 1 rank and on 2 and 3 ranks
# x 1 and 2 threads compared at tolerance 0; decks with a feature not distributed yet refused).
# scripts/run_tests.sh runs it after the default tests when CI=true (or XPL_MPI_TESTS=1).
#
# Usage: scripts/run_mpi_tests.sh
# As root (CI containers) mpirun needs --allow-run-as-root, and with 3 ranks on 2 cores
# --oversubscribe; tests/mpi/mpi_bitwise.py passes both (the first only as root).
# Exit code: the build's, else ctest's.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

# The disks, for the log: a full disk ends a rank alone (docs/dev/mpi.md, "When one rank fails").
df -h . /tmp /dev/shm || true
start=$(date +%s)
XPL_WITH_MPI=1 bash scripts/build.sh mpi xpl
built=$(date +%s)
set +e
ctest --preset mpi -j2
status=$?
set -e
end=$(date +%s)
echo "run_mpi_tests: build $((built - start)) s, tests $((end - built)) s"
exit "$status"

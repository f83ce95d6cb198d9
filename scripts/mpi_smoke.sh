#!/usr/bin/env bash
# Smoke test of the MPI build (issue 37, docs/dev/mpi.md): builds xpl with XPL_MPI=ON and the
# default build, runs an example deck on 1, 2 and 3 ranks and compares every result with the
# default build's at tolerance 0 (bitwise: the distributed time loop sums in the one-rank
# order). The CI runs the MPI tests instead (scripts/run_mpi_tests.sh); as root on 2 cores it
# passes --allow-run-as-root --oversubscribe. Decks with contact, rigid bodies, ties or loads are
# refused on more than one rank (docs/dev/mpi.md).
#
# Usage: scripts/mpi_smoke.sh [DECK.inp]   (default examples/bar_impact/bar_impact.inp)
#   XPL_MPI_BUILD   MPI build directory (default build/mpi)
#   XPL_BUILD       default build directory (default build/release)
#   RANKS           rank counts (default "1 2 3")
# Needs: apt-get install -y libopenmpi-dev libmetis-dev libhdf5-openmpi-dev
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
deck="${1:-examples/bar_impact/bar_impact.inp}"
mpi_build="${XPL_MPI_BUILD:-build/mpi}"
serial_build="${XPL_BUILD:-build/release}"
ranks="${RANKS:-1 2 3}"
job="$(basename "$deck" .inp)"
out="$mpi_build/mpi_smoke/$job"

launcher=()
if command -v ccache > /dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S . -B "$mpi_build" -DCMAKE_BUILD_TYPE=Release -DXPL_MPI=ON \
  "${launcher[@]}" > /dev/null
cmake --build "$mpi_build" -j"$(nproc)" --target xpl
cmake -S . -B "$serial_build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" > /dev/null
cmake --build "$serial_build" -j"$(nproc)" --target xpl

mpirun_flags=(--oversubscribe)
if [[ $(id -u) -eq 0 ]]; then mpirun_flags+=(--allow-run-as-root); fi

rm -rf "$out"
mkdir -p "$out/serial"
"$serial_build/apps/xpl" run "$deck" -o "$out/serial" --quiet --threads 1
status=0
for n in $ranks; do
  dir="$out/np$n"
  mkdir -p "$dir"
  start=$(date +%s.%N)
  mpirun "${mpirun_flags[@]}" -np "$n" "$mpi_build/apps/xpl" run "$deck" -o "$dir" --quiet \
    --threads 1
  end=$(date +%s.%N)
  if "$mpi_build/apps/xpl" compare "$out/serial/$job.h5" "$dir/$job.h5" --frames all > "$dir/compare.txt"; then
    verdict="bitwise equal to the default build"
  else
    verdict="DIFFERS from the default build ($dir/compare.txt)"
    status=1
  fi
  printf 'np %d: %.2f s wall, %s\n' "$n" "$(awk "BEGIN { print $end - $start }")" "$verdict"
  grep -h ' partition: [0-9]* parts' "$dir/$job.msg" | sed 's/^ */  /' || true
done
exit $status

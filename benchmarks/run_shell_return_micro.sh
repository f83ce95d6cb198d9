#!/usr/bin/env bash
# The S4R plane-stress return alone (benchmarks/shell_return_micro.cpp) built against
# elements/material/shell_plasticity.cpp (elements/shell_plasticity.cpp before issue 36) of two
# revisions, run alternately REPS times per case; prints
# the user CPU seconds (best / median), which a loaded machine disturbs far less than wall
# time. Usage: bash benchmarks/run_shell_return_micro.sh OLD_REV [NEW_REV (working tree)]
# Environment: REPS (7), N (4000 increments), MARCH (native).
set -euo pipefail
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
old_rev=$1
new_rev=${2:-}
reps=${REPS:-7}
n=${N:-4000}
work=build/bench/shell_return
mkdir -p "$work"
# The return and, since issue 36, the state's constructor in a file of its own.
show() { # REV OUT
  git show "$1:elements/material/shell_plasticity.cpp" >"$2" 2>/dev/null ||
    git show "$1:elements/shell_plasticity.cpp" >"$2"
  git show "$1:elements/material/shell_plastic_state.cpp" >>"$2" 2>/dev/null || true
}
show "$old_rev" "$work/old.cpp"
if [[ -n $new_rev ]]; then show "$new_rev" "$work/new.cpp"
else cat elements/material/shell_plasticity.cpp elements/material/shell_plastic_state.cpp >"$work/new.cpp"; fi
# Each revision with its own headers of elements/material (the state's members change).
rm -rf "$work/old_inc" "$work/new_inc"
mkdir -p "$work/old_inc" "$work/new_inc/elements"
git archive "$old_rev" elements/material 2>/dev/null | tar -x -C "$work/old_inc" || true
if [[ -n $new_rev ]]; then git archive "$new_rev" elements/material | tar -x -C "$work/new_inc"
else cp -r elements/material "$work/new_inc/elements/"; fi
for v in old new; do
  g++ -O3 -march="${MARCH:-native}" -std=c++20 -w -DNDEBUG -I"$work/${v}_inc" -I. \
    -isystem /usr/include/eigen3 \
    benchmarks/shell_return_micro.cpp "$work/$v.cpp" elements/material/plasticity.cpp -o "$work/$v"
done
for case in "0 0" "1 50"; do
  for v in old new; do "$work/$v" $case "$n"; done
  rows=()
  for rep in $(seq 1 "$reps"); do
    order="old new"; ((rep % 2)) || order="new old"
    for v in $order; do
      t=$({ /usr/bin/time -f "%U" "$work/$v" $case "$n" >/dev/null; } 2>&1)
      rows+=("$v $t")
    done
  done
  printf '%s\n' "${rows[@]}" | /usr/bin/python3 -c "
import statistics, sys
t = {}
for line in sys.stdin:
    v, s = line.split(); t.setdefault(v, []).append(float(s))
print('case $case:', '; '.join(f'{v} best {min(x):.2f} s median {statistics.median(x):.2f} s'
                              for v, x in sorted(t.items(), reverse=True)),
      f\"; new/old median {statistics.median(t['new']) / statistics.median(t['old']):.3f}\")"
done

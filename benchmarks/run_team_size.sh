#!/usr/bin/env bash
# Where a second thread starts to pay (issue 17, item 1: the small-model rule of
# solver/thread_team.hpp): C3D8R blocks of N³ elements, 1 and 2 threads alternated, ROUNDS
# rounds; prints the best and median element-cycle rate of each and 2T/1T.
#   bash benchmarks/run_team_size.sh BUILD/apps/xpl [ROUNDS] [SIZES]
set -euo pipefail
xpl=$(realpath "$1")
rounds=${2:-5}
sizes=${3:-"6 8 10 12 14 17 22"}
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

rate() {  # deck threads -> M element-cycles/s
  OMP_WAIT_POLICY=PASSIVE "$xpl" run "$1" -o "$work/out" --threads "$2" >"$work/log" 2>&1
  sed -n 's/^xpl: element cycles per second: \([0-9.e+-]*\).*/\1/p' "$work/log" |
    awk '{printf "%.3f", $1 / 1e6}'
}
stats() {
  printf '%s\n' "$@" | sort -gr |
    awk '{v[NR]=$1} END {printf "%.2f / %.2f", v[1], (NR % 2 ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2)}'
}

echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "| elements | 1T M/s best / median | 2T M/s best / median | 2T/1T median |"
echo "|---:|---:|---:|---:|"
for n in $sizes; do
  /usr/bin/python3 "$repo/benchmarks/make_block.py" -n "$n" --increments 400 --out "$work/b.inp" >/dev/null
  one=() two=()
  for ((r = 0; r < rounds; ++r)); do
    one+=("$(rate "$work/b.inp" 1)")
    two+=("$(rate "$work/b.inp" 2)")
  done
  m1=$(printf '%s\n' "${one[@]}" | sort -g | awk '{v[NR]=$1} END {print (NR % 2 ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2)}')
  m2=$(printf '%s\n' "${two[@]}" | sort -g | awk '{v[NR]=$1} END {print (NR % 2 ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2)}')
  printf '| %d | %s | %s | %.2f |\n' $((n * n * n)) "$(stats "${one[@]}")" "$(stats "${two[@]}")" \
    "$(echo "$m2 / $m1" | bc -l)"
done
echo "load at end $(cut -d' ' -f1-3 /proc/loadavg)"

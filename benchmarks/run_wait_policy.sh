#!/usr/bin/env bash
# Two threads against one with a competing CPU-bound job (issue 15, item 10): xpl's default
# passive OpenMP wait policy against libgomp's own default (spin 300,000 times at a barrier,
# GOMP_SPINCOUNT=300000). Runs alternate within each round; prints best and median wall
# time of each configuration, and the speed of 2 threads relative to 1.
#   bash benchmarks/run_wait_policy.sh BUILD/apps/xpl [ROUNDS]
set -euo pipefail
xpl=$1
rounds=${2:-3}
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
work=$(mktemp -d)
trap 'kill "$competitor" 2>/dev/null || true; rm -rf "$work"' EXIT

python3 "$repo/benchmarks/make_block.py" -n 46 --increments 100 --out "$work/block.inp" >/dev/null
decks=("$repo/examples/contact/shell_block/shell_block.inp" "$work/block.inp")

yes >/dev/null &
competitor=$!

# One timed run: prints its wall time in seconds.
timed() {
  local deck=$1 threads=$2 out=$3
  shift 3
  local t0 t1
  t0=$(date +%s.%N)
  env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT "$@" "$xpl" run "$deck" -o "$out" --threads "$threads" \
    --quiet
  t1=$(date +%s.%N)
  echo "$t1 - $t0" | bc -l
}

stats() {  # best and median of the arguments
  printf '%s\n' "$@" | sort -g | awk '{v[NR]=$1} END {printf "best %.3f median %.3f", v[1], v[int((NR+1)/2)]}'
}

echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; load $(cut -d' ' -f1-3 /proc/loadavg)"
for deck in "${decks[@]}"; do
  one=() two=() spin=()
  for ((r = 0; r < rounds; ++r)); do
    one+=("$(timed "$deck" 1 "$work/out1")")
    two+=("$(timed "$deck" 2 "$work/out2")")
    spin+=("$(timed "$deck" 2 "$work/out3" GOMP_SPINCOUNT=300000)")
  done
  b1=$(printf '%s\n' "${one[@]}" | sort -g | head -1)
  m1=$(printf '%s\n' "${one[@]}" | sort -g | sed -n "$(((rounds + 1) / 2))p")
  b2=$(printf '%s\n' "${two[@]}" | sort -g | head -1)
  m2=$(printf '%s\n' "${two[@]}" | sort -g | sed -n "$(((rounds + 1) / 2))p")
  bs=$(printf '%s\n' "${spin[@]}" | sort -g | head -1)
  ms=$(printf '%s\n' "${spin[@]}" | sort -g | sed -n "$(((rounds + 1) / 2))p")
  echo "$(basename "$deck" .inp): 1 thread $(stats "${one[@]}") s;" \
    "2 threads passive $(stats "${two[@]}") s;" \
    "2 threads spinning $(stats "${spin[@]}") s"
  printf '  speed vs 1 thread: passive best %.2f median %.2f; spinning best %.2f median %.2f\n' \
    "$(echo "$b1 / $b2" | bc -l)" "$(echo "$m1 / $m2" | bc -l)" \
    "$(echo "$b1 / $bs" | bc -l)" "$(echo "$m1 / $ms" | bc -l)"
  echo "  all runs: 1T ${one[*]} | 2T ${two[*]} | 2T spin ${spin[*]}"
done

#!/usr/bin/env bash
# C3D8R element-loop benchmark: an elastic block of N^3 elements, no output, run with 1
# and 2 threads, best of REPS runs each. Writes benchmarks/results/hex_block.csv (appends)
# and hex_block.png and prints a markdown table for benchmarks/RESULTS.md.
# Environment overrides: N (elements per edge, 46), INCREMENTS (300), REPS (3),
# THREADS ("1 2"), ELEMENT_TYPE (C3D8R or C3D8), SKIP_BUILD=1 (use the existing build), XPL (binary,
# build/release/apps/xpl), RESULTS_DIR (benchmarks/results).
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

n="${N:-46}"
increments="${INCREMENTS:-300}"
reps="${REPS:-3}"
threads_list="${THREADS:-1 2}"
python=/usr/bin/python3 # Debian's python, which has matplotlib (a pyenv python may not)

if [[ "${SKIP_BUILD:-0}" != 1 ]]; then
  bash scripts/build.sh release
fi
xpl="${XPL:-build/release/apps/xpl}"
results_dir="${RESULTS_DIR:-benchmarks/results}"

bench_dir=build/bench
log_dir="$bench_dir/logs"
mkdir -p "$log_dir"
rm -f "$log_dir"/run_t*_r*.log "$log_dir"/run_t*_r*.summary.json
deck="$bench_dir/block_$n.inp"
"$python" benchmarks/make_block.py -n "$n" --increments "$increments" --out "$deck" \
  --element-type "${ELEMENT_TYPE:-C3D8R}"

logs=()
for threads in $threads_list; do
  for rep in $(seq 1 "$reps"); do
    log="$log_dir/run_t${threads}_r${rep}.log"
    echo "run_hex_benchmark: $threads thread(s), repetition $rep of $reps"
    if ! OMP_NUM_THREADS="$threads" "$xpl" run "$deck" -o "$bench_dir/out" \
      --threads "$threads" >"$log" 2>&1; then
      echo "run_hex_benchmark: xpl failed, see $log:" >&2
      tail -n 20 "$log" >&2
      exit 1
    fi
    grep '^xpl: element cycles per second' "$log" || true
    # The run's JOB.summary.json is what hex_benchmark.py reads (no stdout parsing).
    cp "$bench_dir/out/block_$n.summary.json" "${log%.log}.summary.json"
    logs+=("${log%.log}.summary.json")
  done
done

"$python" benchmarks/hex_benchmark.py "${logs[@]}" \
  --csv "$results_dir/hex_block.csv" --png "$results_dir/hex_block.png"
